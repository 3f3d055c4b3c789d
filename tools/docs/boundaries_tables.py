#!/usr/bin/python3
"""Prints the boundary tables of docs/validation/sensitivities.md as Markdown, from a study
whose /boundaries table `python3 -m lubjoint.boundaries STUDY.h5` has written:

    mpirun -np 2 build/sweep/lubsweep configs/grids/full_factorial.json -o ff.h5
    PYTHONPATH=build/python /usr/bin/python3 -m lubjoint.boundaries ff.h5
    PYTHONPATH=build/python /usr/bin/python3 tools/docs/boundaries_tables.py ff.h5

One table per kind of search (the safe-film crossings; the edges, where a safe orbit followed
towards a neighbour without one turns unstable or is lost; the stability crossings between
two orbits), each row a lattice line: its force law, the other axes' values, the located
value with its error, the runs and periods it took; then what they cost against the study's
own periods.
"""
import argparse
import sys

import lubjoint  # PYTHONPATH=build/python
from lubjoint import boundaries

SHOWN = {"clearance_m": (1e3, "mm"), "viscosity_Pa_s": (1.0, "Pa s"), "speed_rpm": (1.0, "rpm")}


def value_text(axis, value):
    factor, unit = SHOWN.get(axis, (1.0, ""))
    return f"{value * factor:.6g} {unit}".strip()


def line_text(row):
    """The line's fixed axes, in the grid's order of SHOWN."""
    return ", ".join(value_text(a, row[a]) for a in SHOWN if a != row["axis"] and a in row and row[a] == row[a])


def table(rows, kind_column):
    head = "| force law | line | boundary | error | " + ("kind | " if kind_column else "") + "runs | periods |"
    out = [head, "|" + "---|" * (head.count("|") - 1)]
    for _, r in rows.iterrows():
        factor, _ = SHOWN.get(r["axis"], (1.0, ""))
        error = f"{r['error'] * factor:.2g}" + boundaries.not_converged(r)
        kind = f"{r['kind']} | " if kind_column else ""
        out.append(f"| {r.get('force_law', '')} | {line_text(r)} | {value_text(r['axis'], r['value'])} | {error} | "
                   f"{kind}{int(r['runs'])} | {int(r['periods'])} |")
    return "\n".join(out)


CROSSINGS = ("fold", "period_doubling", "neimark_sacker")


def parts(frame):
    """(title, rows, whether the kind is shown) of each table: the safe-film crossings, the
    edges (files without the ``edge`` column: kind orbit_end), the stability crossings."""
    edge = boundaries.edge_ends(frame)
    safe = frame["kind"] == "safe_film"
    return (("safe_film", frame[safe], False), ("edge", frame[edge], True),
            ("stability", frame[~edge & frame["kind"].isin(CROSSINGS)], True))


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("study", help="a study file with a /boundaries table")
    args = ap.parse_args(argv)
    frame = boundaries.read(args.study)
    if frame is None:
        print(f"{args.study}: no /boundaries table: run python3 -m lubjoint.boundaries {args.study} first",
              file=sys.stderr)
        return 2
    frame = frame.sort_values(["kind", "force_law", "axis", "value"], kind="stable")
    for title, rows, kinds in parts(frame):
        print(f"### {title} ({len(rows)})\n")
        print(table(rows, kinds) if len(rows) else "none")
        print()
    cases = lubjoint.study.cases(args.study)
    steady = float(cases["periods_integrated"].clip(lower=0).sum())
    sens = float(cases["sensitivity_periods"].clip(lower=0).sum()) if "sensitivity_periods" in cases else 0.0
    print("| cost | periods | runs | share of the steady stages' periods |")
    print("|---|---|---|---|")
    print(f"| steady stages | {steady:.0f} | | |")
    print(f"| sensitivities | {sens:.0f} | | {100 * sens / steady:.1f} % |")
    for title, rows, _ in parts(frame):
        p = float(rows["periods"].sum())
        print(f"| {title} boundaries | {p:.0f} | {int(rows['runs'].sum())} | {100 * p / steady:.1f} % |")
    total = sens + float(frame["periods"].sum())
    print(f"| sensitivities and boundaries | {total:.0f} | {int(frame['runs'].sum())} | {100 * total / steady:.1f} % |")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
