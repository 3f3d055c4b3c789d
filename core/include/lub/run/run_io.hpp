// What a run reports, by name and unit: the one list behind the run file's /metrics and
// /solver, lubsim's summary and the sweep's /cases columns, so they cannot disagree.
#pragma once

#include <string>
#include <vector>

#include "lub/io/h5.hpp"
#include "lub/run/run.hpp"

namespace lub {

/// One scalar a run reports.
struct ResultField {
  const char* name;  ///< column / attribute name, unit in the name where it has one
  const char* unit;  ///< SI unit, "1" for dimensionless, "" for counts and flags
  bool integer;      ///< counts and flags
  double (*get)(const RunResult&);
};

/// Steady-cycle metrics, in column order.
const std::vector<ResultField>& metric_fields();
/// Solver statistics and cost, in column order.
const std::vector<ResultField>& solver_fields();

/// Program version and the build's revision.
std::string program_version();
std::string build_revision();

/// Writes a run file (lubsim's run.h5): root attributes `scene` (the effective scene
/// JSON), `program`, `version`, `revision`, `status`, `message`; /series/<channel>
/// with `units`; /metrics and /solver attributes; /cycles, one row per crank cycle.
/// Writes to PATH.partial and renames, so PATH is never left half-written.
void write_run_file(const std::string& path, const std::string& scene_text, const std::string& program,
                    const RunResult& result);

}  // namespace lub
