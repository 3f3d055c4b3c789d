// lubsweep's command line (CLI11): the options, their help as CLI11 generates it (the man
// page is help2man's reading of it), and the checks of what goes together.
#include <CLI/CLI.hpp>
#include <fmt/format.h>

#include <cmath>
#include <cstdlib>
#include <string>
#include <vector>

#include "lub/io/data_path.hpp"
#include "lub/run/run_io.hpp"
#include "lub/sweep/sweep.hpp"

namespace lub::sweep {

namespace {

// The files named here are the repository's or the installed ones (lub::data_path).
std::string description() {
  return "lubsweep: runs every case of GRID.json (" + data_path("docs/guide/grids.md") + "; examples in " +
         data_path("configs/grids/") +
         ")\n"
         "and writes STUDY.h5: /cases (one row per case: axis values, status, metrics, solver statistics),\n"
         "/grids (case ids over each sub-grid's axes, with dimension scales, and the results over them),\n"
         "/scene and /scene_patches (each case's scene as a JSON Patch of the root attribute\n"
         "reference_scene), /series (the channels a case keeps). Every rank computes, rank 0 included;\n"
         "rank 0 alone writes the file. A study runs as\n"
         "\n"
         "  mpirun -np N lubsweep GRID.json -o STUDY.h5 [options]\n"
         "\n"
         "its table prints with\n"
         "\n"
         "  lubsweep --summary STUDY.h5\n"
         "\n"
         "and its HTML report (a page readable offline) is written with\n"
         "\n"
         "  lubsweep report STUDY.h5 -o report.html [--baseline BASELINE.csv]\n"
         "\n"
         "and cases added where it learns most (between neighbours whose labels differ, or whose metrics\n"
         "change faster than their sensitivities predict) with\n"
         "\n"
         "  mpirun -np N lubsweep refine STUDY.h5 --budget K\n";
}

const char* const kFooter =
    "Exit status: 0 the study is complete (a case that could not be integrated is a\n"
    "result: recorded with its status and message); 3 it stopped early (on_failure =\n"
    "abort): re-run to resume; 2 bad input (grid, options, output: nothing written);\n"
    "1 the file could not be written; 130/143 interrupted (SIGINT/SIGTERM): every case\n"
    "finished is saved, re-run to resume.";

std::string version_line() {
  return "lubsweep " + program_version() + " (revision " + build_revision() + ", " + LUB_BUILD_TYPE + " build)\n";
}

/// The subcommand `refine` (lub/sweep/refine.hpp).
void add_refine(CLI::App& app, Options& o) {
  CLI::App* refine = app.add_subcommand(
      "refine", "add cases where a study learns most (see 'lubsweep refine --help')");
  refine->description(
      "lubsweep refine: adds to STUDY.h5 at most K cases, each at the midpoint of two lattice neighbours\n"
      "whose classification or below_safe_film differ, or whose steady metric changes faster than its\n"
      "sensitivities predict (by more than its error bars and --metric-tolerance of its size); in rounds, the\n"
      "halves of a refined edge scored again. The cases go to /refinement/cases (the columns of /cases, the\n"
      "edge refined, its round and score); /cases, /grids and /lattice are left as they are. Run again (after\n"
      "a kill, or with a larger --budget) it continues; any number of ranks gives the same cases\n"
      "(docs/guide/lubsweep.md, Refining a study):\n"
      "\n"
      "  mpirun -np N lubsweep refine STUDY.h5 --budget K [--metric-tolerance R]");
  refine->footer(
      "Exit status: 0 done (or the budget already spent, or nothing left to refine); 2 bad input (no study\n"
      "file, not a complete study, a bad option, a /refinement of another tolerance or build: the file\n"
      "untouched); 1 the file could not be written; 130/143 interrupted: re-run to resume.");
  refine->add_option("study", o.refine_study, "the study file")->required()->type_name("STUDY.h5");
  refine->add_option("--budget", o.refine_budget, "the most cases /refinement/cases may hold (at least 1)")
      ->required()
      ->type_name("K");
  refine->add_option("--metric-tolerance", o.refine_tolerance,
                     "the metric criterion's allowance beyond the error bars, a fraction of the metric (default "
                     "0.05)")
      ->type_name("R");
  refine->add_flag("-q,--quiet", o.quiet, "no progress lines on stderr");
  refine->set_help_flag("-h,--help", "print this text and exit");
  refine->callback([&o] { o.refine = true; });
}

/// The options of `o` on `app` (`version` for --version).
void add_options(CLI::App& app, Options& o, bool& version) {
  app.footer(kFooter);
  app.set_help_flag("-h,--help", "print this text and exit");
  app.add_option("grid", o.grid, "the grid file (required unless --summary)")->type_name("GRID.json");
  app.add_option("-o,--output", o.output,
                 "the study file (required). If it exists and is a study file, the cases it already holds "
                 "(matched by the hash of their scene) are not run again: re-running a killed sweep resumes it")
      ->type_name("STUDY.h5");
  app.add_flag("--restart", o.restart, "ignore an existing output file and start afresh");
  app.add_flag("--drop-other-cases", o.drop_other_cases,
               "resume, dropping the file's rows that are not cases of this grid (without it such a file is "
               "refused: exit 2)");
  app.add_flag("--retry-failed", o.retry_failed, "run again the cases the file records as not ok");
  app.add_flag("--check", o.check, "validate the grid and list its cases; run nothing");
  app.add_flag("--strict", o.strict,
               "a plausibility warning (a viscosity, clearance or speed that looks like a unit slip) is an "
               "error: exit 2, nothing written");
  app.add_option("--summary", o.summary_of, "print the study's table and exit")->type_name("STUDY.h5");
  app.add_flag_callback("--no-summary", [&o] { o.summary = false; },
                        "no table at the end (by default the study's table is printed)");
  app.add_flag("-q,--quiet", o.quiet, "no progress lines on stderr");
  app.add_flag("--version", version, "print the version, revision and build type and exit");
  app.require_subcommand(0, 1);
  CLI::App* report = app.add_subcommand(
      "report",
      "write a study's self-contained HTML report (see 'lubsweep report --help')");
  report->description(
      "lubsweep report: writes STUDY.h5's report as one HTML file readable offline: the summary table\n"
      "(sortable, filterable), the classification map and each steady metric over every sub-grid with\n"
      "error bars, each case's orbit, film and reaction, the bifurcation edges, the solver statistics;\n"
      "with --baseline the nightly comparison (each metric within or outside its tolerance). It runs\n"
      "/usr/bin/python3 -m lubjoint.report (no MPI; docs/guide/lubsweep.md).");
  report->footer(
      "Exit status: 0 written; 2 bad input (no study file, not a study file, a bad baseline or -o:\n"
      "nothing written); 1 Python, the module lubjoint or Chart.js (libjs-chart.js) not found.");
  report->add_option("study", o.report_study, "the study file")->required()->type_name("STUDY.h5");
  report->add_option("-o,--output", o.report_output, "the HTML file to write")->required()->type_name("HTML");
  report->add_option("--baseline", o.report_baseline,
                     "a baseline CSV (tests/baselines/paper.csv): each metric against its tolerance")
      ->type_name("CSV");
  report->set_help_flag("-h,--help", "print this text and exit");
  report->callback([&o] { o.report = true; });
  add_refine(app, o);
}

/// What goes together, once parsed: an error message, or nullopt.
std::optional<std::string> check(Options& o) {
  if (o.report) {
    if (!o.grid.empty() || !o.output.empty() || !o.summary_of.empty())
      return "report takes a study file, -o HTML and --baseline only (lubsweep report STUDY.h5 -o report.html)";
    return std::nullopt;
  }
  if (o.refine) {
    if (!o.grid.empty() || !o.output.empty() || !o.summary_of.empty())
      return "refine takes a study file, --budget and --metric-tolerance only (lubsweep refine STUDY.h5 --budget K)";
    if (o.refine_budget < 1)
      return "refine: --budget = " + std::to_string(o.refine_budget) +
             ": must be at least 1 (the most cases the refinement may hold)";
    if (!(o.refine_tolerance >= 0.0) || !std::isfinite(o.refine_tolerance))
      return "refine: --metric-tolerance = " + fmt::format("{:g}", o.refine_tolerance) +
             ": must be a finite number >= 0 (a fraction of the metric: 0.05 is 5 %)";
    if (const char* k = std::getenv("LUBSWEEP_TEST_KILL_AFTER")) o.kill_after = std::atol(k);
    return std::nullopt;
  }
  if (!o.summary_of.empty()) {
    if (!o.grid.empty() || !o.output.empty()) return "--summary takes only a study file";
    return std::nullopt;
  }
  if (o.grid.empty()) return "no grid given";
  if (o.output.empty() && !o.check) return "no output file given (-o STUDY.h5)";
  if (o.restart && o.retry_failed) return "--restart and --retry-failed exclude each other";
  if (const char* k = std::getenv("LUBSWEEP_TEST_KILL_AFTER")) o.kill_after = std::atol(k);
  return std::nullopt;
}

}  // namespace

std::optional<std::string> parse_options(const std::vector<std::string>& args, Options& o, bool& help,
                                         std::string& help_text) {
  CLI::App app(description(), "lubsweep");
  help = false;
  bool version = false;
  add_options(app, o, version);
  try {
    app.parse(std::vector<std::string>(args.rbegin(), args.rend()));  // CLI11 wants them last first
  } catch (const CLI::CallForHelp&) {
    help = true;
    const CLI::App* report = app.get_subcommand("report");
    const CLI::App* refine = app.get_subcommand("refine");
    help_text = report->parsed() ? report->help() : refine->parsed() ? refine->help() : app.help();
    return std::nullopt;
  } catch (const CLI::ExtrasError& e) {
    // The extras are the main command's, or the subcommand's (recursive: `report ... --check`).
    const std::vector<std::string> extras = app.remaining(true);
    if (extras.empty()) return std::string(e.what());
    const std::string& extra = extras.front();
    const auto of_subcommand = [&](const std::string& name, const std::string& study) {
      return name + ": " + (!extra.empty() && extra[0] == '-' ? "unknown option " + extra
                                                               : "more than one study given (" + study + ", " + extra + ")");
    };
    if (app.get_subcommand("refine")->parsed()) return of_subcommand("refine", o.refine_study);
    if (app.get_subcommand("report")->parsed()) return of_subcommand("report", o.report_study);
    if (!extra.empty() && extra[0] == '-') return "unknown option " + extra;
    return "more than one grid given (" + o.grid + ", " + extra + ")";
  } catch (const CLI::ParseError& e) {
    return std::string(e.what());
  }
  if (version) {
    help = true;
    help_text = version_line();
    return std::nullopt;
  }
  return check(o);
}

}  // namespace lub::sweep
