// lubjoint._lubjoint: the compiled half of the Python module `lubjoint`.
//
// Thin bindings over lubcore: the scene is read, overridden, validated and run by the same
// functions lubsim calls (read_json_file / parse_json_text, apply_override, parse_scene,
// run_scene, write_run_file), and a force law or a steady bearing by the same functions
// lubbearing calls (film_force, solve_steady_bearing). The Python half
// (core/python/lubjoint/run.py, bearing.py) turns the named results into xarray and NumPy objects.
//
// Bad input throws lub::InputError, seen in Python as lubjoint.InputError (a ValueError)
// with the same message as the command line (JSON path, value, rule). The GIL is released
// while a scene is parsed, run and written, and while a force law is evaluated, so Python
// threads can run cases side by side.
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <algorithm>
#include <cmath>
#include <optional>
#include <string>
#include <vector>

#include "lub/bearing/bearing_inputs.hpp"
#include "lub/bearing/film_force.hpp"
#include "lub/bearing/film_outputs.hpp"
#include "lub/bearing/plausibility.hpp"
#include "lub/common/constants.hpp"
#include "lub/io/json_reader.hpp"
#include "lub/io/output_path.hpp"
#include "lub/bearing/reynolds.hpp"
#include "lub/run/run.hpp"
#include "lub/run/run_io.hpp"
#include "lub/scene/scene.hpp"
#include "lub/bearing/steady_bearing.hpp"

namespace py = pybind11;

namespace {

using lub::kPi;

py::array_t<double> to_array(const std::vector<double>& v) {
  return py::array_t<double>(static_cast<py::ssize_t>(v.size()), v.data());
}

// The records simulate returns, with named fields (lubjoint._lubjoint.Scalar, .Column).
// A metric or solver statistic: one value with its CF unit; `integer` for counts and flags.
struct Scalar {
  std::string name;
  double value;
  std::string units;
  bool integer;
  std::string long_name;
};

// A column over time or cycles (a channel of /series, /orbit, or /cycles).
struct Column {
  std::string name;
  std::string units;
  std::string long_name;
  py::array_t<double> values;
};

// One run, as lubsim does it: output path check, scene (file or JSON text), overrides in
// order, validation, run, and the run file only when `output` is given. Returns a dict of plain
// values and Scalar/Column records (named fields). `strict`: a plausibility warning is an
// InputError (lubsim --strict), raised before any work.
py::dict simulate(const std::optional<std::string>& scene_path, const std::optional<std::string>& scene_text,
                  const std::string& origin, const std::vector<std::string>& assignments,
                  const std::optional<std::string>& output, const std::string& program, bool strict,
                  const std::vector<std::string>& sensitivity, const std::optional<std::string>& from_scene,
                  const std::vector<double>& from_orbit, bool single_step) {
  lub::RunResult r;
  std::string effective;
  std::vector<std::string> warnings;
  std::vector<lub::Sensitivity> sens;
  {
    py::gil_scoped_release release;
    // The output path first, as lubsim: refused before any work, nothing created.
    if (output)
      if (const auto problem = lub::output_path_problem(*output, "output")) throw lub::InputError(*problem);
    lub::Scene scene;
    try {
      // The messages name no file: `origin` prefixes them once, below.
      nlohmann::json doc = lub::parse_json(scene_path ? lub::read_text_file(*scene_path) : *scene_text);
      for (const auto& s : assignments) lub::apply_override(doc, s);
      scene = lub::parse_scene(doc);
      warnings = scene.warnings;
      if (strict && !warnings.empty()) {
        std::string all;
        for (const std::string& w : warnings) all += (all.empty() ? "" : "\n") + w;
        throw lub::InputError(all + "; refused under strict=True");
      }
      effective = doc.dump(2);
      const std::vector<lub::SensitivityParameter> params = lub::sensitivity_parameters(doc, sensitivity, "sensitivity");
      // From a neighbour's orbit (continued along the path of scenes from its scene, no run
      // alone where it is lost), or from the scene's own start.
      if (from_scene && !from_orbit.empty())
        r = lub::run_scene(scene, lub::ContinuationStart{lub::unpack_seed(from_orbit),
                                                         lub::scene_path(lub::parse_json(*from_scene), doc), false,
                                                         single_step ? 1.0 : 0.0});
      else
        r = lub::run_scene(scene);  // throws InputError only if the mechanism cannot assemble
      if (!params.empty()) sens = lub::steady_sensitivities(r, params);
    } catch (const lub::InputError& e) {
      // lubsim prints "lubsim: SCENE: message"; the message here is "SCENE: message".
      throw lub::InputError(origin + ": " + e.what());
    }
    if (output) lub::write_run_file(*output, effective, program, r, warnings, sens);
  }
  py::dict out;
  out["status"] = lub::to_string(r.status);
  out["message"] = r.message;
  out["classification"] = lub::classification(r);
  out["steady_method"] = std::string(lub::name_of(r.steady.method));
  std::vector<double> mod, arg;
  for (const auto& mu : r.steady.multipliers) mod.push_back(std::abs(mu)), arg.push_back(std::arg(mu));
  out["multiplier_modulus"] = to_array(mod);
  out["multiplier_angle_rad"] = to_array(arg);
  out["scene"] = effective;
  out["program"] = program;
  out["version"] = lub::program_version();
  out["revision"] = lub::build_revision();
  out["warnings"] = warnings;
  out["notes"] = r.notes;
  out["orbit_seed"] = r.orbit_seed.valid() ? lub::pack_seed(r.orbit_seed) : std::vector<double>{};
  py::list sl;
  for (const lub::Sensitivity& s : sens) {
    py::dict d;
    d["parameter"] = s.name;
    d["unit"] = s.unit;
    d["value"] = s.value;
    d["ok"] = s.ok;
    d["message"] = s.message;
    d["periods"] = s.periods;
    d["d_metric"] = to_array(s.d_metric);
    d["d_metric_error"] = to_array(s.d_metric_error);
    std::vector<std::string> units;
    for (const lub::SteadyMetric& m : lub::steady_metrics()) units.push_back(lub::derivative_unit(m.unit, s.unit));
    d["units"] = units;
    sl.append(d);
  }
  out["sensitivities"] = sl;
  std::vector<std::string> metric_names;
  for (const lub::SteadyMetric& m : lub::steady_metrics()) metric_names.emplace_back(m.name);
  out["steady_metric_names"] = metric_names;
  std::vector<Scalar> metrics, solver;
  for (const auto& f : lub::metric_fields()) metrics.push_back({f.name, f.get(r), f.unit, f.integer, f.long_name});
  if (lub::has_energy_balance(r))  // as the run file
    for (const auto& f : lub::energy_fields()) metrics.push_back({f.name, f.get(r), f.unit, f.integer, f.long_name});
  for (const auto& f : lub::solver_fields()) solver.push_back({f.name, f.get(r), f.unit, f.integer, f.long_name});
  out["metrics"] = metrics;
  out["solver"] = solver;
  py::dict solver_settings;
  const lub::SolverSettingNames names = lub::setting_names(r.stats);
  solver_settings["method"] = names.method;
  solver_settings["formulation"] = names.formulation;
  solver_settings["jacobian"] = names.jacobian;
  solver_settings["rtol"] = r.stats.rtol;
  solver_settings["atol"] = r.stats.atol;
  out["solver_settings"] = solver_settings;
  // The channels as the run file's /series: CF units, long names from the scene.
  std::vector<Column> series;  // "t" first
  const std::vector<std::string> long_names = lub::channel_long_names(effective, r.series.names);
  for (size_t i = 0; i < r.series.names.size(); ++i)
    series.push_back({r.series.names[i], lub::cf_units(r.series.units[i]),
                      i < long_names.size() ? long_names[i] : std::string(), to_array(r.series.data[i])});
  out["series"] = series;
  std::vector<Column> orbit;  // the periodic orbit's channels (shooting), as series
  for (size_t i = 0; i < r.orbit.names.size(); ++i)
    orbit.push_back({r.orbit.names[i], lub::cf_units(r.orbit.units[i]), std::string(), to_array(r.orbit.data[i])});
  out["orbit"] = orbit;
  std::vector<Column> cycles;  // /cycles of the run file
  for (const lub::CycleField& f : lub::cycle_fields()) {
    std::vector<double> values;
    values.reserve(r.cycles.size());
    for (const lub::CycleMetrics& cy : r.cycles) values.push_back(f.get(cy));
    cycles.push_back({f.name, f.unit, f.long_name, to_array(values)});
  }
  out["cycles"] = cycles;
  return out;
}

// The bearing of lubbearing's read_common: R_B = R_J + c, with the same rules
// (lub/bearing/bearing_inputs.hpp) and messages, named after the Python arguments.
void require_positive(const char* name, double value, const char* unit) {
  if (!lub::is_positive_input(value)) lub::fail(name, value, lub::positive_rule(unit));
}

struct Bearing {
  lub::ForceLaw law = lub::ForceLaw::gumbel_short;
  lub::BearingGeometry geometry;
  double viscosity = 0.0;
  lub::FiniteBearingOptions finite;
};

Bearing read_bearing(const std::string& law, double radius_m, double clearance_m, double length_m,
                     double viscosity_Pa_s, const std::optional<std::string>& cavitation,
                     std::optional<int> n_theta, std::optional<int> n_z, bool groove) {
  Bearing b;
  if (const auto parsed = lub::parse_name<lub::ForceLaw>(law))
    b.law = *parsed;
  else
    lub::fail("law", law, "must be one of " + lub::names_list<lub::ForceLaw>());
  require_positive("radius_m", radius_m, "m");
  require_positive("clearance_m", clearance_m, "m");
  require_positive("length_m", length_m, "m");
  require_positive("viscosity_Pa_s", viscosity_Pa_s, "Pa s");
  b.geometry.journal_radius_m = radius_m;
  b.geometry.bearing_radius_m = radius_m + clearance_m;
  b.geometry.length_m = length_m;
  b.viscosity = viscosity_Pa_s;
  const bool finite = b.law == lub::ForceLaw::finite_reynolds;
  const std::string only = "applies only to law finite_reynolds (got " + law + ")";
  if (cavitation) {
    if (!finite) lub::fail("cavitation", *cavitation, only);
    if (const auto parsed = lub::parse_name<lub::Cavitation>(*cavitation))
      b.finite.cavitation = *parsed;
    else
      lub::fail("cavitation", *cavitation, "must be one of " + lub::names_list<lub::Cavitation>());
  }
  if (n_theta) {
    if (!finite) lub::fail("n_theta", *n_theta, only);
    if (!lub::kReynoldsNThetaRange.contains(*n_theta)) lub::fail("n_theta", *n_theta, lub::kReynoldsNThetaRange.rule());
    b.finite.n_theta = *n_theta;
  }
  if (n_z) {
    if (!finite) lub::fail("n_z", *n_z, only);
    if (!lub::kReynoldsNZRange.contains(*n_z)) lub::fail("n_z", *n_z, lub::kReynoldsNZRange.rule());
    b.finite.n_z = *n_z;
  }
  if (groove && !finite) lub::fail("groove_at_max_film", true, only);
  b.finite.groove_at_max_film = groove;
  return b;
}

using Flat = py::array_t<double, py::array::c_style | py::array::forcecast>;

// Film force at n states (the arrays already broadcast and flattened by the Python half).
py::dict force(const std::string& law, const Flat& eps, const Flat& eps_dot, const Flat& wedge,
                double radius_m, double clearance_m, double length_m, double viscosity_Pa_s,
                const std::optional<std::string>& cavitation, std::optional<int> n_theta,
                std::optional<int> n_z, bool groove) {
  const Bearing b = read_bearing(law, radius_m, clearance_m, length_m, viscosity_Pa_s, cavitation, n_theta, n_z,
                                 groove);
  const py::ssize_t n = eps.size();
  if (eps_dot.size() != n || wedge.size() != n)
    throw lub::InputError("eps, eps_dot, wedge_rad_s: must have the same number of elements after broadcasting");
  py::array_t<double> fr(n), ft(n);
  const double* e = eps.data();
  const double* ed = eps_dot.data();
  const double* w = wedge.data();
  double* r_out = fr.mutable_data();
  double* t_out = ft.mutable_data();
  {
    py::gil_scoped_release release;
    // lubbearing force's rules, element by element (index into the broadcast, flattened arrays)
    const auto at = [](const char* name, py::ssize_t i) { return std::string(name) + "[" + std::to_string(i) + "]"; };
    for (py::ssize_t i = 0; i < n; ++i) {
      if (!lub::is_film_eccentricity_ratio(e[i]))
        lub::fail(at("eps", i), e[i], std::string(lub::kFilmEccentricityRatioRule));
      if (!std::isfinite(ed[i])) lub::fail(at("eps_dot", i), ed[i], "must be finite");
      if (!std::isfinite(w[i])) lub::fail(at("wedge_rad_s", i), w[i], "must be finite");
    }
    lub::FiniteBearingSolver solver(b.finite);
    for (py::ssize_t i = 0; i < n; ++i) {
      lub::BearingState s;
      s.eps = e[i];
      s.eps_dot = ed[i];
      s.wedge = w[i];
      const lub::FilmForce f = lub::film_force(b.law, b.geometry, b.viscosity, s, &solver);
      r_out[i] = f.radial_N;
      t_out[i] = f.tangential_N;
    }
  }
  py::dict out;
  out["radial_N"] = fr;
  out["tangential_N"] = ft;
  return out;
}

// Mid-plane film pressure [Pa] at angles theta [rad] from the line of maximum film, one state:
// the closed-form law's own field, or the finite bearing's grid (its mid-plane cell centres,
// interpolated linearly and periodically in θ).
py::array_t<double> pressure(const std::string& law, const Flat& theta, double eps, double eps_dot, double wedge,
                             double radius_m, double clearance_m, double length_m, double viscosity_Pa_s,
                             const std::optional<std::string>& cavitation, std::optional<int> n_theta,
                             std::optional<int> n_z, bool groove) {
  const Bearing b = read_bearing(law, radius_m, clearance_m, length_m, viscosity_Pa_s, cavitation, n_theta, n_z,
                                 groove);
  if (!lub::is_film_eccentricity_ratio(eps)) lub::fail("eps", eps, std::string(lub::kFilmEccentricityRatioRule));
  if (!std::isfinite(eps_dot)) lub::fail("eps_dot", eps_dot, "must be finite");
  if (!std::isfinite(wedge)) lub::fail("wedge_rad_s", wedge, "must be finite");
  const py::ssize_t n = theta.size();
  const double* th = theta.data();
  for (py::ssize_t i = 0; i < n; ++i)
    if (!std::isfinite(th[i])) lub::fail("theta_rad[" + std::to_string(i) + "]", th[i], "must be finite");
  py::array_t<double> out(n);
  double* p = out.mutable_data();
  py::gil_scoped_release release;
  const lub::BearingState s{eps, eps_dot, wedge};
  if (b.law != lub::ForceLaw::finite_reynolds) {
    for (py::ssize_t i = 0; i < n; ++i) p[i] = lub::film_pressure_Pa(b.law, b.geometry, b.viscosity, s, th[i]);
    return out;
  }
  lub::FiniteBearingSolver solver(b.finite);
  solver.solve(b.geometry, b.viscosity, s);
  std::vector<std::pair<double, double>> cells;  // (θ in [0, 2π), p) at the mid-plane
  for (int i = 0; i < b.finite.n_theta; ++i) {
    const double t = solver.theta_rad(i);
    cells.emplace_back(t - lub::kTwoPi * std::floor(t / lub::kTwoPi), solver.pressure_Pa(i, 0));
  }
  std::sort(cells.begin(), cells.end());
  cells.insert(cells.begin(), {cells.back().first - lub::kTwoPi, cells.back().second});
  cells.emplace_back(cells[1].first + lub::kTwoPi, cells[1].second);
  for (py::ssize_t i = 0; i < n; ++i) {
    const double t = th[i] - lub::kTwoPi * std::floor(th[i] / lub::kTwoPi);
    const auto hi = std::upper_bound(cells.begin(), cells.end(), std::make_pair(t, -HUGE_VAL));
    const auto lo = hi - 1;
    const double w = (t - lo->first) / (hi->first - lo->first);
    p[i] = (1.0 - w) * lo->second + w * hi->second;
  }
  return out;
}

// lubbearing steady: the same inputs, the same keys as its JSON.
py::dict steady_bearing(const std::string& law, double load_N, double speed_rpm, double radius_m,
                        double clearance_m, double length_m, double viscosity_Pa_s,
                        const std::optional<std::string>& cavitation, std::optional<int> n_theta,
                        std::optional<int> n_z, bool groove) {
  const Bearing b = read_bearing(law, radius_m, clearance_m, length_m, viscosity_Pa_s, cavitation, n_theta, n_z,
                                 groove);
  require_positive("load_N", load_N, "N");
  if (!lub::is_journal_speed(speed_rpm)) lub::fail("speed_rpm", speed_rpm, std::string(lub::kJournalSpeedRule));
  lub::SteadyBearingInput in;
  in.law = b.law;
  in.finite = b.finite;
  in.geometry = b.geometry;
  in.viscosity_Pa_s = b.viscosity;
  in.load_N = load_N;
  in.speed_rad_s = speed_rpm * 2.0 * kPi / 60.0;
  lub::SteadyBearingResult r;
  {
    py::gil_scoped_release release;
    r = lub::solve_steady_bearing(in);
  }
  py::dict out;
  out["model"] = std::string(lub::name_of(b.law));
  out["radius_m"] = radius_m;
  out["clearance_m"] = clearance_m;
  out["length_m"] = length_m;
  out["viscosity_Pa_s"] = viscosity_Pa_s;
  if (b.law == lub::ForceLaw::finite_reynolds) {
    out["cavitation"] = std::string(lub::name_of(b.finite.cavitation));
    out["n_theta"] = b.finite.n_theta;
    out["n_z"] = b.finite.n_z;
    out["groove_at_max_film"] = b.finite.groove_at_max_film;
  }
  lub::report_steady_bearing(out, in, speed_rpm, r);
  // Plausibility warnings, as lubbearing's "warnings" (lub/bearing/plausibility.hpp), named
  // after the Python arguments.
  std::vector<std::string> warnings;
  if (auto w = lub::implausible_viscosity("viscosity_Pa_s", viscosity_Pa_s)) warnings.push_back(*w);
  if (auto w = lub::implausible_clearance_ratio("clearance_m / radius_m", clearance_m, radius_m)) warnings.push_back(*w);
  if (auto w = lub::implausible_speed_rpm("speed_rpm", speed_rpm)) warnings.push_back(*w);
  out["warnings"] = warnings;
  return out;
}

}  // namespace

PYBIND11_MODULE(_lubjoint, m) {
  m.doc() = "Compiled core of lubjoint (lubcore bindings); use the lubjoint package, not this module.";
  py::register_exception<lub::InputError>(m, "InputError", PyExc_ValueError);
  py::class_<Scalar>(m, "Scalar", "A metric or solver statistic of a run (simulate's metrics, solver).")
      .def_readonly("name", &Scalar::name)
      .def_readonly("value", &Scalar::value)
      .def_readonly("units", &Scalar::units, "CF style")
      .def_readonly("integer", &Scalar::integer, "a count or flag (int64 in the Dataset)")
      .def_readonly("long_name", &Scalar::long_name);
  py::class_<Column>(m, "Column", "A column of a run (simulate's series, orbit, cycles).")
      .def_readonly("name", &Column::name)
      .def_readonly("units", &Column::units, "CF style")
      .def_readonly("long_name", &Column::long_name)
      .def_readonly("values", &Column::values);
  m.def("simulate", &simulate, py::arg("scene_path"), py::arg("scene_text"), py::arg("origin"),
        py::arg("assignments"), py::arg("output"), py::arg("program") = "lubjoint", py::arg("strict") = false,
        py::arg("sensitivity") = std::vector<std::string>{}, py::arg("from_scene") = std::nullopt,
        py::arg("from_orbit") = std::vector<double>{}, py::arg("single_step") = false,
        "Runs one scene as lubsim does (GIL released); returns a dict with Scalar/Column records. See lubjoint.simulate.");
  m.def("force", &force, py::arg("law"), py::arg("eps"), py::arg("eps_dot"), py::arg("wedge_rad_s"),
        py::arg("radius_m"), py::arg("clearance_m"), py::arg("length_m"), py::arg("viscosity_Pa_s"),
        py::arg("cavitation") = py::none(), py::arg("n_theta") = py::none(), py::arg("n_z") = py::none(),
        py::arg("groove_at_max_film") = false,
        "Film force [N] {radial_N, tangential_N} at flat, equally long arrays (GIL released). See lubjoint.force.");
  m.def("pressure", &pressure, py::arg("law"), py::arg("theta_rad"), py::arg("eps"), py::arg("eps_dot"),
        py::arg("wedge_rad_s"), py::arg("radius_m"), py::arg("clearance_m"), py::arg("length_m"),
        py::arg("viscosity_Pa_s"), py::arg("cavitation") = py::none(), py::arg("n_theta") = py::none(),
        py::arg("n_z") = py::none(), py::arg("groove_at_max_film") = false,
        "Mid-plane film pressure [Pa] at a flat array of angles, one state. See lubjoint.bearing.pressure.");
  m.def("steady_bearing", &steady_bearing, py::arg("law"), py::arg("load_N"), py::arg("speed_rpm"),
        py::arg("radius_m"), py::arg("clearance_m"), py::arg("length_m"), py::arg("viscosity_Pa_s"),
        py::arg("cavitation") = py::none(), py::arg("n_theta") = py::none(), py::arg("n_z") = py::none(),
        py::arg("groove_at_max_film") = false, "lubbearing steady. See lubjoint.steady_bearing.");
  m.def("force_law_names", [] { return lub::names_list<lub::ForceLaw>(); }, "The force laws a scene can name, comma separated.");
  m.def("version", [] { return lub::program_version(); });
  m.def("revision", [] { return lub::build_revision(); });
}
