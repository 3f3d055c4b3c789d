#!/usr/bin/env python3
"""Real signals to a real `mpirun -np 2 lubsweep` (ctest: mpi_sweep_signals, label mpi, and
mpi_sweep_signals_slow, label slow). Usage:

  sweep_signal_test.py MPIEXEC LUBSWEEP STUDY_COMPARE WORKDIR COUNT [SEED]

COUNT signals of each kind (SIGINT, SIGTERM, SIGKILL) that land on a running sweep, in a
seeded random order, each sent to mpirun at a seeded random moment of a run of
tests/mpi/signal_grid.json (a run that ends first is followed by another with the same
signal); each run is the resume of the one before, started at once with the same command.
Asserted:
- every case whose `ok` line was printed before the signal is in the file (SIGINT/SIGTERM:
  read once mpirun has ended; SIGKILL: the resume says it holds it, and never runs it again);
- no resume is refused: the ranks of a killed mpirun end within 0.9 s (they lived ~1.03 s,
  holding the file's lock, before the parent-death signal);
- a run that is signalled ends non-zero (mpirun, signalled, exits 1: Open MPI's choice), and
  its line `interrupted: k of N cases saved in FILE`, when mpirun forwarded it, says k rows;
- every chain of runs ends with a complete study equal to an uninterrupted run's
  (study_compare: every number but wall times and ranks).
Then lubsweep without mpirun: SIGINT and SIGTERM after its first `ok` line end it with 130
and 143 and the line, naming the rows the file holds.
"""
import os
import random
import re
import signal
import subprocess
import sys
import threading
import time

MPIEXEC, LUBSWEEP, COMPARE, WORK = sys.argv[1:5]
COUNT = int(sys.argv[5])
SEED = int(sys.argv[6]) if len(sys.argv) > 6 else 29
GRID = os.path.join(os.path.dirname(os.path.abspath(__file__)), "signal_grid.json")
ENV = dict(os.environ, OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1",
           OMPI_MCA_rmaps_base_oversubscribe="1")
OK = re.compile(r"lubsweep: \[ *\d+/\d+\] (case_\d+) ok ")
SAVED = re.compile(r"lubsweep: interrupted: (\d+) of (\d+) cases saved in (\S+); run the same command to resume")
HOLDS = re.compile(r"holds (\d+) of them")
ORPHAN_BOUND_S = 0.9
TOTAL = 18  # cases in signal_grid.json

failures = []


def fail(msg):
    failures.append(msg)
    print("FAIL: " + msg, flush=True)


class Run:
    """One lubsweep command; its stderr lines with the time each was read."""

    def __init__(self, out, mpi=True):
        cmd = [LUBSWEEP, GRID, "-o", out, "--no-summary"]
        if mpi:
            cmd = [MPIEXEC, "-np", "2"] + cmd
        self.t0 = time.monotonic()
        self.proc = subprocess.Popen(cmd, env=ENV, stderr=subprocess.PIPE, stdout=subprocess.DEVNULL, text=True)
        self.lines = []  # (time read, line)
        self.reader = threading.Thread(target=self._read, daemon=True)
        self.reader.start()

    def _read(self):
        for line in self.proc.stderr:
            self.lines.append((time.monotonic(), line.rstrip("\n")))

    def finish(self, timeout=120):
        try:
            rc = self.proc.wait(timeout)
        except subprocess.TimeoutExpired:
            self.proc.kill()
            rc = self.proc.wait()
            fail("a run did not end within %d s" % timeout)
        self.reader.join(10)
        return rc

    def ok_before(self, t):
        return [m.group(1) for (when, line) in self.lines if when < t for m in [OK.search(line)] if m]

    def text(self):
        return "\n".join(line for _, line in self.lines)


def children(pid):
    out = []
    try:
        for task in os.listdir("/proc/%d/task" % pid):
            try:
                with open("/proc/%d/task/%s/children" % (pid, task)) as f:
                    out += [int(x) for x in f.read().split()]
            except OSError:
                pass
    except OSError:
        pass
    return out


def alive(pid):
    try:
        with open("/proc/%d/stat" % pid) as f:
            return f.read().rsplit(")", 1)[1].split()[0] != "Z"
    except OSError:
        return False


def lifetime(pids, t_ref):
    """Waits (up to 30 s) until `pids` have ended; the seconds from t_ref to the last end."""
    life = {}
    while len(life) < len(pids) and time.monotonic() - t_ref < 30:
        for k in pids:
            if k not in life and not alive(k):
                life[k] = time.monotonic() - t_ref
        time.sleep(0.002)
    return max([life.get(k, 99.0) for k in pids] + [0.0])


def names_in(path):
    r = subprocess.run([COMPARE, "--names", path], stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    if r.returncode != 0:
        fail("cannot read the names in %s: %s" % (path, r.stderr.strip()))
        return set()
    return set(r.stdout.split())


def remove(*paths):
    for p in paths:
        if os.path.exists(p):
            os.remove(p)


def signal_chains(rng, reference_s):
    """The COUNT x 3 signals, each to the resume of the run before; returns stats."""
    kinds = [signal.SIGINT, signal.SIGTERM, signal.SIGKILL] * COUNT
    rng.shuffle(kinds)
    chain, out = 0, "chain0.h5"
    remove(out, out + ".lock")
    seen = set()  # cases printed ok in this chain so far
    stats = {"orphan_max_s": 0.0, "after_mpirun_max_s": 0.0, "lines": 0, "interrupted": 0, "chains": 0,
             "landed": 0}
    i, attempts = 0, 0
    while kinds and attempts < 9 * COUNT + 10:
        if len(seen) == TOTAL:  # every case done: the same command completes the file; a new chain
            run = Run(out)
            if run.finish() != 0:
                fail("a resume with every case done failed:\n" + run.text())
            check_complete(out, "chain %d" % chain)
            chain += 1
            stats["chains"] += 1
            out = "chain%d.h5" % chain
            remove(out, out + ".lock")
            seen = set()
        sig = kinds[0]
        attempts += 1
        # A moment while the run still has work: its start-up, then the cases left.
        delay = rng.uniform(0.0, 0.5 + reference_s * (TOTAL - len(seen)) / TOTAL)
        i += 1
        run = Run(out)
        time.sleep(delay)
        kids = children(run.proc.pid)
        t_sig = time.monotonic()
        finished_first = run.proc.poll() is not None
        if not finished_first:
            run.proc.send_signal(sig)
        rc = run.finish()
        text = run.text()
        before = run.ok_before(t_sig)
        tag = "run %d (%s at %.2f s)" % (i, signal.Signals(sig).name, delay)
        if "in use by another sweep" in text:
            fail(tag + ": the run was refused:\n" + text)
        again = seen.intersection(run.ok_before(float("inf")))
        if again:
            fail(tag + ": cases printed ok in an earlier run of this chain ran again: %s" % sorted(again))
        holds = HOLDS.search(text)
        if holds and int(holds.group(1)) < len(seen):
            fail(tag + ": the resume holds %s cases, %d were printed ok before" % (holds.group(1), len(seen)))
        seen.update(run.ok_before(float("inf")))
        if sig == signal.SIGKILL and kids:
            # The ranks end with mpirun; the next resume starts at once (next turn).
            worst = lifetime(kids, t_sig)
            stats["orphan_max_s"] = max(stats["orphan_max_s"], worst)
            if worst > ORPHAN_BOUND_S:
                fail(tag + ": the ranks of the killed mpirun lived %.2f s after it" % worst)
        elif not finished_first:
            # mpirun may return before rank 0 has ended (it still holds the file): read after.
            t_end = time.monotonic()
            stats["after_mpirun_max_s"] = max(stats["after_mpirun_max_s"], lifetime(kids, t_end))
            # A signal in the start-up, before the first case and the file: nothing to hold.
            names = names_in(out) if before or os.path.exists(out) else set()
            missing = set(before) - names
            if missing:
                fail(tag + ": printed ok before the signal but not in the file: %s\n%s" % (sorted(missing), text))
            m = SAVED.search(text)
            if m:
                stats["interrupted"] += 1
                if int(m.group(1)) != len(names) or m.group(3) != out:
                    fail(tag + ": '%s' but the file holds %d rows" % (m.group(0), len(names)))
        stats["lines"] += 1
        if not finished_first and rc != 0:  # it landed: the next kind; else this one again
            kinds.pop(0)
            stats["landed"] += 1
        print("%s: exit %d, %d ok before the signal, %d in the chain" % (tag, rc, len(before), len(seen)),
              flush=True)
        if rc == 0:  # the run completed before or despite the signal: a new chain
            check_complete(out, tag)
            chain += 1
            stats["chains"] += 1
            out = "chain%d.h5" % chain
            remove(out, out + ".lock")
            seen = set()
        elif finished_first:
            fail(tag + ": a run ended with %d before any signal:\n%s" % (rc, text))
    if kinds:
        fail("%d signals did not land on a running sweep in %d runs" % (len(kinds), attempts))
    # The last chain: the same command, not signalled, completes it.
    run = Run(out)
    if run.finish() != 0:
        fail("the last resume failed:\n" + run.text())
    check_complete(out, "the last chain")
    stats["chains"] += 1
    return stats


def check_complete(out, tag):
    r = subprocess.run([COMPARE, "reference.h5", out], stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    if r.returncode != 0:
        fail(tag + ": the study differs from the uninterrupted run's:\n" + r.stderr)


def without_mpirun():
    """lubsweep alone: SIGINT -> 130, SIGTERM -> 143, each with the line."""
    for sig, code in ((signal.SIGINT, 130), (signal.SIGTERM, 143)):
        out = "alone_%d.h5" % sig
        remove(out, out + ".lock")
        run = Run(out, mpi=False)
        while run.proc.poll() is None and not run.ok_before(float("inf")):
            time.sleep(0.01)
        run.proc.send_signal(sig)
        rc = run.finish()
        m = SAVED.search(run.text())
        if rc != code or not m:
            fail("lubsweep alone, %s: exit %d, expected %d with the line:\n%s"
                 % (signal.Signals(sig).name, rc, code, run.text()))
            continue
        rows = names_in(out)
        if int(m.group(1)) != len(rows) or not set(run.ok_before(float("inf"))) <= rows:
            fail("lubsweep alone: '%s' but the file holds %s" % (m.group(0), sorted(rows)))
        if os.path.exists(out + ".lock"):
            fail("lubsweep alone: the interrupted sweep left its lock file")


def main():
    os.makedirs(WORK, exist_ok=True)
    os.chdir(WORK)
    remove("reference.h5")
    t = time.monotonic()
    ref = Run("reference.h5")
    if ref.finish() != 0:
        print(ref.text())
        sys.exit("FAIL: the uninterrupted run failed")
    reference_s = time.monotonic() - t
    rng = random.Random(SEED)
    stats = signal_chains(rng, reference_s)
    without_mpirun()
    print("%d runs, %d signals landed on a running sweep, %d chains completed, %d interrupt lines forwarded "
          "by mpirun; ranks of a killed mpirun lived at most %.3f s; after SIGINT/SIGTERM, ranks outlived "
          "mpirun by at most %.3f s" % (stats["lines"], stats["landed"], stats["chains"], stats["interrupted"],
                                         stats["orphan_max_s"], stats["after_mpirun_max_s"]))
    if failures:
        sys.exit("FAIL: %d problems" % len(failures))
    print("sweep_signal_test: ok")


if __name__ == "__main__":
    main()
