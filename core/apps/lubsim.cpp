// lubsim: runs one scene and writes its run file.
//
//   lubsim SCENE.json -o RUN.h5 [--set POINTER=VALUE ...] [--strict] [--quiet]
//
// Exit status: 0 run completed; 2 bad input, or implausible input under --strict (nothing
// written); 3 the run could not be
// completed (film collapse, solver failure, budget): the file is written with its status.
#include <cstdio>
#include <exception>
#include <fstream>
#include <iostream>
#include <string>
#include <vector>

#include "lub/io/output_path.hpp"
#include "lub/run/run.hpp"
#include "lub/run/run_io.hpp"
#include "lub/scene/scene.hpp"

namespace {

const char* kUsage =
    "usage: lubsim SCENE.json -o RUN.h5 [--set POINTER=VALUE ...] [--strict] [--quiet]\n"
    "\n"
    "Runs one scene (see README, \"Scene format\") and writes RUN.h5: /series (the\n"
    "scene's channels, each with a units attribute), /metrics, /solver, /cycles, and\n"
    "the scene, version and status as root attributes.\n"
    "\n"
    "  -o, --output RUN.h5     the run file to write (required)\n"
    "  --set POINTER=VALUE     override one scene value by JSON Pointer (RFC 6901);\n"
    "                          VALUE is parsed as JSON, a bare word is a string, e.g.\n"
    "                          --set /joints/3/viscosity_Pa_s=0.04\n"
    "                          --set /joints/3/force_law=frene_long\n"
    "  --strict                an implausible value (README \"Scene format\", plausible\n"
    "                          ranges: a viscosity, clearance or speed that looks like a\n"
    "                          unit slip) is an error, not a warning\n"
    "  -q, --quiet             no summary on stdout\n"
    "  --version               print the version and exit\n"
    "\n"
    "Plausibility warnings go to stderr, once, and into the run file's root attribute\n"
    "`warnings`.\n"
    "\n"
    "Exit status: 0 completed, 2 bad input (no file written), 3 run not completed\n"
    "(file written with its status and message).\n";

int usage_error(const std::string& msg) {
  std::cerr << "lubsim: " << msg << "\n\n" << kUsage;
  return 2;
}

}  // namespace

int main(int argc, char** argv) {
  std::string scene_path, out_path;
  std::vector<std::string> sets;
  bool quiet = false, strict = false;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "-h" || a == "--help") {
      std::cout << kUsage;
      return 0;
    } else if (a == "--version") {
      std::cout << "lubsim " << lub::program_version() << " (" << lub::build_revision() << ")\n";
      return 0;
    } else if (a == "-o" || a == "--output") {
      if (++i >= argc) return usage_error(a + " needs a file name");
      out_path = argv[i];
    } else if (a == "--set") {
      if (++i >= argc) return usage_error("--set needs POINTER=VALUE");
      sets.push_back(argv[i]);
    } else if (a.rfind("--set=", 0) == 0) {
      sets.push_back(a.substr(6));
    } else if (a == "-q" || a == "--quiet") {
      quiet = true;
    } else if (a == "--strict") {
      strict = true;
    } else if (!a.empty() && a[0] == '-') {
      return usage_error("unknown option " + a);
    } else if (scene_path.empty()) {
      scene_path = a;
    } else {
      return usage_error("more than one scene given (" + scene_path + ", " + a + ")");
    }
  }
  if (scene_path.empty()) return usage_error("no scene given");
  if (out_path.empty()) return usage_error("no output file given (-o RUN.h5)");
  // The output path first: a run that could not be written is refused before any work.
  if (const auto problem = lub::output_path_problem(out_path)) {
    std::cerr << "lubsim: " << *problem << "\n";
    return 2;
  }

  lub::Scene scene;
  std::string scene_text;
  try {
    nlohmann::json doc = lub::read_json_file(scene_path);
    for (const auto& s : sets) lub::apply_override(doc, s);
    scene = lub::parse_scene(doc);
    scene_text = doc.dump(2);
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
  try {
    lub::write_run_file(out_path, scene_text, "lubsim", r, scene.warnings);
  } catch (const std::exception& e) {
    std::cerr << "lubsim: cannot write " << out_path << ": " << e.what() << "\n";
    return 1;
  }
  if (!quiet) {
    std::printf("status   %s%s%s\n", lub::to_string(r.status).c_str(), r.message.empty() ? "" : ": ",
                r.message.c_str());
    const std::string cls = lub::classification(r);
    std::printf("steady   %s (%s)%s\n", cls.c_str(), r.steady.method.c_str(),
                cls == "periodic" || cls == "periodic_unstable"
                    ? ""
                    : ": the metrics below are a transient's, not a steady cycle's (README \"Steady cycles\")");
    if (r.steady.method == "shooting")
      std::printf("metrics  (the periodic orbit, %d cycles)\n", scene.simulation.metric_cycles);
    else
      std::printf("metrics  (last %d of %d cycles)\n", std::min<int>(scene.simulation.metric_cycles, r.metrics.cycles_run),
                  r.metrics.cycles_run);
    for (const auto& f : lub::metric_fields())
      std::printf("  %-34s %.6g %s\n", f.name.c_str(), f.get(r), f.unit.c_str());
    std::printf("solver   %s (%s) rtol %.3g atol %.3g m (per state, README \"Integration\") jacobian %s\n",
                r.stats.method.c_str(), r.stats.formulation.c_str(), r.stats.rtol, r.stats.atol,
                r.stats.jacobian.c_str());
    for (const auto& f : lub::solver_fields())
      std::printf("  %-34s %.6g %s\n", f.name.c_str(), f.get(r), f.unit.c_str());
    std::printf("wrote    %s\n", out_path.c_str());
  }
  return r.status == lub::RunStatus::ok ? 0 : 3;
}
