#!/usr/bin/python3
"""Discrete-event model of lubsweep's scheduling, fed with measurements (issue 16).

Predicts the wall time and the parallel efficiency of a sweep on P ranks from
  - the cases' own costs: wall_time_s of every case of a study file computed at -np 1
    (in case-id order, the order the coordinator hands them out);
  - the sweep's costs per case, measured by `mpirun -np 2 build/tests/bench/bench_sweep_overhead`
    (a JSON line): the coordinator's service time per result (receive, decode, record,
    answer), the writer's time per row, and the round trip of a message;
  - the fixed costs of one run (start-up, the final rewrite of the study file), and the time
    a worker spends on a case outside its own wall_time_s (parsing the task, encoding the
    result), both read off the measured -np 1 run: T1 = fixed + sum(case + worker overhead).

The model (what lubsweep does, sweep/src/scheduler.cpp): rank 0 is the coordinator (one
server, first come first served, `service` per result) and computes cases itself on a
thread that shares its core with the coordinator (each service delays its case); ranks
1..P-1 hold up to `prefetch` cases while at least 2 cases per worker are queued, one
otherwise; a message takes half a round trip each way. With more ranks than one machine's
cores it assumes one rank per core and the same per-case costs.

    PYTHONPATH=build/python /usr/bin/python3 tools/perf/scaling_model.py STUDY_NP1.h5 --overhead bench.json \
        --measured 2=WALL_NP2 --wall1 WALL_NP1 [--ranks 1 2 16 64 256 1024] [--replicate K]

Prints a table (ranks, predicted wall, efficiency, coordinator utilisation, what limits it);
--measured P=WALL compares the prediction with a measured wall.
"""
import argparse
import heapq
import json
import sys

import numpy as np


def simulate(costs, ranks, service_s, latency_s, worker_overhead_s, prefetch=2, fixed_s=0.0, local=True):
    """Wall time of one sweep of `costs` (seconds, in hand-out order) on `ranks` ranks.

    Returns (wall, coordinator busy time, time the last case ended)."""
    costs = list(costs)
    n = len(costs)
    workers = ranks - 1
    next_case = 0
    coord_free = 0.0
    coord_busy = 0.0
    events = []  # (time, seq, kind, worker)
    seq = 0

    def push(t, kind, w):
        nonlocal seq
        heapq.heappush(events, (t, seq, kind, w))
        seq += 1

    held = [0] * (workers + 1)          # cases held by each remote worker (running + queued)
    queue_at = [[] for _ in range(workers + 1)]  # arrival times of their queued cases
    running = [False] * (workers + 1)
    local_busy_until = 0.0
    last_end = 0.0

    def depth():
        return prefetch if (n - next_case) >= 2 * max(workers, 1) else 1

    def hand_out(t, w):
        """Coordinator at time t tops worker w up; returns nothing (events pushed)."""
        nonlocal next_case
        while next_case < n and (held[w] < 1 or held[w] < depth()):
            c = costs[next_case]
            next_case += 1
            held[w] += 1
            push(t + latency_s, "task", (w, c))

    # start: every worker says ready (arrives at latency), the local worker starts at 0
    for w in range(1, workers + 1):
        push(latency_s, "result", (w, None))
    if local:
        if next_case < n:
            c = costs[next_case]
            next_case += 1
            push(c + worker_overhead_s, "local_done", c)
    local_delay = 0.0  # coordinator time spent on rank 0's core during the local case

    while events:
        t, _, kind, payload = heapq.heappop(events)
        if kind == "task":
            w, c = payload
            queue_at[w].append(c)
            if not running[w]:
                running[w] = True
                c0 = queue_at[w].pop(0)
                push(t + c0 + worker_overhead_s, "done", w)
        elif kind == "done":
            w = payload
            last_end = max(last_end, t)
            push(t + latency_s, "result", (w, "r"))
            if queue_at[w]:
                c0 = queue_at[w].pop(0)
                push(t + c0 + worker_overhead_s, "done", w)
            else:
                running[w] = False
        elif kind == "result":
            w, r = payload
            start = max(t, coord_free)
            coord_free = start + service_s
            coord_busy += service_s
            if local:
                local_delay += service_s
            if r is not None:
                held[w] -= 1
            hand_out(coord_free, w)
            if r is not None:
                last_end = max(last_end, coord_free)
        elif kind == "local_done":
            # the coordinator's work during this case ran on the same core: it ends later
            if local_delay > 0:
                d = local_delay
                local_delay = 0.0
                push(t + d, "local_done", payload)
                continue
            # the next case is given at once, then the result recorded (on the same core)
            start = max(t, coord_free)
            coord_free = start + service_s
            coord_busy += service_s
            local_delay += service_s
            if next_case < n:
                c = costs[next_case]
                next_case += 1
                push(t + c + worker_overhead_s, "local_done", c)
            last_end = max(last_end, coord_free)
    return last_end + fixed_s, coord_busy, last_end


def read_costs(path):
    """wall_time_s of every case of a study file, in case-id order (the hand-out order).
    Read with lubjoint.study, the one reader of study files (PYTHONPATH=build/python)."""
    from lubjoint import study as study_reader
    study_reader.check_or_exit(path)
    cases = study_reader.cases(path).sort_index()  # index: the case id
    return np.asarray(cases["wall_time_s"], dtype=float)


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("study", help="a study file computed at -np 1 (its wall_time_s column)")
    ap.add_argument("--overhead", required=True, help="bench_sweep_overhead's JSON line (a file)")
    ap.add_argument("--wall1", type=float, required=True, help="measured wall of the -np 1 run [s]")
    ap.add_argument("--fixed", type=float, default=None,
                    help="fixed cost of a run [s] (start-up and final rewrite); default: 0.3 s of "
                         "start-up and the bench's final rewrite per case")
    ap.add_argument("--measured", action="append", default=[], help="P=WALL: a measured wall at P ranks")
    ap.add_argument("--check", action="append", default=[],
                    help="P=STUDY:WALL: a run at P ranks, predicted from its own case times (the machine's "
                         "speed that day: cases run slower when every core computes) against its wall")
    ap.add_argument("--ranks", type=int, nargs="+", default=[1, 2, 16, 64, 256, 1024])
    ap.add_argument("--replicate", type=int, default=1, help="the grid K times over (a larger grid of the same cases)")
    ap.add_argument("--prefetch", type=int, default=2)
    ap.add_argument("--json", help="write the table here as JSON")
    a = ap.parse_args(argv)

    costs = read_costs(a.study)
    with open(a.overhead) as fh:
        ov = json.loads(fh.read().strip().splitlines()[-1])
    service = ov["service_us"] * 1e-6
    latency = max(ov["round_trip_us"] - ov["service_us"], 0.0) * 1e-6 / 2
    n1 = len(costs)
    # Worker overhead outside wall_time_s and the fixed cost, from the -np 1 run:
    # wall1 = fixed + sum(costs) + n (overhead + service) at one rank (its coordinator's
    # service delays its own worker).
    finalize_per_case = ov.get("finalize_s", 0.0) / ov["cases"]
    fixed = a.fixed if a.fixed is not None else 0.3 + n1 * finalize_per_case
    worker_overhead = max((a.wall1 - fixed - costs.sum()) / n1 - service, 0.0)
    costs = np.tile(costs, a.replicate)
    n = len(costs)
    fixed_n = fixed if a.replicate == 1 else fixed + (a.replicate - 1) * n1 * finalize_per_case

    t1, _, _ = simulate(costs, 1, service, latency, worker_overhead, a.prefetch, fixed_n)
    measured = {int(k): float(v) for k, v in (m.split("=") for m in a.measured)}
    rows = []
    print(f"# {n} cases ({n1} measured x {a.replicate}), case time {costs.sum():.1f} s, longest {costs.max()*1e3:.1f} ms, "
          f"mean {costs.mean()*1e3:.2f} ms")
    print(f"# service {service*1e6:.1f} us/result, one-way latency {latency*1e6:.1f} us, worker overhead "
          f"{worker_overhead*1e6:.0f} us/case, fixed {fixed_n:.2f} s, prefetch {a.prefetch}")
    print(f"{'ranks':>6} {'wall [s]':>10} {'efficiency':>10} {'coord. busy':>11} {'measured':>9}  limit")
    for p in a.ranks:
        wall, busy, end = simulate(costs, p, service, latency, worker_overhead, a.prefetch, fixed_n)
        eff = t1 / (p * wall)
        util = busy / end if end > 0 else 0.0
        per_rank = costs.sum() / p
        if util > 0.8:
            limit = "rank 0's service (messages + writer)"
        elif n < 2 * p:
            limit = "too few cases per rank"
        elif costs.max() > 0.5 * per_rank:
            limit = "the longest case"
        elif fixed_n > 0.2 * wall:
            limit = "fixed start-up and final rewrite"
        else:
            limit = "-"
        m = measured.get(p)
        ms = f"{m:9.2f}" if m else f"{'':>9}"
        print(f"{p:>6} {wall:>10.2f} {eff:>10.3f} {util:>11.2f} {ms}  {limit}")
        rows.append({"ranks": p, "wall_s": wall, "efficiency": eff, "coordinator_utilisation": util,
                     "measured_wall_s": m, "limit": limit})
    for chk in a.check:
        p, rest = chk.split("=", 1)
        path, wall = rest.rsplit(":", 1)
        c = read_costs(path)
        pred, _, _ = simulate(c, int(p), service, latency, worker_overhead, a.prefetch, fixed)
        print(f"# check: {p} ranks, {path}: its case time {c.sum():.1f} s; predicted wall {pred:.2f} s, "
              f"measured {float(wall):.2f} s ({(pred / float(wall) - 1) * 100:+.1f} %)")
    if a.json:
        with open(a.json, "w") as fh:
            json.dump(rows, fh, indent=1)
    return 0


if __name__ == "__main__":
    sys.exit(main())
