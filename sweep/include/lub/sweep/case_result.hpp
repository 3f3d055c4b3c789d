// Running one case, and its outcome as a value that travels between ranks.
#pragma once

#include <string>
#include <vector>

#include "lub/run/run.hpp"
#include "lub/run/run_io.hpp"
#include "lub/sweep/case_outcome.hpp"
#include "lub/sweep/grid.hpp"

namespace lub::sweep {

/// The result columns of /cases: lub::metric_fields() then lub::solver_fields(), so that
/// lubsim and lubsweep report the same quantities under the same names and units.
std::vector<ResultField> result_fields();

/// One case's outcome. `values` follow result_fields(); NaN where a case that could not
/// run has no value.
struct Task;

/// The /cases columns of the sensitivities to `parameters`: for each parameter, each steady
/// metric's derivative d_<metric>_per_<axis> [metric unit / axis unit], then its error bar
/// (`_error`), in that order: CaseResult::sensitivities' layout.
std::vector<ResultField> sensitivity_fields(const std::vector<AxisParameter>& parameters);

struct CaseResult {
  int case_id = -1;
  int rank = 0;                 ///< MPI rank that computed it
  Named<CaseStatus> status = CaseStatus::error;  ///< its run's RunStatus, or invalid_scene, error
  std::string message;
  /// The steady cycle (periodic, periodic_unstable, drifting, not_converged); the status
  /// for a case that is not ok.
  Named<CaseClass> classification = CaseClass::error;
  std::vector<double> values;
  std::string revision;         ///< build revision of the program that computed it
  /// The scene's channels ("t" first); empty if none. A periodic or periodic_unstable case
  /// found by shooting: the periodic orbit's, over the metric cycles; otherwise the run's
  /// last cycles.
  Series series;
  /// The periodic orbit found, packed (pack_seed, lub/run/run.hpp): what a neighbouring
  /// case continues from. Empty: none.
  std::vector<double> orbit_seed;
  int continued_from = -1;      ///< the case whose orbit it started from (-1: none)
  /// A located orbit's sensitivities to the task's parameters, sensitivity_fields' layout
  /// (NaN where not computed); empty where none were asked.
  std::vector<double> sensitivities;
  long long sensitivity_periods = 0;  ///< the periods they integrated

  bool ok() const { return status == CaseStatus::ok; }
};

/// Runs a case's parsed scene. Never throws: a scene the core refuses at run time
/// ("invalid_scene") or any exception ("error") becomes the status.
CaseResult run_case(int case_id, const Scene& scene, int rank);
/// The same from the case's scene as canonical JSON (a task from the coordinator), parsed
/// here once.
CaseResult run_case(int case_id, const std::string& scene_json, int rank);
/// A task: its case, continued from the task's orbit along the path from its from_scene
/// when it has one.
CaseResult run_task(const Task& task, int rank);

/// Byte encoding for messages between processes (MessagePack, nlohmann-json's binary format).
std::string encode(const CaseResult& r);
/// Throws std::runtime_error, saying what is wrong, on a truncated or malformed buffer.
CaseResult decode(const std::string& bytes);

}  // namespace lub::sweep
