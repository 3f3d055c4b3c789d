#include "lub/run/run_io.hpp"

#include <cmath>
#include <cstdio>
#include <map>
#include <stdexcept>
#include <utility>

#include <nlohmann/json.hpp>

#include "lub/common/constants.hpp"
#include "lub/run/orbit.hpp"

#ifndef LUB_VERSION
#define LUB_VERSION "unknown"
#endif
#ifndef LUB_GIT_REVISION
#define LUB_GIT_REVISION "unknown"
#endif

namespace lub {

namespace {

/// A value whose negative stands for "unknown" in the run's structs (periodicity of the
/// first cycle, cycles_to_steady of a run that never settled): NaN in every output.
double known(double v) { return v < 0 ? kNaN : v; }

// The crank period, from the last cycle the run measured (NaN: none).
double cycle_period(const RunResult& r) {
  return r.cycles.empty() ? kNaN : r.cycles.back().t_end_s - r.cycles.back().t_start_s;
}

// The k-th Floquet multiplier's modulus or angle (NaN when there is none).
double multiplier(const RunResult& r, size_t k, bool angle) {
  if (k >= r.steady.multipliers.size()) return kNaN;
  return angle ? std::arg(r.steady.multipliers[k]) : std::abs(r.steady.multipliers[k]);
}

// Whether the film is below the safe film, as a result: 1, 0, or NaN (unknown). An orbit's
// steady film decides; a film that collapsed is below it; a film that drifts down is below
// it once its drift law crosses the safe film, or when it is already there. A transient's
// last film is no result: any other case is unknown.
double below_safe_film(const RunResult& r) {
  if (r.status == RunStatus::film_collapse) return 1.0;
  if (r.status != RunStatus::ok) return kNaN;
  switch (r.steady.kind) {
    case SteadyClass::periodic: return r.metrics.below_safe_film ? 1.0 : 0.0;
    // The journal leaves an unstable orbit: its film is the orbit's, not the bearing's.
    case SteadyClass::periodic_unstable: return kNaN;
    case SteadyClass::drifting: {
      const bool falling = r.steady.min_film_drift_m_per_cycle < 0.0;
      return std::isfinite(r.steady.safe_film_cycle) || (falling && r.metrics.below_safe_film) ? 1.0 : kNaN;
    }
    case SteadyClass::not_converged: return kNaN;
  }
  return kNaN;
}
}  // namespace

const std::vector<ResultField>& metric_fields() {
  static const std::vector<ResultField> f = [] {
    std::vector<ResultField> fields;
    for (const SteadyMetric& sm : steady_metrics())
      fields.push_back({sm.name, sm.unit, false, [v = sm.value](const RunResult& r) { return r.metrics.*v; },
                        sm.long_name, true});
    fields.push_back({"periodicity", "1", false, [](const RunResult& r) { return known(r.metrics.periodicity); },
                      "largest cycle-to-cycle journal orbit distance over the metric cycles / clearance (NaN: unknown)"});
    // Error bars (set_errors, error_bars.cpp): NaN without simulation.error_bars.
    for (const SteadyMetric& sm : steady_metrics())
      fields.push_back({std::string(sm.name) + "_error", sm.unit, false,
                        [e = sm.error](const RunResult& r) { return r.metrics.*e; },
                        std::string("error bar of ") + sm.name + sm.error_note, true});
    std::vector<ResultField> rest = {
        {"steady", "1", true, [](const RunResult& r) { return r.metrics.steady ? 1.0 : 0.0; },
         "1 if the classification is periodic"},
        {"cycles_to_steady", "1", true, [](const RunResult& r) { return known(r.metrics.cycles_to_steady); },
         "periods integrated until the steady cycle was known (missing: never)"},
        {"cycles_run", "1", true, [](const RunResult& r) { return double(r.metrics.cycles_run); },
         "transient crank cycles run"},
        {"contraction_rate", "1", false, [](const RunResult& r) { return r.steady.contraction_rate; },
         "rho: cycle-to-cycle orbit distances shrink by this per cycle (transient, least squares; NaN: unknown)"},
        {"remaining_distance", "1", false, [](const RunResult& r) { return r.steady.remaining_distance; },
         "the transient's distance still to go to its steady cycle, in clearances: delta rho / (1 - rho), or the period map's |(I - M)^-1 (P(z) - z)| where it confirmed or refused the transient's stop"},
        {"orbit_residual", "1", false, [](const RunResult& r) { return r.steady.orbit_residual; },
         "shooting: max |P(z) - z| over the states, each in its own unit (lengths in clearances)"},
        {"orbit_error", "1", false, [](const RunResult& r) { return r.steady.orbit_error; },
         "shooting: how far the orbit moves from rtol to rtol/100, max over the states each in its own unit (lengths in clearances)"},
        {"newton_iterations", "1", true, [](const RunResult& r) { return double(r.steady.newton_iterations); },
         "Newton iterations of shooting"},
        {"transient_cycles", "1", true, [](const RunResult& r) { return double(r.steady.transient_cycles); },
         "transient cycles integrated (before shooting)"},
        {"periods_integrated", "1", true, [](const RunResult& r) { return double(r.steady.periods_integrated); },
         "crank periods integrated in all: transient, shooting's maps and differences, measurement, error bars"},
        {"min_film_drift_m_per_cycle", "m", false, [](const RunResult& r) { return r.steady.min_film_drift_m_per_cycle; },
         "change of the per-cycle minimum film thickness per crank cycle over the transient's last 10 cycles"},
        {"min_film_drift_m_per_cycle_error", "m", false,
         [](const RunResult& r) { return r.steady.min_film_drift_error_m_per_cycle; },
         "where the slow flow gave the drift: how much of it may be its period map's own error a cycle, the metric film's eccentricity one period on at the flow's rtol and at rtol/100, apart, times the clearance (NaN: not measured)"},
        {"last_cycle_min_film_m", "m", false, [](const RunResult& r) { return r.steady.last_cycle_min_film_m; },
         "the last transient cycle's minimum film thickness (a transient value, not a steady metric)"},
        {"last_cycle_asperity_load_ratio", "1", false,
         [](const RunResult& r) { return r.steady.last_cycle_asperity_load_ratio; },
         "the last transient cycle's peak asperity load over its peak joint force (a transient value; 0 without mixed lubrication)"},
        {"slow_flow_cycles", "1", false, [](const RunResult& r) { return r.steady.slow_flow_cycles; },
         "cycles of the slow flow followed by projective steps after the transient, where shooting from the transient found no orbit (0: not followed)"},
        {"drift_exponent", "1", false, [](const RunResult& r) { return r.steady.drift_exponent; },
         "where the slow flow drifts: p of the film's law dh/dN = -a h^p fitted along the flow (NaN: no law)"},
        {"drift_exponent_error", "1", false, [](const RunResult& r) { return r.steady.drift_exponent_error; },
         "error bar of drift_exponent: twice the fit's standard error"},
        {"safe_film_cycle", "1", false, [](const RunResult& r) { return r.steady.safe_film_cycle; },
         "the crank cycle, from the run's start, at which the film crosses safe_film_thickness_m by the drift law (NaN: no law, not falling, already below, or beyond the law's reach)"},
        {"safe_film_cycle_error", "1", false, [](const RunResult& r) { return r.steady.safe_film_cycle_error; },
         "error bar of safe_film_cycle: twice the standard deviation of the law's fit, the drift's error and the slow flow's cycle count"},
        {"multiplier_1_modulus", "1", false, [](const RunResult& r) { return multiplier(r, 0, false); },
         "largest Floquet multiplier's modulus (NaN: not computed)"},
        {"multiplier_1_angle_rad", "rad", false, [](const RunResult& r) { return multiplier(r, 0, true); },
         "largest Floquet multiplier's angle"},
        {"multiplier_2_modulus", "1", false, [](const RunResult& r) { return multiplier(r, 1, false); },
         "second Floquet multiplier's modulus"},
        {"multiplier_2_angle_rad", "rad", false, [](const RunResult& r) { return multiplier(r, 1, true); },
         "second Floquet multiplier's angle"},
        {"multiplier_3_modulus", "1", false, [](const RunResult& r) { return multiplier(r, 2, false); },
         "third Floquet multiplier's modulus"},
        {"multiplier_3_angle_rad", "rad", false, [](const RunResult& r) { return multiplier(r, 2, true); },
         "third Floquet multiplier's angle"},
        {"multiplier_4_modulus", "1", false, [](const RunResult& r) { return multiplier(r, 3, false); },
         "fourth Floquet multiplier's modulus"},
        {"multiplier_4_angle_rad", "rad", false, [](const RunResult& r) { return multiplier(r, 3, true); },
         "fourth Floquet multiplier's angle"},
        {"orbit_conditioning", "1", false, [](const RunResult& r) { return orbit_conditioning(r.steady.multipliers); },
         "kappa = 1/min|1 - mu| over the Floquet multipliers: how much the orbit's place amplifies its period map's error or a parameter's change (NaN: no multipliers)"},
        {"slowest_mode_cycles", "1", false, [](const RunResult& r) { return slowest_mode_cycles(r.steady.multipliers); },
         "e-folding time of the slowest Floquet mode, 1/min|ln|mu||, in crank cycles: how long a disturbance along it takes to decay or grow by e (NaN: no multipliers)"},
        {"slowest_mode_s", "s", false,
         [](const RunResult& r) { return slowest_mode_cycles(r.steady.multipliers) * cycle_period(r); },
         "the same e-folding time in seconds (slowest_mode_cycles x the crank period)"},
        {"safe_film_thickness_m", "m", false, [](const RunResult& r) { return r.metrics.safe_film_thickness_m; },
         "safe minimum film thickness, 0.00015 mm per mm of bearing diameter (ESDU 84031)"},
        {"below_safe_film", "1", true, [](const RunResult& r) { return below_safe_film(r); },
         "1 if the minimum film thickness is below the safe film thickness: an orbit's; a collapsed film's; a "
         "drifting film's once its drift law crosses the safe film or it is already below and falling "
         "(missing: unknown, a case without a steady film)"},
        {"load_reverses", "1", true, [](const RunResult& r) { return r.metrics.load_reverses ? 1.0 : 0.0; },
         "1 if the metric joint's film force turns by more than 90 degrees (in the bearing body's frame) within a metric cycle"},
    };
    fields.insert(fields.end(), rest.begin(), rest.end());
    return fields;
  }();
  return f;
}

const std::vector<ResultField>& energy_fields() {
  static const std::vector<ResultField> f = {
      {"driver_work_J", "J", false, [](const RunResult& r) { return r.metrics.driver_work_J; }, "work of the drivers"},
      {"film_dissipation_J", "J", false, [](const RunResult& r) { return r.metrics.film_dissipation_J; },
       "energy dissipated by the films"},
      {"energy_change_J", "J", false, [](const RunResult& r) { return r.metrics.energy_change_J; },
       "change of kinetic and potential energy"},
      {"energy_residual_J", "J", false, [](const RunResult& r) { return r.metrics.energy_residual_J; },
       "driver work - energy change - film dissipation"},
  };
  return f;
}

bool has_energy_balance(const RunResult& r) {
  return r.metrics.driver_work_J != 0.0 || r.metrics.film_dissipation_J != 0.0;
}

const std::vector<ResultField>& solver_fields() {
  static const std::vector<ResultField> f = {
      {"steps", "1", true, [](const RunResult& r) { return double(r.stats.steps); }, "integrator steps"},
      {"rhs_evals", "1", true, [](const RunResult& r) { return double(r.stats.rhs_evals); }, "right-hand-side evaluations"},
      {"rhs_evals_jacobian", "1", true, [](const RunResult& r) { return double(r.stats.rhs_evals_jacobian); },
       "right-hand-side evaluations for difference-quotient Jacobians (SUNDIALS' and the joint formulation's own)"},
      {"jacobian_evals", "1", true, [](const RunResult& r) { return double(r.stats.jacobian_evals); }, "Jacobian evaluations"},
      {"film_law_evals_jacobian", "1", true, [](const RunResult& r) { return double(r.stats.film_law_evals_jacobian); },
       "force-law evaluations for structured Jacobians"},
      {"linear_setups", "1", true, [](const RunResult& r) { return double(r.stats.linear_setups); }, "linear solver setups"},
      {"error_test_fails", "1", true, [](const RunResult& r) { return double(r.stats.error_test_fails); }, "local error test failures"},
      {"nonlinear_iters", "1", true, [](const RunResult& r) { return double(r.stats.nonlinear_iters); }, "nonlinear solver iterations"},
      {"nonlinear_conv_fails", "1", true, [](const RunResult& r) { return double(r.stats.nonlinear_conv_fails); },
       "nonlinear solver convergence failures"},
      {"root_evals", "1", true, [](const RunResult& r) { return double(r.stats.root_evals); }, "root-function (event) evaluations"},
      {"observer_evals", "1", true, [](const RunResult& r) { return double(r.stats.observer_evals); }, "observer evaluations"},
      {"mode_switches", "1", true, [](const RunResult& r) { return double(r.stats.mode_switches); }, "film mode switches"},
      {"repartitions", "1", true, [](const RunResult& r) { return double(r.stats.repartitions); }, "coordinate repartitions"},
      {"wall_time_s", "s", false, [](const RunResult& r) { return r.stats.wall_time_s; }, "wall-clock time of the run"},
      {"final_time_s", "s", false, [](const RunResult& r) { return r.stats.final_time_s; }, "simulated time reached"},
      {"max_position_drift", "m", false, [](const RunResult& r) { return r.stats.max_position_drift; },
       "largest position constraint violation max |Phi| (m, or rad for angular rows)"},
      {"max_velocity_drift", "m s-1", false, [](const RunResult& r) { return r.stats.max_velocity_drift; },
       "largest velocity constraint violation max |dPhi/dt| (m s-1, or rad s-1 for angular rows)"},
  };
  return f;
}

std::string cf_units(const std::string& u) {
  static const std::vector<std::pair<std::string, std::string>> map = {
      {"", "1"},           {"m/s", "m s-1"},     {"m/s^2", "m s-2"},  {"rad/s", "rad s-1"},
      {"rad/s^2", "rad s-2"}, {"kg m^2", "kg m2"}, {"N/m", "N m-1"}};
  for (const auto& [from, to] : map)
    if (u == from) return to;
  return u;
}

namespace {
/// What a channel quantity is, for `long_name`.
std::string quantity_text(const std::string& q) {
  static const std::vector<std::pair<std::string, std::string>> text = {
      {"x", "x position of the centre of mass"}, {"y", "y position of the centre of mass"},
      {"angle", "orientation angle"}, {"vx", "x velocity of the centre of mass"},
      {"vy", "y velocity of the centre of mass"}, {"omega", "angular velocity"},
      {"ax", "x acceleration of the centre of mass"}, {"ay", "y acceleration of the centre of mass"},
      {"alpha", "angular acceleration"}, {"reaction", "force magnitude on the journal (body j)"},
      {"reaction_x", "x force on the journal (body j)"}, {"reaction_y", "y force on the journal (body j)"},
      {"e_x", "x eccentricity (journal - bearing centre)"}, {"e_y", "y eccentricity (journal - bearing centre)"},
      {"h_min", "minimum film thickness c (1 - eps)"}, {"eps", "eccentricity ratio |e|/c"},
      {"eps_dot", "rate of the eccentricity ratio"}, {"gamma", "angle of the eccentricity vector"},
      {"gamma_dot", "rate of the eccentricity angle"}, {"wedge", "wedge (entraining) angular speed"},
      {"film_radial", "radial film force"}, {"film_tangential", "tangential film force"}};
  for (const auto& [k, v] : text)
    if (k == q) return v;
  return q;
}
}  // namespace

std::vector<std::string> channel_long_names(const std::string& scene_json, const std::vector<std::string>& names) {
  std::map<std::string, std::string> by_name;
  try {
    const nlohmann::json doc = nlohmann::json::parse(scene_json);
    if (doc.contains("outputs") && doc["outputs"].contains("channels"))
      for (const auto& c : doc["outputs"]["channels"]) {
        const std::string q = c.value("quantity", "");
        std::string where;
        if (c.contains("body")) where = " of body " + c["body"].get<std::string>();
        if (c.contains("joint")) where = " of joint " + c["joint"].get<std::string>();
        by_name[c.value("name", "")] = q + where + ": " + quantity_text(q);
      }
  } catch (const std::exception&) {
    // No descriptions then: the names and units still say what a channel is.
  }
  std::vector<std::string> out;
  for (const std::string& n : names) {
    if (n == "t") {
      out.push_back("time");
      continue;
    }
    const auto it = by_name.find(n);
    out.push_back(it == by_name.end() ? n : it->second);
  }
  return out;
}

void write_series(h5::Group& g, const Series& s, const std::vector<std::string>& long_names) {
  if (s.names.empty()) return;
  g.set_attribute("channels", s.names);
  std::vector<h5::Dataset> ds;
  for (std::size_t i = 0; i < s.names.size(); ++i) {
    ds.push_back(g.write_dataset(s.names[i], s.data[i], cf_units(s.units[i])));
    if (i < long_names.size() && !long_names[i].empty()) ds.back().set_attribute("long_name", long_names[i]);
  }
  // t is the first channel: the dimension scale of the others.
  if (s.names.front() != "t") return;
  ds.front().make_scale("t");
  for (std::size_t i = 1; i < ds.size(); ++i)
    if (ds[i].shape() == ds.front().shape()) ds[i].attach_scale(ds.front(), 0);
}

const std::vector<CycleField>& cycle_fields() {
  static const std::vector<CycleField> f = [] {
    std::vector<CycleField> fields = {
        {"t_start_s", "s", "start of the cycle", [](const CycleMetrics& c) { return c.t_start_s; }},
        {"t_end_s", "s", "end of the cycle", [](const CycleMetrics& c) { return c.t_end_s; }},
    };
    for (const SteadyMetric& sm : steady_metrics())
      fields.push_back({sm.name, sm.unit, sm.cycle_long_name, [p = sm.per_cycle](const CycleMetrics& c) { return c.*p; }});
    std::vector<CycleField> rest = {
        {"periodicity", "1", "largest orbit distance to the previous cycle / clearance (NaN: first cycle)",
         [](const CycleMetrics& c) { return known(c.periodicity); }},
        {"end_eccentricity_x", "1", "metric joint's e_x / c at the cycle's end (crank angle 0: Poincare section)",
         [](const CycleMetrics& c) { return c.end_eccentricity_x; }},
        {"end_eccentricity_y", "1", "metric joint's e_y / c at the cycle's end",
         [](const CycleMetrics& c) { return c.end_eccentricity_y; }},
        {"end_eccentricity_rate_x", "s-1", "metric joint's de_x/dt / c at the cycle's end",
         [](const CycleMetrics& c) { return c.end_eccentricity_rate_x; }},
        {"end_eccentricity_rate_y", "s-1", "metric joint's de_y/dt / c at the cycle's end",
         [](const CycleMetrics& c) { return c.end_eccentricity_rate_y; }},
    };
    fields.insert(fields.end(), rest.begin(), rest.end());
    return fields;
  }();
  return f;
}

std::string program_version() { return LUB_VERSION; }
std::string build_revision() { return LUB_GIT_REVISION; }

namespace {
void put(h5::Object& obj, const ResultField& f, const RunResult& r) {
  const double v = f.get(r);
  if (f.integer)
    obj.set_attribute_int64(f.name, std::isfinite(v) ? static_cast<std::int64_t>(v) : kMissingInteger);
  else
    obj.set_attribute(f.name, v);
}
}  // namespace

std::string derivative_unit(const std::string& metric_unit, const std::string& parameter_unit) {
  if (parameter_unit.empty() || parameter_unit == "1") return metric_unit;
  // A unit of one factor without exponent divides as it is ("m/m"); any other in
  // parentheses ("m/(Pa s)", "m/(min-1)").
  if (parameter_unit.find_first_of(" -0123456789") == std::string::npos) return metric_unit + "/" + parameter_unit;
  return metric_unit + "/(" + parameter_unit + ")";
}

namespace {

void write_sensitivities(h5::File& f, const std::vector<Sensitivity>& sens) {
  if (sens.empty()) return;
  h5::Group g = f.require_group("sensitivities");
  for (std::size_t k = 0; k < sens.size(); ++k) {
    const Sensitivity& s = sens[k];
    h5::Group p = g.require_group(std::to_string(k));
    p.set_attribute("parameter", s.name);
    p.set_attribute("parameter_unit", s.unit);
    p.set_attribute("value", s.value);
    p.set_attribute("status", s.ok ? "ok" : "failed");
    p.set_attribute("message", s.message);
    p.set_attribute_int64("periods_integrated", s.periods);
    const auto& metrics = steady_metrics();
    for (std::size_t i = 0; i < metrics.size(); ++i) {
      const std::string unit = derivative_unit(metrics[i].unit, s.unit);
      const std::string name = metrics[i].name;
      p.write_dataset(name, std::vector<double>{s.d_metric[i]}, unit)
          .set_attribute("long_name", "d " + name + " / d " + s.name + " on the located orbit");
      p.write_dataset(name + "_error", std::vector<double>{s.d_metric_error[i]}, unit)
          .set_attribute("long_name", "error bar of d " + name + " / d " + s.name + " (step delta against 4 delta)");
    }
  }
}
}  // namespace

void write_run_file(const std::string& path, const std::string& scene_text, const std::string& program,
                    const RunResult& r, const std::vector<std::string>& warnings,
                    const std::vector<Sensitivity>& sensitivities) {
  const std::string tmp = path + ".partial";
  {
    h5::File f = h5::File::create(tmp);
    f.set_attribute("scene", scene_text);
    f.set_attribute("program", program);
    f.set_attribute("format", kRunFormat);
    f.set_attribute("version", program_version());
    f.set_attribute("revision", build_revision());
    f.set_attribute("status", to_string(r.status));
    f.set_attribute("message", r.message);
    f.set_attribute("warnings", warnings);  // plausibility warnings (Scene::warnings)
    f.set_attribute("notes", r.notes);      // validity notes (RunResult::notes)
    if (!r.series.names.empty()) {
      h5::Group sg = f.require_group("series");
      write_series(sg, r.series, channel_long_names(scene_text, r.series.names));
    }
    if (!r.orbit.names.empty()) {
      // The periodic orbit found by shooting, over the metric cycles (its own time axis).
      h5::Group og = f.require_group("orbit");
      write_series(og, r.orbit, channel_long_names(scene_text, r.orbit.names));
    }
    write_sensitivities(f, sensitivities);
    h5::Group m = f.require_group("metrics");
    std::vector<std::string> units;
    m.set_attribute("classification", classification(r));
    m.set_attribute("steady_method", std::string(name_of(r.steady.method)));
    m.set_attribute_int64("missing_value", kMissingInteger);  // of its integer attributes; floats: NaN
    for (const auto& fld : metric_fields()) put(m, fld, r);
    // Every Floquet multiplier (the columns above hold the four largest).
    std::vector<double> mod, arg;
    for (const auto& mu : r.steady.multipliers) mod.push_back(std::abs(mu)), arg.push_back(std::arg(mu));
    m.set_attribute("multiplier_modulus", mod);
    m.set_attribute("multiplier_angle_rad", arg);
    if (has_energy_balance(r))
      for (const auto& fld : energy_fields()) m.set_attribute(fld.name, fld.get(r));
    h5::Group sv = f.require_group("solver");
    const SolverSettingNames names = setting_names(r.stats);
    sv.set_attribute("method", names.method);
    sv.set_attribute("formulation", names.formulation);
    sv.set_attribute("jacobian", names.jacobian);
    sv.set_attribute("rtol", r.stats.rtol);
    sv.set_attribute("atol", r.stats.atol);
    sv.set_attribute_int64("missing_value", kMissingInteger);
    for (const auto& fld : solver_fields()) put(sv, fld, r);

    std::vector<h5::Column> columns = {{"cycle", h5::ColumnType::Int64, "1", "crank cycle number (1: the first)"}};
    for (const CycleField& fld : cycle_fields())
      columns.push_back({fld.name, h5::ColumnType::Float64, fld.unit, fld.long_name});
    h5::Table c = f.create_table("cycles", columns);
    for (const CycleField& fld : cycle_fields()) c.column(fld.name).set_attribute("_FillValue", kNaN);
    std::vector<h5::Row> rows;
    std::int64_t number = 0;
    for (const CycleMetrics& cy : r.cycles) {
      h5::Row& row = rows.emplace_back();
      row.reserve(columns.size());
      row.emplace_back(std::in_place_type<std::int64_t>, ++number);
      for (const CycleField& fld : cycle_fields()) row.emplace_back(std::in_place_type<double>, fld.get(cy));
    }
    c.append(rows);
    f.close();
  }
  if (std::rename(tmp.c_str(), path.c_str()) != 0) {
    std::remove(tmp.c_str());
    throw std::runtime_error("cannot rename " + tmp + " to " + path);
  }
}

}  // namespace lub
