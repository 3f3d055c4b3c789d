#!/usr/bin/python3
"""Compare two outputs: one tool, one subcommand per question (each in tools/compare/).

    /usr/bin/python3 tools/compare.py identical A.h5 B.h5 [--ignore NAME ...]
    PYTHONPATH=build/python /usr/bin/python3 tools/compare.py study STUDY.h5 BASELINE.h5 [--rtol R] [--tol ...]
    PYTHONPATH=build/python /usr/bin/python3 tools/compare.py nightly STUDY.h5 [--baseline CSV] [--report DIR] [--accept]
    PYTHONPATH=build/python /usr/bin/python3 tools/compare.py tolerance DEFAULT.h5 TIGHT.h5 [--markdown]
    /usr/bin/python3 tools/compare.py builds OLD_BUILD NEW_BUILD [--full-factorial]

identical  two run or study files bit for bit, wall times, the revision and rank aside
           (a refactor changed no number)
study      a study against a baseline study, cases matched by hash, every metric within a
           relative tolerance (a regression check between any two studies of one grid)
nightly    the paper grid's study against the committed CSV baseline, cases keyed by their
           axis values, each metric with its own tolerance; a report with figures; --accept
           writes the baseline (tools/check/nightly.sh)
tolerance  a study against the same grid integrated more tightly: labels kept, metrics
           within their error bars (not a regression check: an accuracy check)
builds     two build directories run on the same scenes and the paper grid, every file
           compared with `identical` and every printed report with diff

`compare.py SUBCOMMAND --help` gives each one's options. Exit status: 0 no difference (or a
report only: tolerance), 1 a difference or regression, 2 bad input.
"""
import argparse
import os
import subprocess
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(HERE, "compare"))

SUBCOMMANDS = {  # name: the module in tools/compare/, its one-line help
    "identical": ("identical", "two HDF5 files identical bit for bit, wall times aside"),
    "study": ("study", "a study against a baseline study (cases by hash, metrics within --rtol)"),
    "nightly": ("nightly", "the paper grid's study against tests/baselines/paper.csv; --accept writes it"),
    "tolerance": ("tolerance", "a study against the same grid integrated more tightly"),
}


def run_builds(args):
    """`builds`: tools/compare/builds.sh, which runs both builds and compares with `identical`."""
    cmd = ["bash", os.path.join(HERE, "compare", "builds.sh"), args.old, args.new]
    return subprocess.call(cmd + (["--full-factorial"] if args.full_factorial else []))


def main(argv=None):
    argv = sys.argv[1:] if argv is None else argv
    ap = argparse.ArgumentParser(prog="compare.py", description=__doc__,
                                 formatter_class=argparse.RawDescriptionHelpFormatter)
    sub = ap.add_subparsers(dest="command", required=True, metavar="SUBCOMMAND")
    for name, (module, summary) in SUBCOMMANDS.items():
        # Only the subcommand asked for is imported: each needs its own dependencies alone
        # (identical reads HDF5 directly; the others read studies with lubjoint.study, from
        # PYTHONPATH=build/python).
        if not argv or argv[0] != name:
            sub.add_parser(name, help=summary)
            continue
        m = __import__(module)
        p = sub.add_parser(name, help=summary, description=m.__doc__,
                           formatter_class=argparse.RawDescriptionHelpFormatter)
        m.add_arguments(p)
        p.set_defaults(run=m.run)
    b = sub.add_parser("builds", help="two builds on the same cases: every file and report the same",
                       description="two builds on the same cases: every file and report the same")
    b.add_argument("old", help="the build directory of the old revision")
    b.add_argument("new", help="the build directory of the new revision")
    b.add_argument("--full-factorial", action="store_true",
                   help="also configs/grids/full_factorial.json (~4 min a build)")
    b.set_defaults(run=run_builds)
    args = ap.parse_args(argv)
    try:
        return args.run(args)
    except SystemExit as e:  # a message: bad input, exit 2 (1 means a difference)
        if isinstance(e.code, str):
            print(e.code, file=sys.stderr)
            return 2
        raise


if __name__ == "__main__":
    sys.exit(main())
