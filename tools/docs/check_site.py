#!/usr/bin/env python3
"""Checks a built documentation site (tools/docs/site.sh runs it after Sphinx): it works offline.

- no page loads a script from the network (an http(s) or protocol-relative src);
- every script a page loads is in the site;
- MathJax (docs/conf.py copies it from Debian's libjs-mathjax) is there with its TeX fonts,
  and the pages with formulas load it: at least the force-law page, whose formulas must be
  typeset;
- the tutorial's page shows the notebook's outputs, its figures included (unless
  --no-notebook: the site was built without running it).

    /usr/bin/python3 tools/docs/check_site.py [--no-notebook] BUILD/docs/html
"""
import pathlib
import re
import sys
from urllib.parse import unquote, urlsplit

SCRIPT = re.compile(r"<script\b[^>]*\bsrc=\"([^\"]+)\"", re.IGNORECASE)
MATHJAX_FILES = ["MathJax.js", "config/TeX-AMS_CHTML.js", "jax/input/TeX/config.js",
                 "jax/output/CommonHTML/jax.js", "fonts/HTML-CSS/TeX/woff/MathJax_Main-Regular.woff",
                 "fonts/HTML-CSS/TeX/woff/MathJax_Math-Italic.woff"]
MUST_TYPESET = ["theory/force-laws.html", "theory/steady-cycles.html"]
NOTEBOOK_PAGES = {"tutorials/first-study.html": 2}   # page: figures it must show


def check(site: pathlib.Path, notebooks: bool = True) -> list:
    problems = []
    pages = sorted(site.rglob("*.html"))
    if not pages:
        return [f"{site}: no HTML pages"]
    with_math = set()
    for page in pages:
        text = page.read_text(encoding="utf-8", errors="replace")
        rel = page.relative_to(site).as_posix()
        for src in SCRIPT.findall(text):
            parts = urlsplit(src)
            if parts.scheme or src.startswith("//"):
                problems.append(f"{rel}: loads a script from the network: {src}")
                continue
            target = (page.parent / unquote(parts.path)).resolve()
            if not target.is_file():
                problems.append(f"{rel}: loads {src}, which is not in the site")
            if parts.path.endswith("mathjax/MathJax.js"):
                with_math.add(rel)
    mathjax = site / "_static" / "mathjax"
    for name in MATHJAX_FILES:
        if not (mathjax / name).is_file():
            problems.append(f"_static/mathjax/{name} missing (docs/conf.py copies MathJax)")
    for rel in MUST_TYPESET:
        if rel not in with_math:
            problems.append(f"{rel}: does not load the site's MathJax")
        elif 'class="math' not in (site / rel).read_text(encoding="utf-8"):
            problems.append(f"{rel}: has no formula for MathJax to typeset")
    for rel, figures in NOTEBOOK_PAGES.items():
        page = site / rel
        if not page.is_file():
            problems.append(f"{rel}: missing (the tutorial notebook's page)")
        elif notebooks:
            shown = page.read_text(encoding="utf-8").count('src="data:image/png;base64,')
            if shown < figures:
                problems.append(f"{rel}: shows {shown} of the notebook's {figures} figures "
                                "(tools/docs/site.sh runs it first)")
    return problems


def main(argv):
    args = argv[1:]
    notebooks = "--no-notebook" not in args
    args = [a for a in args if a != "--no-notebook"]
    if len(args) != 1:
        print(__doc__.strip().splitlines()[-1].strip(), file=sys.stderr)
        return 2
    site = pathlib.Path(args[0])
    problems = check(site, notebooks)
    for p in problems:
        print(f"check_site: {p}", file=sys.stderr)
    if problems:
        return 1
    print(f"check_site: {site}: no network scripts, MathJax bundled and loaded by the pages with formulas"
          + (", the notebook's outputs shown" if notebooks else ""), file=sys.stderr)
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
