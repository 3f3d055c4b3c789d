// Dynamic scheduling of a sweep's cases, over any transport (transport.hpp).
//
// The coordinator hands out cases to whichever worker asks (a worker asks again by
// returning a result; a remote worker holds its next case ahead while the queue is long,
// Schedule::prefetch), computes cases itself on a worker thread of its own while
// its calling thread serves the others and records results, and stops handing out work
// after the first failure when the grid says on_failure = abort. Every case is computed
// from its own scene, so the results do not depend on how many workers there are or on
// which one ran a case. A continued case starts from its fixed parent's orbit, handed out
// only once that is in (Schedule::parents): the same start whatever the worker count.
#pragma once

#include <deque>
#include <functional>
#include <map>

#include "lub/sweep/case_result.hpp"
#include "lub/sweep/grid.hpp"
#include "lub/sweep/transport.hpp"

namespace lub::sweep {

/// The ids of the grid's cases that `done` (the results a study file already holds) does
/// not have, in case-id order: what a resumed sweep still runs.
std::deque<int> cases_to_run(const Grid& grid, const std::map<int, CaseResult>& done);

struct Schedule {
  FailurePolicy on_failure = FailurePolicy::continue_on_failure;
  /// Runs a case on the coordinator's own worker thread; empty: the coordinator computes
  /// nothing itself (then the transport must have workers).
  std::function<CaseResult(const Task&)> local;
  /// Called on the calling thread for every result, in the order they arrive, after the
  /// worker that returned it has been given its next case.
  std::function<void(const CaseResult&)> record;
  /// Called once, before `record`, for the result that stops a sweep with on_failure = abort.
  std::function<void(const CaseResult&)> on_abort;
  /// Called on the calling thread at every turn of the loop, so at least every ~1 ms while
  /// it waits for results, whatever runs: the coordinator writes the results it holds when
  /// they are due (StudyWriter::flush_if_due) and acts on an interrupt there.
  std::function<void()> tick;
  /// Cases a remote worker holds at once while the queue is long (its running one and the
  /// next): 1 hands out one at a time. Always 1 with on_failure = abort.
  int prefetch = 2;
  /// Each case's parent (continuation_parents; empty: none): a case is handed out once
  /// its parent's result is in, with the orbit of its nearest ancestor that found one.
  std::vector<int> parents;
  /// The orbits (packed seeds, possibly empty) of the cases the study file already holds.
  std::map<int, std::vector<double>> finished;
};

/// Runs the cases `queue` names (ids into grid.cases) on the transport's workers and the
/// local one; returns once every worker has been told to stop and nothing is running:
/// true if the sweep stopped early (on_failure = abort). Throws TransportError if a
/// worker's message cannot be read.
bool schedule(const Grid& grid, std::deque<int> queue, CoordinatorTransport& transport, const Schedule& s);

/// A worker: announces itself, then runs each task it is given and returns the result,
/// until told to stop.
void serve(WorkerTransport& transport, const std::function<CaseResult(const Task&)>& run);

}  // namespace lub::sweep
