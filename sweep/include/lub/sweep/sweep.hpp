// lubsweep's driver: options (cli.cpp), signals (signals.cpp) and the sweep on MPI_COMM_WORLD
// (sweep.cpp).
//
// Rank 0 validates the grid and the output before any work, then coordinates
// (scheduler.hpp over mpi_transport.hpp): it hands out cases one at a time to whichever
// rank asks, computes cases itself on a worker thread while its main thread serves the
// other ranks, and alone writes the study file. Every case is computed from its own scene,
// so the metrics do not depend on the number of ranks or on which rank ran a case.
#pragma once

#include <optional>
#include <string>
#include <vector>

namespace lub::sweep {

struct Options {
  std::string grid;
  std::string output;
  bool restart = false;       ///< ignore (and overwrite) an existing output file
  bool retry_failed = false;  ///< run again the cases the file records as failed
  bool drop_other_cases = false;  ///< resume a file holding rows of other cases, dropping them
  bool quiet = false;         ///< no progress lines
  bool summary = true;        ///< print the study's table at the end
  std::string summary_of;     ///< --summary FILE: only print FILE's table
  bool check = false;         ///< validate the grid, list its cases, run nothing
  bool strict = false;        ///< --strict: a plausibility warning is an error (exit 2)
  long kill_after = -1;       ///< tests: rank 0 kills itself (SIGKILL) after this many new rows
  bool report = false;        ///< the subcommand `report`: write a study's HTML report, no MPI
  std::string report_study;   ///< report: the study file
  std::string report_output;  ///< report: the HTML file (-o)
  std::string report_baseline;  ///< report: --baseline CSV, or empty
  bool refine = false;        ///< the subcommand `refine`: add cases to a study (refine.hpp)
  std::string refine_study;   ///< refine: the study file
  long refine_budget = 0;     ///< refine: --budget, the most cases /refinement may hold
  double refine_tolerance = 0.05;  ///< refine: --metric-tolerance (kDefaultMetricTolerance)
};

/// Exit statuses.
inline constexpr int kExitOk = 0;           ///< complete: every case has a row (ok or not)
inline constexpr int kExitIoError = 1;      ///< the study file could not be written
inline constexpr int kExitBadInput = 2;     ///< bad grid, options or output: nothing written
inline constexpr int kExitCaseFailed = 3;   ///< stopped early by on_failure = abort
inline constexpr int kExitInterrupted = 128;  ///< + the signal: 130 SIGINT, 143 SIGTERM

/// Under an MPI launcher (Open MPI, PMIx or PMI variables in the environment) the process
/// ends with its parent (mpirun, or the daemon it started): a parent-death signal (Linux
/// prctl), SIGTERM for rank 0 (it saves, setup_process), SIGKILL for the others (they hold
/// nothing). Not without a launcher: `nohup lubsweep ... &` outlives its shell. Call it
/// first in main, before MPI_Init: a launcher killed during MPI_Init must end the rank too,
/// and MPI_Init of a process started alone sets PMIX_RANK.
void end_with_launcher();

/// A rank's signal handling, right after MPI_Init:
/// - Rank 0: SIGINT and SIGTERM only record the signal. The coordinator's loop acts on it
///   within ~1 ms: it writes the rows it holds, closes the file, tells the workers to stop,
///   prints "lubsweep: interrupted: k of N cases saved in FILE; run the same command to
///   resume" and exits 128 + the signal without waiting for the case it computes. Outside
///   that loop (start-up, the final rewrite) a watchdog thread does it 0.5 s after the
///   signal, never while rows are being written.
/// - The other ranks leave 0.8 s after SIGINT or SIGTERM. mpirun (Open MPI 4.1), signalled,
///   sends SIGTERM to every rank 1 s later, SIGKILLs them all as soon as one has died (and
///   1 s later in any case), and exits 1: rank 0 must end first.
void setup_process(int rank);

/// Parses the command line (argv[1..]) (cli.cpp). Returns an error message, or nullopt on
/// success; `help` is set for -h/--help (CLI11's generated help into `help_text`) and for
/// --version (the version line into `help_text`).
std::optional<std::string> parse_options(const std::vector<std::string>& args, Options& out, bool& help,
                                         std::string& help_text);

/// `lubsweep report STUDY.h5 -o report.html [--baseline CSV]` (report.cpp): runs
/// `/usr/bin/python3 -m lubjoint.report` with the module lubjoint on PYTHONPATH (this build
/// tree's build/python for the build tree's lubsweep, else the install prefix's Python
/// directory beside its bin/), before and without MPI. Returns its exit status: 0 written,
/// 2 bad input (no study file, not a study: the message names the file, nothing written),
/// 1 Python or the module not found.
int run_report(const Options& options);

/// Runs the sweep on MPI_COMM_WORLD (MPI initialised with at least MPI_THREAD_FUNNELED).
/// Returns the exit status on every rank (rank 0's decides; others return 0 or 2).
int run_sweep(const Options& options);

}  // namespace lub::sweep
