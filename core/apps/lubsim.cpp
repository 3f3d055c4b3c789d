// lubsim: runs one scene and writes its run file.
//
//   lubsim SCENE.json -o RUN.h5 [--set POINTER=VALUE ...] [--strict] [--quiet]
//   lubsim --help;  lubsim --version
//
// Exit status: 0 run completed; 2 bad input, or implausible input under --strict (nothing
// written); 3 the run could not be
// completed (film collapse, solver failure, budget): the file is written with its status.
#include <CLI/CLI.hpp>

#include <cstdio>
#include <exception>
#include <fstream>
#include <iostream>
#include <string>
#include <vector>

#include "lub/io/output_path.hpp"
#include "lub/run/orbit.hpp"
#include "lub/run/run.hpp"
#include "lub/run/run_io.hpp"
#include "lub/scene/scene.hpp"

namespace {

const char* const kDescription =
    "lubsim: runs one scene (format: configs/scene.schema.json) and writes RUN.h5: /series (the\n"
    "scene's channels, each with a units attribute), /orbit (the periodic orbit, when found by\n"
    "shooting), /metrics, /solver, /cycles (per-cycle extremes), and the scene, version, revision,\n"
    "status, warnings and notes as root attributes.";

const char* const kFooter =
    "Plausibility warnings go to stderr, once, and into the run file's root attribute `warnings`;\n"
    "validity notes (a force law outside its assumptions) likewise, into `notes`.\n"
    "Exit status: 0 completed, 2 bad input (no file written), 3 run not completed (file written\n"
    "with its status and message).";

// The one error format of the three programs: "PROGRAM: message" on stderr and, for a usage
// error, where the usage is.
int usage_error(const std::string& msg) {
  std::cerr << "lubsim: " << msg << "\nrun 'lubsim --help' for usage\n";
  return 2;
}

struct Options {
  std::string scene_path, out_path;
  std::vector<std::string> sets;
  std::vector<std::string> sensitivities;  ///< JSON Pointers of scene numbers
  bool quiet = false, strict = false, version = false;
};

// Parses argv into `o`. Returns -1 to go on, or the exit status (help, version, usage error).
int parse_options(int argc, char** argv, Options& o) {
  CLI::App app(kDescription, "lubsim");
  app.footer(kFooter);
  app.allow_extras();
  app.add_option("scene", o.scene_path, "the scene file (required)")->type_name("SCENE.json");
  app.add_option("-o,--output", o.out_path, "the run file to write (required)")->type_name("RUN.h5")->take_last();
  app.add_option("--set", o.sets,
                 "override one scene value by JSON Pointer (RFC 6901), repeatable, applied in order; VALUE is "
                 "parsed as JSON, a bare word is a string, e.g. --set /joints/3/viscosity_Pa_s=0.04 "
                 "--set /joints/3/force_law=frene_long; an element of joints, bodies, ... by its index or its name: "
                 "/joints/rod_slider/viscosity_Pa_s")
      ->type_name("POINTER=VALUE")
      ->allow_extra_args(false);
  app.add_option("--sensitivity", o.sensitivities,
                 "the located orbit's steady metrics differentiated with respect to this scene number (JSON "
                 "Pointer, repeatable), e.g. --sensitivity /joints/3/viscosity_Pa_s; written to the run file's "
                 "/sensitivities (docs/theory/sensitivities.md)")
      ->type_name("POINTER")
      ->allow_extra_args(false);
  app.add_flag("--strict", o.strict,
               "an implausible value (a viscosity, clearance or speed that looks like a unit slip) is an "
               "error (exit 2, nothing written), not a warning");
  app.add_flag("-q,--quiet", o.quiet, "no summary on stdout");
  app.add_flag("--version", o.version, "print the version, revision and build type and exit");
  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp&) {
    std::cout << app.help();
    return 0;
  } catch (const CLI::ParseError& e) {
    return usage_error(e.what());
  }
  if (o.version) {
    std::cout << "lubsim " << lub::program_version() << " (revision " << lub::build_revision() << ", "
              << LUB_BUILD_TYPE << " build)\n";
    return 0;
  }
  if (const auto extra = app.remaining(); !extra.empty()) {
    if (extra.front().rfind('-', 0) == 0) return usage_error("unknown option " + extra.front());
    return usage_error("more than one scene given (" + o.scene_path + ", " + extra.front() + ")");
  }
  if (o.scene_path.empty()) return usage_error("no scene given");
  if (o.out_path.empty()) return usage_error("no output file given (-o RUN.h5)");
  return -1;
}

}  // namespace

void print_sensitivities(const std::vector<lub::Sensitivity>& sens) {
  for (const lub::Sensitivity& s : sens) {
    std::printf("sensitivity to %s = %.6g %s: %s%s%s (%lld periods)\n", s.name.c_str(), s.value, s.unit.c_str(),
                s.ok ? "ok" : "failed", s.message.empty() ? "" : ": ", s.message.c_str(), s.periods);
    if (!s.ok) continue;
    const auto& metrics = lub::steady_metrics();
    for (std::size_t i = 0; i < metrics.size(); ++i)
      std::printf("  d %-30s %+.6g ± %.2g %s\n", metrics[i].name, s.d_metric[i], s.d_metric_error[i],
                  lub::derivative_unit(metrics[i].unit, s.unit).c_str());
  }
}

int main(int argc, char** argv) {
  Options o;
  if (const int status = parse_options(argc, argv, o); status >= 0) return status;
  const std::string& scene_path = o.scene_path;
  const std::string& out_path = o.out_path;
  const std::vector<std::string>& sets = o.sets;
  const bool quiet = o.quiet, strict = o.strict;
  // The output path first: a run that could not be written is refused before any work.
  if (const auto problem = lub::output_path_problem(out_path)) {
    std::cerr << "lubsim: " << *problem << "\n";
    return 2;
  }

  lub::Scene scene;
  std::string scene_text;
  std::vector<lub::SensitivityParameter> sens_params;
  try {
    nlohmann::json doc = lub::parse_json(lub::read_text_file(scene_path));  // messages: no path, added below
    for (const auto& s : sets) lub::apply_override(doc, s);
    scene = lub::parse_scene(doc);
    scene_text = doc.dump(2);
    sens_params = lub::sensitivity_parameters(doc, o.sensitivities, "--sensitivity");
  } catch (const lub::InputError& e) {
    std::cerr << "lubsim: " << scene_path << ": " << e.what() << "\n";
    return 2;
  }
  // Plausibility (lub/bearing/plausibility.hpp): warned once, before the run; refused under --strict.
  for (const std::string& w : scene.warnings)
    std::cerr << "lubsim: " << (strict ? scene_path + ": " : std::string("warning: ")) << w
              << (strict ? "; refused under --strict" : "") << "\n";
  if (strict && !scene.warnings.empty()) return 2;

  lub::RunResult r;
  try {
    r = lub::run_scene(scene);
  } catch (const lub::InputError& e) {  // assembly: the mechanism cannot close
    std::cerr << "lubsim: " << scene_path << ": " << e.what() << "\n";
    return 2;
  }
  std::vector<lub::Sensitivity> sens;
  if (!sens_params.empty()) {
    if (!quiet) std::cerr << "lubsim: sensitivities of the orbit to " << sens_params.size() << " parameter(s)...\n";
    sens = lub::steady_sensitivities(r, sens_params);
  }
  try {
    lub::write_run_file(out_path, scene_text, "lubsim", r, scene.warnings, sens);
  } catch (const std::exception& e) {
    std::cerr << "lubsim: cannot write " << out_path << ": " << e.what() << "\n";
    return 1;
  }
  // Validity notes (lub/bearing/law_validity.hpp): once, after the run; never refused.
  for (const std::string& n : r.notes) std::cerr << "lubsim: note: " << n << "\n";
  if (!quiet) {
    std::printf("status   %s%s%s\n", lub::to_string(r.status).c_str(), r.message.empty() ? "" : ": ",
                r.message.c_str());
    const std::string cls = lub::classification(r);
    const bool orbit = r.status == lub::RunStatus::ok && lub::has_orbit(r.steady.kind);
    std::printf("steady   %s (%s)%s\n", cls.c_str(), std::string(lub::name_of(r.steady.method)).c_str(),
                orbit ? ""
                    : ": the metrics below are a transient's, not a steady cycle's (docs/theory/steady-cycles.md)");
    if (r.steady.method == lub::SteadyCycleMethod::shooting)
      std::printf("metrics  (the periodic orbit, %d cycles)\n", scene.simulation.metric_cycles);
    else if (r.steady.method == lub::SteadyCycleMethod::slow_flow)
      std::printf("metrics  (%d cycles where the slow flow got to, about %.0f cycles after the transient's %d)\n",
                  scene.simulation.metric_cycles, r.steady.slow_flow_cycles, r.metrics.cycles_run);
    else
      std::printf("metrics  (last %d of %d cycles)\n", std::min<int>(scene.simulation.metric_cycles, r.metrics.cycles_run),
                  r.metrics.cycles_run);
    for (const auto& f : lub::metric_fields())
      std::printf("  %-34s %.6g %s\n", f.name.c_str(), f.get(r), f.unit.c_str());
    const lub::SolverSettingNames names = lub::setting_names(r.stats);
    std::printf("solver   %s (%s) rtol %.3g atol %.3g m (per state: docs/theory/formulations.md) jacobian %s\n",
                names.method.c_str(), names.formulation.c_str(), r.stats.rtol, r.stats.atol, names.jacobian.c_str());
    for (const auto& f : lub::solver_fields())
      std::printf("  %-34s %.6g %s\n", f.name.c_str(), f.get(r), f.unit.c_str());
    print_sensitivities(sens);
    std::printf("wrote    %s\n", out_path.c_str());
  }
  return r.status == lub::RunStatus::ok ? 0 : 3;
}
