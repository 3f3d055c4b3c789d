#!/usr/bin/env python3
"""Checks that every theory page (docs/theory/*.md) explains rather than records: each under
2 500 words, counted as `wc -w` counts them. Measurements belong in docs/validation/.

    /usr/bin/python3 tools/docs/theory_length.py [--limit N] [DOCS_DIR]
"""
import argparse
import pathlib
import sys

LIMIT = 2500


def words(path: pathlib.Path) -> int:
    return len(path.read_text(encoding="utf-8").split())


def main(argv=None):
    ap = argparse.ArgumentParser(description="every theory page under a word limit")
    ap.add_argument("docs", nargs="?", default=str(pathlib.Path(__file__).resolve().parents[2] / "docs"))
    ap.add_argument("--limit", type=int, default=LIMIT)
    args = ap.parse_args(argv)
    pages = sorted(pathlib.Path(args.docs, "theory").glob("*.md"))
    if not pages:
        print(f"theory_length: no pages in {args.docs}/theory", file=sys.stderr)
        return 2
    long = [(p, words(p)) for p in pages if words(p) >= args.limit]
    for p, n in long:
        print(f"theory_length: {p.name}: {n} words, the limit is {args.limit}: move measurements to "
              "docs/validation/ or split the page", file=sys.stderr)
    if not long:
        print(f"theory_length: {len(pages)} theory pages, each under {args.limit} words", file=sys.stderr)
    return 1 if long else 0


if __name__ == "__main__":
    sys.exit(main())
