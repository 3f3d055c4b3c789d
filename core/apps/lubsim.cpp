// lubsim: runs one scene and writes its run file.
//
//   lubsim SCENE.json -o RUN.h5 [--set POINTER=VALUE ...] [--strict] [--quiet]
//   lubsim SCENE.json [--set ...] --check | --print-scene   (nothing run, nothing written)
//   lubsim --help;  lubsim --version
//
// Exit status: 0 run completed (or the scene is valid: --check, --print-scene); 2 bad input,
// or implausible input under --strict (nothing written); 3 the run could not be
// completed (film collapse, solver failure, budget): the file is written with its status.
#include <CLI/CLI.hpp>

#include <cstdio>
#include <exception>
#include <fstream>
#include <iostream>
#include <string>
#include <vector>

#include "lub/io/data_path.hpp"
#include "lub/io/output_path.hpp"
#include "lub/mechanism/builder.hpp"
#include "lub/run/orbit.hpp"
#include "lub/run/run.hpp"
#include "lub/run/run_io.hpp"
#include "lub/scene/scene.hpp"

namespace {

// The files named here are the repository's or the installed ones (lub::data_path).
std::string description() {
  return "lubsim: runs one scene (format: " + lub::data_path("configs/scene.schema.json") +
         ") and writes RUN.h5:\n"
         "/series (the scene's channels, each with a units attribute), /orbit (the periodic orbit,\n"
         "when found by shooting), /metrics, /solver, /cycles (per-cycle extremes), and the scene,\n"
         "version, revision, status, warnings and notes as root attributes.\nExample scenes: " +
         lub::data_path("configs/scenes/");
}

const char* const kFooter =
    "Plausibility warnings go to stderr, once, and into the run file's root attribute `warnings`;\n"
    "validity notes (a force law outside its assumptions) likewise, into `notes`.\n"
    "Exit status: 0 completed (--check, --print-scene: the scene is valid), 2 bad input (no file\n"
    "written), 3 run not completed (file written with its status and message).";

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
  bool check = false, print_scene = false;  ///< validate only / print the effective scene: no run, no file
};

// Parses argv into `o`. Returns -1 to go on, or the exit status (help, version, usage error).
int parse_options(int argc, char** argv, Options& o) {
  CLI::App app(description(), "lubsim");
  app.footer(kFooter);
  app.allow_extras();
  app.add_option("scene", o.scene_path, "the scene file (required)")->type_name("SCENE.json");
  app.add_option("-o,--output", o.out_path, "the run file to write (required, but for --check and --print-scene)")->type_name("RUN.h5")->take_last();
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
                 "/sensitivities (" + lub::data_path("docs/theory/sensitivities.md") + ")")
      ->type_name("POINTER")
      ->allow_extra_args(false);
  app.add_flag("--strict", o.strict,
               "an implausible value (a viscosity, clearance or speed that looks like a unit slip) is an "
               "error (exit 2, nothing written), not a warning");
  app.add_flag("--check", o.check,
               "parse and validate the scene (after --set, and its initial assembly), print \"ok\" and its "
               "plausibility warnings and validity notes, and exit: 0 valid, 2 not; nothing is run or written "
               "(-o not needed)");
  app.add_flag("--print-scene", o.print_scene,
               "print the effective scene (the file after --set, validated) as JSON on stdout and exit 0; "
               "nothing is run or written (-o not needed)");
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
  if (o.check && o.print_scene) return usage_error("--check and --print-scene exclude each other");
  if (o.out_path.empty() && !o.check && !o.print_scene) return usage_error("no output file given (-o RUN.h5)");
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

// The lines on stdout after a run: status, steady cycle, metrics, solver, sensitivities.
void print_run(const lub::Scene& scene, const lub::RunResult& r, const std::vector<lub::Sensitivity>& sens,
               const std::string& out_path) {
  std::printf("status   %s%s%s\n", lub::to_string(r.status).c_str(), r.message.empty() ? "" : ": ", r.message.c_str());
  const std::string cls = lub::classification(r);
  const bool orbit = r.status == lub::RunStatus::ok && lub::has_orbit(r.steady.kind);
  std::printf("steady   %s (%s)%s\n", cls.c_str(), std::string(lub::name_of(r.steady.method)).c_str(),
              orbit ? "" : (": the metrics below are a transient's, not a steady cycle's (" +
                            lub::data_path("docs/theory/steady-cycles.md") + ")").c_str());
  if (r.steady.method == lub::SteadyCycleMethod::shooting)
    std::printf("metrics  (the periodic orbit, %d cycles)\n", scene.simulation.metric_cycles);
  else if (r.steady.method == lub::SteadyCycleMethod::slow_flow)
    std::printf("metrics  (%d cycles where the slow flow got to, about %.0f cycles after the transient's %d)\n",
                scene.simulation.metric_cycles, r.steady.slow_flow_cycles, r.metrics.cycles_run);
  else
    std::printf("metrics  (last %d of %d cycles)\n", std::min<int>(scene.simulation.metric_cycles, r.metrics.cycles_run),
                r.metrics.cycles_run);
  for (const auto& f : lub::metric_fields()) std::printf("  %-34s %.6g %s\n", f.name.c_str(), f.get(r), f.unit.c_str());
  const lub::SolverSettingNames names = lub::setting_names(r.stats);
  std::printf("solver   %s (%s) rtol %.3g atol %.3g m (per state: %s) jacobian %s\n", names.method.c_str(),
              names.formulation.c_str(), r.stats.rtol, r.stats.atol,
              lub::data_path("docs/theory/formulations.md").c_str(), names.jacobian.c_str());
  for (const auto& f : lub::solver_fields()) std::printf("  %-34s %.6g %s\n", f.name.c_str(), f.get(r), f.unit.c_str());
  print_sensitivities(sens);
  std::printf("wrote    %s\n", out_path.c_str());
}

namespace {

// Bad input: "lubsim: SCENE: message" on stderr, exit status 2.
int bad_input(const Options& o, const std::string& message) {
  std::cerr << "lubsim: " << o.scene_path << ": " << message << "\n";
  return 2;
}

struct LoadedScene {
  lub::Scene scene;
  std::string text;  ///< the effective scene's JSON (the file after --set)
  std::vector<lub::SensitivityParameter> sensitivities;
};

// The scene file with the --set overrides in order, validated, and the --sensitivity
// parameters. Returns -1 to go on, or the exit status (bad input, or a warning under --strict).
int load_scene(const Options& o, LoadedScene& loaded) {
  try {
    nlohmann::json doc = lub::parse_json(lub::read_text_file(o.scene_path));  // messages: no path, added once
    for (const auto& s : o.sets) lub::apply_override(doc, s);
    loaded.scene = lub::parse_scene(doc);
    loaded.text = doc.dump(2);
    loaded.sensitivities = lub::sensitivity_parameters(doc, o.sensitivities, "--sensitivity");
  } catch (const lub::InputError& e) {
    return bad_input(o, e.what());
  }
  // Plausibility (lub/bearing/plausibility.hpp): warned once, before any work; refused under --strict.
  for (const std::string& w : loaded.scene.warnings)
    std::cerr << "lubsim: " << (o.strict ? o.scene_path + ": " : std::string("warning: ")) << w
              << (o.strict ? "; refused under --strict" : "") << "\n";
  if (o.strict && !loaded.scene.warnings.empty()) return 2;
  return -1;
}

// --check: the scene is valid if, besides its rules, its mechanism assembles (as a run's
// first step does); "ok" on stdout, the validity notes on stderr as after a run.
int check_scene(const Options& o, const lub::Scene& scene) {
  try {
    const lub::Model model = lub::build_model(scene);
    Eigen::VectorXd q, v;
    lub::assemble_initial_state(model, scene, 0.0, q, v);
  } catch (const lub::InputError& e) {  // assembly: the mechanism cannot close
    return bad_input(o, e.what());
  }
  for (const std::string& n : scene.validity_notes) std::cerr << "lubsim: note: " << n << "\n";
  std::printf("ok\n");
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  Options o;
  if (const int status = parse_options(argc, argv, o); status >= 0) return status;
  // The output path first: a run that could not be written is refused before any work.
  if (!o.check && !o.print_scene)
    if (const auto problem = lub::output_path_problem(o.out_path)) {
      std::cerr << "lubsim: " << *problem << "\n";
      return 2;
    }
  LoadedScene in;
  if (const int status = load_scene(o, in); status >= 0) return status;
  if (o.check) return check_scene(o, in.scene);
  if (o.print_scene) {
    std::printf("%s\n", in.text.c_str());
    return 0;
  }

  lub::RunResult r;
  try {
    r = lub::run_scene(in.scene);
  } catch (const lub::InputError& e) {  // assembly: the mechanism cannot close
    return bad_input(o, e.what());
  }
  std::vector<lub::Sensitivity> sens;
  if (!in.sensitivities.empty()) {
    if (!o.quiet) std::cerr << "lubsim: sensitivities of the orbit to " << in.sensitivities.size() << " parameter(s)...\n";
    sens = lub::steady_sensitivities(r, in.sensitivities);
  }
  try {
    lub::write_run_file(o.out_path, in.text, "lubsim", r, in.scene.warnings, sens);
  } catch (const std::exception& e) {
    std::cerr << "lubsim: cannot write " << o.out_path << ": " << e.what() << "\n";
    return 1;
  }
  // Validity notes (lub/bearing/law_validity.hpp): once, after the run; never refused.
  for (const std::string& n : r.notes) std::cerr << "lubsim: note: " << n << "\n";
  if (!o.quiet) print_run(in.scene, r, sens, o.out_path);
  return r.status == lub::RunStatus::ok ? 0 : 3;
}
