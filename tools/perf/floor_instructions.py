#!/usr/bin/python3
"""The engine against the hand-written floor at equal accuracy, in instructions.

bench_floor_accuracy times both by CPU time, which on a shared machine scatters by more
than the margins it is asked about (Frêne long at 1e-4 c: 1.84x, then 0.88x in two runs).
This script counts instructions instead (valgrind's callgrind, which does not move from
run to run): for each force law and rtol 1e-5 ... 1e-11 it runs one integration of 4 crank
cycles from eps = 0 of the engine (`lub::run_scene`, the study's measurements on) and of
the floor (`floor_model::integrate`), each in its own process
(`bench_floor_accuracy --point LAW RTOL engine|floor`), counts the instructions inside
that call (`--toggle-collect`), and measures the error as bench_floor_accuracy does: the
largest distance, in clearances, between the eccentricity vectors at the cycle ends and
the floor's at rtol 1e-12. The cost at 1e-4 c and 1e-6 c comes from log-log
interpolation between the bracketing tolerances.

    /usr/bin/python3 tools/perf/floor_instructions.py [--build build] [--laws a,b] [--formulation joint] [-j 2]
                                                 [--floor-kernels sundials|small]

Prints a markdown table: per cycle at equal accuracy, per step at rtol 1e-8, and the
instructions per step of each side.
"""
import argparse
import concurrent.futures
import math
import os
import re
import subprocess
import sys
import tempfile

LAWS = ["frene_long", "frene_short", "gumbel_long", "pinkus_sternlicht_continuous", "pinkus_sternlicht"]
RTOLS = [1e-5, 1e-6, 1e-7, 1e-8, 1e-9, 1e-10, 1e-11]
TARGETS = [1e-4, 1e-6]
CYCLES = 4
CLEARANCE_M = 0.0100 - 0.0095  # the floor's (and slider_crank.json's) clearance
TOGGLE = {"engine": "lub::run_scene*", "floor": "floor_model::integrate*"}


def parse_point(text):
    steps, ends = None, []
    for line in text.splitlines():
        f = line.split()
        if f and f[0] == "steps":
            steps = float(f[1])
        elif f and f[0] == "end":
            ends.append((float(f[1]), float(f[2])))
    return steps, ends


def point_command(bench, law, rtol, side, formulation, floor_kernels="sundials"):
    return [bench, "--point", law, repr(rtol), side, "--formulation", formulation, "--floor-kernels", floor_kernels]


def run_point(bench, law, rtol, side, formulation, callgrind, floor_kernels="sundials"):
    cmd = point_command(bench, law, rtol, side, formulation, floor_kernels)
    if not callgrind:
        out = subprocess.run(cmd, check=True, capture_output=True, text=True).stdout
        return parse_point(out) + (None,)
    with tempfile.TemporaryDirectory() as tmp:
        cg = os.path.join(tmp, "cg.out")
        out = subprocess.run(["valgrind", "--tool=callgrind", "--callgrind-out-file=" + cg,
                              "--toggle-collect=" + TOGGLE[side]] + cmd,
                             check=True, capture_output=True, text=True).stdout
        ir = None
        with open(cg) as f:
            for line in f:
                m = re.match(r"(summary|totals):\s+(\d+)", line)
                if m:
                    ir = int(m.group(2))
        return parse_point(out) + (ir,)


def distance_c(a, b):
    return max(math.hypot(x[0] - y[0], x[1] - y[1]) for x, y in zip(a, b)) / CLEARANCE_M


def cost_at(points, err):
    """points: [(error, cost)] in rtol order; log-log interpolation between a bracketing pair."""
    for (ea, ca), (eb, cb) in zip(points, points[1:]):
        lo, hi = min(ea, eb), max(ea, eb)
        if lo <= 0 or not (lo <= err <= hi):
            continue
        w = (math.log(err) - math.log(ea)) / (math.log(eb) - math.log(ea))
        return math.exp(math.log(ca) + w * (math.log(cb) - math.log(ca)))
    return math.nan


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--build", default="build")
    ap.add_argument("--laws", default=",".join(LAWS))
    ap.add_argument("--formulation", default="joint")
    ap.add_argument("-j", type=int, default=2, help="callgrind processes at once")
    ap.add_argument("--floor-kernels", choices=["sundials", "small"], default="sundials",
                    help="the floor's CVODE kernels: SUNDIALS' own (the floor as defined), or the engine's "
                         "small-size ones (the same numbers), to see the engine's own overhead with like kernels")
    args = ap.parse_args()
    bench = os.path.join(args.build, "tests", "bench", "bench_floor_accuracy")
    if not os.access(bench, os.X_OK):
        sys.exit(f"{bench}: not built (cmake --build {args.build} --target bench_floor_accuracy)")
    laws = args.laws.split(",")
    for law in laws:
        if law not in LAWS:
            print(f"--laws: '{law}' is not one of {', '.join(LAWS)}", file=sys.stderr)
            sys.exit(2)
    jobs = {}
    with concurrent.futures.ThreadPoolExecutor(max_workers=args.j) as pool:
        for law in laws:
            jobs[(law, "ref")] = pool.submit(run_point, bench, law, 1e-12, "floor", args.formulation, False)
            for rtol in RTOLS:
                for side in ("engine", "floor"):
                    jobs[(law, rtol, side)] = pool.submit(run_point, bench, law, rtol, side, args.formulation, True,
                                                          args.floor_kernels)
    print(f"Instructions per cycle, {CYCLES} cycles from eps = 0; engine: {args.formulation} (`lub::run_scene`), "
          f"floor: `floor_model::integrate` with {args.floor_kernels} kernels; error: max |e - e_ref| / c at the "
          "cycle ends, e_ref the floor at rtol 1e-12\n")
    print("| law | rtol | engine Ir/cycle | engine error [c] | engine steps/cycle | floor Ir/cycle | floor error [c] | floor steps/cycle |")
    print("|---|---|---|---|---|---|---|---|")
    summary = []
    for law in laws:
        _, ref, _ = jobs[(law, "ref")].result()
        pts = {"engine": [], "floor": []}
        at8 = {}
        for rtol in RTOLS:
            row = [law, f"{rtol:.0e}"]
            for side in ("engine", "floor"):
                steps, ends, ir = jobs[(law, rtol, side)].result()
                err = distance_c(ends, ref)
                pts[side].append((err, ir / CYCLES))
                row += [f"{ir / CYCLES / 1e6:.3f} M", f"{err:.2e}", f"{steps:.0f}"]
                if rtol == 1e-8:
                    at8[side] = (ir / CYCLES, steps)
            print("| " + " | ".join(row) + " |")
        ratios = [cost_at(pts["engine"], t) / cost_at(pts["floor"], t) for t in TARGETS]
        per_step = {s: at8[s][0] / at8[s][1] for s in at8}
        summary.append((law, ratios, per_step["engine"] / per_step["floor"], per_step["engine"], per_step["floor"],
                        at8["engine"][0] / at8["floor"][0]))
    print("\nEngine over floor: per cycle at equal accuracy (1e-4 c, 1e-6 c), per cycle and per step at rtol 1e-8\n")
    print("| law | at 1e-4 c | at 1e-6 c | per cycle, rtol 1e-8 | per step, rtol 1e-8 | engine Ir/step | floor Ir/step |")
    print("|---|---|---|---|---|---|---|")
    for law, r, step_ratio, es, fs, cyc8 in summary:
        print(f"| {law} | {r[0]:.2f}x | {r[1]:.2f}x | {cyc8:.2f}x | {step_ratio:.2f}x | {es / 1e3:.1f}k | {fs / 1e3:.1f}k |")


if __name__ == "__main__":
    main()
