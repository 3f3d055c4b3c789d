// lubbearing: the bearing alone, for designers and for checking a force law.
//
//   lubbearing force  --model M --eps E --eps-dot ED --omega W --gamma-dot GD
//                     --radius-m R --clearance-m C --length-m L --viscosity-Pa-s MU [--gamma G]
//                     [finite_reynolds options] [--strict]
//   lubbearing steady --model M --load-N W --speed-rpm N
//                     --radius-m R --clearance-m C --length-m L --viscosity-Pa-s MU
//                     [finite_reynolds options] [--strict]
//
// Prints one JSON object on stdout, with the plausibility warnings (lub/bearing/plausibility.hpp)
// in "warnings" (also printed on stderr). Exit status: 0 done, 2 bad arguments (message on
// stderr naming the argument, its value and the rule; or an implausible one under --strict), 3 a steady state that does not exist (the
// JSON says why).
#include <nlohmann/json.hpp>

#include <cmath>
#include <cstdlib>
#include <iostream>
#include <map>
#include <optional>
#include <set>
#include <stdexcept>
#include <string>
#include <vector>

#include "lub/bearing/bearing_inputs.hpp"
#include "lub/bearing/film_force.hpp"
#include "lub/bearing/plausibility.hpp"
#include "lub/common/constants.hpp"
#include "lub/bearing/reynolds.hpp"
#include "lub/bearing/steady_bearing.hpp"

namespace {

using lub::kPi;

const char* kUsage =
    "usage: lubbearing force  --model M --eps E --eps-dot ED --omega W --gamma-dot GD\n"
    "                         --radius-m R --clearance-m C --length-m L --viscosity-Pa-s MU\n"
    "                         [--gamma G] [finite_reynolds options] [--strict]\n"
    "       lubbearing steady --model M --load-N W --speed-rpm N\n"
    "                         --radius-m R --clearance-m C --length-m L --viscosity-Pa-s MU\n"
    "                         [finite_reynolds options] [--strict]\n"
    "\n"
    "force:  film force on the journal (SI units) at eccentricity ratio E (0 <= E < 1), its rate\n"
    "        ED [1/s], journal angular velocity W relative to the bearing [rad/s] and rate GD of\n"
    "        the line of centres relative to the bearing [rad/s] (wedge speed w = W - 2 GD).\n"
    "        Prints radial_N (along the line of centres, outward) and tangential_N (+90 deg);\n"
    "        with --gamma G [rad] (line of centres from the x axis) also x_N, y_N (Eqs. 15-16).\n"
    "steady: equilibrium of a journal turning at N rpm under a constant load W [N]: prints eps,\n"
    "        attitude_angle_deg (load line to line of centres), min_film_thickness_m,\n"
    "        sommerfeld_number (R/c)^2 mu N_s/P, P = W/(L D).\n"
    "\n"
    "  --model M                one of: %MODELS%\n"
    "  --radius-m R             journal radius R > 0 [m]\n"
    "  --clearance-m C          radial clearance C > 0 [m]\n"
    "  --length-m L             bearing length L > 0 [m]\n"
    "  --viscosity-Pa-s MU      dynamic viscosity > 0 [Pa s]\n"
    "finite_reynolds options (only with --model finite_reynolds):\n"
    "  --cavitation C           gumbel, reynolds (default) or sommerfeld\n"
    "  --n-theta N              cells around the circumference (default 48, >= 8)\n"
    "  --n-z N                  axial nodes over half the length (default 8, >= 1)\n"
    "  --groove                 ambient pressure along the line of maximum film thickness\n"
    "                           (Raimondi & Boyd's supply condition)\n"
    "  --strict                 an implausible value (viscosity outside 1e-4 - 5 Pa s,\n"
    "                           clearance/radius outside 1e-4 - 0.3, speed above 50000 rpm:\n"
    "                           probably a unit slip) is an error, not a warning\n"
    "\n"
    "Plausibility warnings go to stderr and into the JSON's \"warnings\" (a list).\n"
    "\n"
    "Exit status: 0 done, 2 bad arguments, 3 no steady state (reason in the JSON).\n";

struct UsageError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

std::string usage() {
  std::string u = kUsage;
  const std::string key = "%MODELS%";
  u.replace(u.find(key), key.size(), lub::names_list<lub::ForceLaw>());
  return u;
}

// "--name = value: rule", the house style for bad input.
[[noreturn]] void bad(const std::string& name, const std::string& value, const std::string& rule) {
  throw UsageError(name + " = " + value + ": " + rule);
}

class Args {
 public:
  Args(int argc, char** argv, int first, const std::set<std::string>& flags_with_value,
       const std::set<std::string>& bare_flags) {
    for (int i = first; i < argc; ++i) {
      std::string a = argv[i];
      std::string value;
      bool has_value = false;
      if (const auto eq = a.find('='); a.rfind("--", 0) == 0 && eq != std::string::npos) {
        value = a.substr(eq + 1);
        a = a.substr(0, eq);
        has_value = true;
      }
      if (bare_flags.count(a)) {
        if (has_value) bad(a, value, "takes no value");
        bare_.insert(a);
        continue;
      }
      if (!flags_with_value.count(a)) throw UsageError("unknown argument " + a);
      if (values_.count(a)) throw UsageError(a + " given twice");
      if (!has_value) {
        if (++i >= argc) throw UsageError(a + " needs a value");
        value = argv[i];
      }
      values_[a] = value;
    }
  }
  bool has(const std::string& name) const { return values_.count(name) || bare_.count(name); }
  std::string text(const std::string& name) const {
    const auto it = values_.find(name);
    if (it == values_.end()) throw UsageError(name + " is required");
    return it->second;
  }
  // A finite number satisfying `rule` (described by `rule_text`).
  template <class Rule>
  double number(const std::string& name, Rule rule, const std::string& rule_text) const {
    const std::string t = text(name);
    char* end = nullptr;
    const double v = std::strtod(t.c_str(), &end);
    if (t.empty() || end != t.c_str() + t.size()) bad(name, t, "must be a number");
    if (!std::isfinite(v)) bad(name, t, "must be finite");
    if (!rule(v)) bad(name, t, rule_text);
    return v;
  }
  int integer(const std::string& name, lub::IntRange range) const {
    const std::string t = text(name);
    char* end = nullptr;
    const long v = std::strtol(t.c_str(), &end, 10);
    if (t.empty() || end != t.c_str() + t.size()) bad(name, t, "must be an integer");
    if (!range.contains(v)) bad(name, t, range.rule());
    return static_cast<int>(v);
  }

 private:
  std::map<std::string, std::string> values_;
  std::set<std::string> bare_;
};

struct Common {
  lub::ForceLaw law = lub::ForceLaw::gumbel_short;
  lub::BearingGeometry geometry;
  double clearance = 0.0;  ///< as given (geometry.clearance_m() is R_B − R_J, rounded)
  double viscosity = 0.0;
  lub::FiniteBearingOptions finite;
};

Common read_common(const Args& a) {
  Common c;
  const std::string model = a.text("--model");
  if (const auto law = lub::parse_name<lub::ForceLaw>(model))
    c.law = *law;
  else
    bad("--model", model, "must be one of " + lub::names_list<lub::ForceLaw>());
  const double r = a.number("--radius-m", lub::is_positive_input, lub::positive_rule("m"));
  const double cl = a.number("--clearance-m", lub::is_positive_input, lub::positive_rule("m"));
  c.geometry.journal_radius_m = r;
  c.geometry.bearing_radius_m = r + cl;
  c.clearance = cl;
  c.geometry.length_m = a.number("--length-m", lub::is_positive_input, lub::positive_rule("m"));
  c.viscosity = a.number("--viscosity-Pa-s", lub::is_positive_input, lub::positive_rule("Pa s"));
  const bool finite = c.law == lub::ForceLaw::finite_reynolds;
  const std::string only = "applies only to --model finite_reynolds (got --model " + model + ")";
  for (const char* opt : {"--cavitation", "--n-theta", "--n-z"})
    if (a.has(opt) && !finite) bad(opt, a.text(opt), only);
  if (a.has("--groove") && !finite) bad("--groove", "set", only);
  if (a.has("--cavitation")) {
    const std::string cav = a.text("--cavitation");
    if (const auto parsed = lub::parse_name<lub::Cavitation>(cav))
      c.finite.cavitation = *parsed;
    else
      bad("--cavitation", cav, "must be one of " + lub::names_list<lub::Cavitation>());
  }
  if (a.has("--n-theta")) c.finite.n_theta = a.integer("--n-theta", lub::kReynoldsNThetaRange);
  if (a.has("--n-z")) c.finite.n_z = a.integer("--n-z", lub::kReynoldsNZRange);
  c.finite.groove_at_max_film = a.has("--groove");
  return c;
}

// The plausibility warnings of the common arguments (lub/bearing/plausibility.hpp).
std::vector<std::string> warnings_of(const Common& c) {
  std::vector<std::string> w;
  if (auto v = lub::implausible_viscosity("--viscosity-Pa-s", c.viscosity)) w.push_back(*v);
  if (auto r = lub::implausible_clearance_ratio("--clearance-m / --radius-m", c.clearance, c.geometry.journal_radius_m))
    w.push_back(*r);
  return w;
}

// Prints the warnings on stderr once. Under --strict they refuse the input: returns true
// (exit 2, no JSON).
bool refuse_implausible(const std::vector<std::string>& warnings, bool strict) {
  for (const std::string& w : warnings)
    std::cerr << "lubbearing: " << (strict ? "" : "warning: ") << w << (strict ? "; refused under --strict" : "")
              << "\n";
  return strict && !warnings.empty();
}

nlohmann::json describe(const Common& c) {
  nlohmann::json j;
  j["model"] = std::string(lub::name_of(c.law));
  j["radius_m"] = c.geometry.journal_radius_m;
  j["clearance_m"] = c.clearance;
  j["length_m"] = c.geometry.length_m;
  j["viscosity_Pa_s"] = c.viscosity;
  if (c.law == lub::ForceLaw::finite_reynolds) {
    j["cavitation"] = std::string(lub::name_of(c.finite.cavitation));
    j["n_theta"] = c.finite.n_theta;
    j["n_z"] = c.finite.n_z;
    j["groove_at_max_film"] = c.finite.groove_at_max_film;
  }
  return j;
}

const std::set<std::string> kCommonFlags = {"--model",          "--radius-m",   "--clearance-m",
                                            "--length-m",       "--viscosity-Pa-s", "--cavitation",
                                            "--n-theta",        "--n-z"};

int run_force(int argc, char** argv) {
  std::set<std::string> flags = kCommonFlags;
  flags.insert({"--eps", "--eps-dot", "--omega", "--gamma-dot", "--gamma"});
  const Args a(argc, argv, 2, flags, {"--groove", "--strict"});
  const Common c = read_common(a);
  lub::BearingState s;
  s.eps = a.number("--eps", lub::is_film_eccentricity_ratio, std::string(lub::kFilmEccentricityRatioRule));
  s.eps_dot = a.number("--eps-dot", [](double) { return true; }, "");
  const double omega = a.number("--omega", [](double) { return true; }, "");
  const double gamma_dot = a.number("--gamma-dot", [](double) { return true; }, "");
  s.wedge = omega - 2.0 * gamma_dot;
  const double gamma = a.has("--gamma") ? a.number("--gamma", [](double) { return true; }, "") : 0.0;
  std::vector<std::string> warnings = warnings_of(c);
  if (auto w = lub::implausible_speed_rad_s("--omega", omega)) warnings.push_back(*w);
  if (refuse_implausible(warnings, a.has("--strict"))) return 2;
  lub::FiniteBearingSolver solver(c.finite);
  const lub::FilmForce f = lub::film_force(c.law, c.geometry, c.viscosity, s, &solver);
  nlohmann::json out = describe(c);
  out["eps"] = s.eps;
  out["eps_dot_per_s"] = s.eps_dot;
  out["omega_rad_s"] = omega;
  out["gamma_dot_rad_s"] = gamma_dot;
  out["wedge_rad_s"] = s.wedge;
  out["radial_N"] = f.radial_N;
  out["tangential_N"] = f.tangential_N;
  out["magnitude_N"] = std::hypot(f.radial_N, f.tangential_N);
  if (a.has("--gamma")) {
    out["gamma_rad"] = gamma;
    out["x_N"] = f.radial_N * std::cos(gamma) - f.tangential_N * std::sin(gamma);
    out["y_N"] = f.radial_N * std::sin(gamma) + f.tangential_N * std::cos(gamma);
  }
  if (c.law == lub::ForceLaw::finite_reynolds) {
    out["active_set_iterations"] = solver.stats().active_set_iterations;
    out["cavitated_cells"] = solver.stats().cavitated_cells;
    out["converged"] = solver.stats().converged;
  }
  out["warnings"] = warnings;
  std::cout << out.dump(2) << "\n";
  return 0;
}

int run_steady(int argc, char** argv) {
  std::set<std::string> flags = kCommonFlags;
  flags.insert({"--load-N", "--speed-rpm"});
  const Args a(argc, argv, 2, flags, {"--groove", "--strict"});
  const Common c = read_common(a);
  lub::SteadyBearingInput in;
  in.law = c.law;
  in.finite = c.finite;
  in.geometry = c.geometry;
  in.viscosity_Pa_s = c.viscosity;
  in.load_N = a.number("--load-N", lub::is_positive_input, lub::positive_rule("N"));
  const double rpm = a.number("--speed-rpm", lub::is_journal_speed, std::string(lub::kJournalSpeedRule));
  in.speed_rad_s = rpm * 2.0 * kPi / 60.0;
  std::vector<std::string> warnings = warnings_of(c);
  if (auto w = lub::implausible_speed_rpm("--speed-rpm", rpm)) warnings.push_back(*w);
  if (refuse_implausible(warnings, a.has("--strict"))) return 2;
  const lub::SteadyBearingResult r = lub::solve_steady_bearing(in);
  nlohmann::json out = describe(c);
  lub::report_steady_bearing(out, in, rpm, r);
  out["warnings"] = warnings;
  std::cout << out.dump(2) << "\n";
  return r.converged ? 0 : 3;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 2) {
    std::cerr << "lubbearing: a command is required (force or steady)\n\n" << usage();
    return 2;
  }
  const std::string cmd = argv[1];
  if (cmd == "-h" || cmd == "--help") {
    std::cout << usage();
    return 0;
  }
  try {
    if (cmd == "force") return run_force(argc, argv);
    if (cmd == "steady") return run_steady(argc, argv);
    throw UsageError("unknown command " + cmd + " (must be force or steady)");
  } catch (const UsageError& e) {
    std::cerr << "lubbearing: " << e.what() << "\n\n" << usage();
    return 2;
  } catch (const std::exception& e) {  // e.g. a solver option rejected by the library
    std::cerr << "lubbearing: " << e.what() << "\n";
    return 2;
  }
}
