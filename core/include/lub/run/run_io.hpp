// What a run reports, by name and unit: the one list behind the run file's /metrics and
// /solver, lubsim's summary and the sweep's /cases columns, so they cannot disagree.
#pragma once

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "lub/io/h5.hpp"
#include "lub/run/run.hpp"

namespace lub {

/// The missing-value convention of every file and of the Python module (docs/reference/run-file.md,
/// missing values): a float value that is unknown is NaN (a float variable or column declares
/// `_FillValue` = NaN, CF 2.5.1); an integer one (a count or flag) keeps this sentinel,
/// declared by the attribute `missing_value` = -1. ResultField::get, CycleField::get return
/// NaN for an unknown value, integer fields included: writers of integers store the sentinel.
inline constexpr std::int64_t kMissingInteger = -1;

/// One scalar a run reports.
struct ResultField {
  std::string name;  ///< column / attribute name, unit in the name where it has one
  std::string unit;  ///< SI unit, CF style ("m", "m s-2", "rad"); "1" for ratios, counts, flags
  bool integer;      ///< counts and flags
  std::function<double(const RunResult&)> get;
  std::string long_name;  ///< a description (netCDF `long_name`)
  /// A steady-cycle metric or its error bar: a study reports it only for a case whose
  /// classification is periodic or periodic_unstable (NaN otherwise: a transient's value
  /// is not a result).
  bool steady_metric = false;
};

/// Steady-cycle metrics, in column order: the six of steady_metrics(), periodicity, their
/// error bars, the classification's numbers, the Floquet multipliers, the safe film.
const std::vector<ResultField>& metric_fields();
/// The energy balance (outputs.energy_balance), reported where a run has one
/// (has_energy_balance): driver work, film dissipation, energy change, residual [J].
const std::vector<ResultField>& energy_fields();
bool has_energy_balance(const RunResult& r);
/// Solver statistics and cost, in column order.
const std::vector<ResultField>& solver_fields();

/// One column of the run file's /cycles (after `cycle`, the cycle number): the one list
/// behind the file and the Python module's `cycle_*` variables.
struct CycleField {
  std::string name;       ///< column name, unit in the name where it has one
  std::string unit;       ///< CF-style SI unit
  std::string long_name;  ///< a description (netCDF `long_name`)
  std::function<double(const CycleMetrics&)> get;
};
const std::vector<CycleField>& cycle_fields();

/// Version of the run file's layout, in the root attribute `format`.
inline constexpr const char* kRunFormat = "lubsim-run-3";  // 3: NaN for an unknown periodicity (2: -1)

/// Program version and the build's revision.
std::string program_version();
std::string build_revision();

/// CF-style unit of a scene key's suffix or a channel unit: "m/s^2" → "m s-2",
/// "m/s" → "m s-1", "rad/s" → "rad s-1", "kg m^2" → "kg m2", "" → "1"; others unchanged.
std::string cf_units(const std::string& unit);

/// `long_name` of each channel of a series ("t": "time"), from the scene's
/// outputs.channels ("eps of joint rod_slider: eccentricity ratio |e|/c").
std::vector<std::string> channel_long_names(const std::string& scene_json,
                                            const std::vector<std::string>& names);

/// Writes a series into `group`: one 1-D dataset per channel with `units` and
/// `long_name`, `t` (first) the dimension scale of every other channel, so xarray
/// (h5netcdf) indexes the group by time; group attribute `channels`.
void write_series(h5::Group& group, const Series& series, const std::vector<std::string>& long_names);

/// A derivative's unit, the metric's over the parameter's, UDUNITS syntax: "m/(Pa s)",
/// "N/rpm", the metric's own for a dimensionless parameter.
std::string derivative_unit(const std::string& metric_unit, const std::string& parameter_unit);

/// Writes a run file (lubsim's run.h5): root attributes `scene` (the effective scene
/// JSON), `program`, `format`, `version`, `revision`, `status`, `message`;
/// /series/<channel> on the dimension scale /series/t (write_series); /metrics and
/// /solver attributes; /cycles, a table (one column per quantity, dimension `cycle`).
/// Writes to PATH.partial and renames, so PATH is never left half-written. Root attribute
/// `warnings`: the scene's plausibility warnings (Scene::warnings; an empty list if none).
/// /sensitivities/<k>, one group per parameter asked for (steady_sensitivities): attributes
/// `parameter` (its JSON Pointer), `parameter_unit`, `value`, `status` (`ok`, `failed`),
/// `message`, `periods_integrated`; one 1-element dataset per steady metric, its derivative
/// with `units` derivative_unit(metric, parameter), and `<metric>_error`.
void write_run_file(const std::string& path, const std::string& scene_text, const std::string& program,
                    const RunResult& result, const std::vector<std::string>& warnings = {},
                    const std::vector<Sensitivity>& sensitivities = {});

}  // namespace lub
