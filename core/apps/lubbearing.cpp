// lubbearing: the bearing alone, for designers and for checking a force law.
//
//   lubbearing force  --model M --eps E --eps-dot ED --omega W --gamma-dot GD
//                     --radius-m R --clearance-m C --length-m L --viscosity-Pa-s MU [--gamma G]
//                     [finite_reynolds options] [--strict]
//   lubbearing steady --model M --load-N W --speed-rpm N
//                     --radius-m R --clearance-m C --length-m L --viscosity-Pa-s MU
//                     [finite_reynolds options] [--strict]
//   lubbearing --version;  lubbearing [force|steady] --help
//
// Prints one JSON object on stdout, with the plausibility warnings (lub/bearing/plausibility.hpp)
// in "warnings" (also printed on stderr). Exit status: 0 done, 2 bad arguments (message on
// stderr naming the argument, its value and the rule; or an implausible one under --strict), 3 a steady state that does not exist (the
// JSON says why).
#include <CLI/CLI.hpp>
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

struct UsageError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// "--name = value: rule", the house style for bad input.
[[noreturn]] void bad(const std::string& name, const std::string& value, const std::string& rule) {
  throw UsageError(name + " = " + value + ": " + rule);
}

// The values given on the command line (parsed by CLI11 as text), checked here so that a
// message names the argument, its value and the rule.
class Args {
 public:
  Args(std::map<std::string, std::string> values, std::set<std::string> bare)
      : values_(std::move(values)), bare_(std::move(bare)) {}
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

int run_force(const Args& a) {
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

int run_steady(const Args& a) {
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

// One subcommand's command line: every value kept as text (Args checks it), every flag a bool.
struct Command {
  CLI::App* app = nullptr;
  std::map<std::string, std::string> text;  // CLI11 writes here (std::map: stable addresses)
  std::map<std::string, CLI::Option*> given;
  std::map<std::string, bool> flag;

  void value(const std::string& name, const std::string& type, const std::string& help,
             const std::string& group = "Options") {
    // One value per occurrence; a second occurrence is refused by args() ("given twice").
    given[name] = app->add_option(name, text[name], help)->type_name(type)->take_last()->group(group);
  }
  void option_flag(const std::string& name, const std::string& help, const std::string& group = "Options") {
    app->add_flag(name, flag[name], help)->group(group);
  }
  Args args() const {
    std::map<std::string, std::string> values;
    for (const auto& [name, opt] : given)
      if (opt->count() > 1)
        throw UsageError(name + " given twice");
      else if (opt->count() == 1)
        values[name] = text.at(name);
    std::set<std::string> bare;
    for (const auto& [name, on] : flag)
      if (on) bare.insert(name);
    return Args(values, bare);
  }
};

const char* const kFooter =
    "Prints one JSON object on stdout. Plausibility warnings go to stderr and into the JSON's\n"
    "\"warnings\" (a list). Exit status: 0 done, 2 bad arguments (nothing printed on stdout),\n"
    "3 no steady state (reason in the JSON).";

// The options both commands take: the bearing, the force law and its finite_reynolds options.
void add_common(Command& c) {
  c.value("--model", "M", "force law, one of: " + lub::names_list<lub::ForceLaw>() + " (required)");
  c.value("--radius-m", "R", "journal radius R > 0 [m] (required)");
  c.value("--clearance-m", "C", "radial clearance C > 0 [m] (required)");
  c.value("--length-m", "L", "bearing length L > 0 [m] (required)");
  c.value("--viscosity-Pa-s", "MU", "dynamic viscosity > 0 [Pa s] (required)");
  const std::string fr = "finite_reynolds options (only with --model finite_reynolds)";
  c.value("--cavitation", "C", "one of: " + lub::names_list<lub::Cavitation>() + " (default reynolds)", fr);
  c.value("--n-theta", "N", "cells around the circumference (default 48, " + lub::kReynoldsNThetaRange.rule() + ")", fr);
  c.value("--n-z", "N", "axial nodes over half the length (default 8, " + lub::kReynoldsNZRange.rule() + ")", fr);
  c.option_flag("--groove",
                "ambient pressure along the line of maximum film thickness (Raimondi & Boyd's supply condition)",
                fr);
  c.option_flag("--strict",
                "an implausible value (viscosity outside 1e-4 - 5 Pa s, clearance/radius outside 1e-4 - 0.3, "
                "speed above 50000 rpm: probably a unit slip) is an error (exit 2), not a warning");
  c.app->footer(kFooter);
}

Command force_command(CLI::App& app) {
  Command c;
  c.app = app.add_subcommand(
      "force",
      "Film force on the journal (SI units) at eccentricity ratio E, its rate ED, the journal's angular "
      "velocity W and the rate GD of the line of centres, both relative to the bearing (wedge speed "
      "w = W - 2 GD). Prints radial_N (along the line of centres, outward) and tangential_N (+90 deg); "
      "with --gamma G also x_N, y_N (paper Eqs. 15-16).");
  c.value("--eps", "E", "eccentricity ratio, " + std::string(lub::kFilmEccentricityRatioRule) + " (required)");
  c.value("--eps-dot", "ED", "its rate [1/s] (required)");
  c.value("--omega", "W", "journal angular velocity relative to the bearing [rad/s] (required)");
  c.value("--gamma-dot", "GD", "rate of the line of centres relative to the bearing [rad/s] (required)");
  c.value("--gamma", "G", "line of centres from the x axis [rad]: adds x_N, y_N");
  add_common(c);
  return c;
}

Command steady_command(CLI::App& app) {
  Command c;
  c.app = app.add_subcommand(
      "steady",
      "Equilibrium of a journal turning at N rpm under a constant load W: prints eps, attitude_angle_deg "
      "(load line to line of centres), min_film_thickness_m, sommerfeld_number (R/c)^2 mu N_s/P, "
      "P = W/(L D).");
  c.value("--load-N", "W", "constant load > 0 [N] (required)");
  c.value("--speed-rpm", "N", "journal speed [rpm], " + std::string(lub::kJournalSpeedRule) + " (required)");
  add_common(c);
  return c;
}

// The one error format of the three programs: "PROGRAM: message" on stderr and, for a usage
// error, where the usage is.
int usage_error(const std::string& message, const std::string& command) {
  std::cerr << "lubbearing: " << message << "\nrun 'lubbearing" << (command.empty() ? "" : " " + command)
            << " --help' for usage\n";
  return 2;
}

std::string version_line() {
  return std::string("lubbearing ") + LUB_VERSION + " (revision " + LUB_GIT_REVISION + ", " + LUB_BUILD_TYPE +
         " build)";
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app("lubbearing: the bearing alone, for designers and for checking a force law.", "lubbearing");
  app.footer(kFooter);
  app.require_subcommand(0, 1);
  app.allow_extras();
  bool version = false;
  app.add_flag("--version", version, "print the version, revision and build type and exit");
  Command force = force_command(app);
  Command steady = steady_command(app);
  force.app->allow_extras();
  steady.app->allow_extras();
  const auto command = [&]() -> std::string { return app.get_subcommands().empty() ? "" : app.get_subcommands()[0]->get_name(); };
  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp&) {
    std::cout << app.help();  // the selected command's help, if one is
    return 0;
  } catch (const CLI::ParseError& e) {
    return usage_error(e.what(), command());
  }
  if (version) {
    std::cout << version_line() << "\n";
    return 0;
  }
  if (const auto extra = app.remaining(true); !extra.empty()) {
    if (command().empty() && extra.front().rfind('-', 0) != 0)
      return usage_error("unknown command " + extra.front() + " (must be force or steady)", "");
    return usage_error("unknown argument " + extra.front(), command());
  }
  if (command().empty()) return usage_error("a command is required (force or steady)", "");
  try {
    return force.app->parsed() ? run_force(force.args()) : run_steady(steady.args());
  } catch (const UsageError& e) {
    return usage_error(e.what(), command());
  } catch (const std::exception& e) {  // e.g. a solver option rejected by the library
    std::cerr << "lubbearing: " << e.what() << "\n";
    return 2;
  }
}
