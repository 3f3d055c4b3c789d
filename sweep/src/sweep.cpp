#include "lub/sweep/continuation_tree.hpp"
#include "lub/sweep/sweep.hpp"

#include <mpi.h>

#include <CLI/CLI.hpp>

#include <atomic>
#include <chrono>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <deque>
#include <exception>
#include <memory>
#include <thread>
#include <sys/prctl.h>
#include <sys/stat.h>
#include <unistd.h>

#include "lub/io/json_reader.hpp"
#include "lub/io/output_path.hpp"
#include "lub/run/run_io.hpp"
#include "lub/sweep/case_result.hpp"
#include "lub/sweep/grid.hpp"
#include "lub/sweep/mpi_transport.hpp"
#include "lub/sweep/output_lock.hpp"
#include "lub/sweep/progress.hpp"
#include "lub/sweep/scheduler.hpp"
#include "lub/sweep/study_file.hpp"

namespace lub::sweep {

const char* const kUsage =
    "usage: mpirun -np N lubsweep GRID.json -o STUDY.h5 [options]\n"
    "       lubsweep --summary STUDY.h5\n"
    "\n"
    "Runs every case of GRID.json (docs/guide/grids.md) and writes STUDY.h5:\n"
    "/cases (one row per case: axis values, status, metrics, solver statistics), /grids\n"
    "(case ids over each sub-grid's axes, with dimension scales, and the results over them),\n"
    "/scene and /scene_patches (each case's scene as a JSON Patch of the root attribute\n"
    "reference_scene), /series (the channels a case keeps).\n"
    "Every rank computes, rank 0 included; rank 0 alone writes the file.\n"
    "\n"
    "  -o, --output STUDY.h5   the study file (required). If it exists and is a study\n"
    "                          file, the cases it already holds (matched by the hash of\n"
    "                          their scene) are not run again: re-running a killed sweep\n"
    "                          resumes it\n"
    "  --restart               ignore an existing output file and start afresh\n"
    "  --drop-other-cases      resume, dropping the file's rows that are not cases of\n"
    "                          this grid (without it such a file is refused: exit 2)\n"
    "  --retry-failed          run again the cases the file records as not ok\n"
    "  --check                 validate the grid and list its cases; run nothing\n"
    "  --strict                a plausibility warning (a viscosity, clearance or speed that\n"
    "                          looks like a unit slip) is an error: exit 2, nothing written\n"
    "  --summary STUDY.h5      print the study's table and exit\n"
    "  --no-summary            no table at the end\n"
    "  -q, --quiet             no progress lines on stderr\n"
    "  --version               print the version, revision and build type and exit\n"
    "  -h, --help              print this text and exit\n"
    "\n"
    "Exit status: 0 the study is complete (a case that could not be integrated is a\n"
    "result: recorded with its status and message); 3 it stopped early (on_failure =\n"
    "abort): re-run to resume; 2 bad input (grid, options, output: nothing written);\n"
    "1 the file could not be written; 130/143 interrupted (SIGINT/SIGTERM): every case\n"
    "finished is saved, re-run to resume.\n";

std::optional<std::string> parse_options(const std::vector<std::string>& args, Options& o, bool& help,
                                         std::string& help_text) {
  CLI::App app("lubsweep");
  app.set_help_flag();  // -h prints kUsage, not CLI11's generated text
  help = false;
  bool version = false;
  app.add_flag("-h,--help", help);
  app.add_flag("--version", version);
  app.add_option("grid", o.grid);
  app.add_option("-o,--output", o.output);
  app.add_option("--summary", o.summary_of);
  app.add_flag("--restart", o.restart);
  app.add_flag("--retry-failed", o.retry_failed);
  app.add_flag("--drop-other-cases", o.drop_other_cases);
  app.add_flag("--check", o.check);
  app.add_flag("--strict", o.strict);
  app.add_flag("--no-summary{false}", o.summary);
  app.add_flag("-q,--quiet", o.quiet);
  try {
    app.parse(std::vector<std::string>(args.rbegin(), args.rend()));  // CLI11 wants them last first
  } catch (const CLI::ExtrasError&) {
    const std::string extra = app.remaining().front();
    if (!extra.empty() && extra[0] == '-') return "unknown option " + extra;
    return "more than one grid given (" + o.grid + ", " + extra + ")";
  } catch (const CLI::ParseError& e) {
    return std::string(e.what());
  }
  if (help || version) {
    help = true;
    help_text = version ? "lubsweep " + program_version() + " (revision " + build_revision() + ", " +
                             LUB_BUILD_TYPE + " build)\n"
                       : kUsage;
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

namespace {

using Clock = std::chrono::steady_clock;

// Interrupts (rank 0). The handler only records the signal; the coordinator's loop acts on
// it (leave_interrupted), or, when rank 0 is elsewhere (start-up, the final rewrite, a wait
// on other ranks), the watchdog thread after kInterruptGrace unless rows are being written.
std::atomic<int> g_signal{0};          // the first SIGINT or SIGTERM
std::atomic<int> g_writing{0};         // > 0 while rows are appended to the study file
std::atomic<bool> g_leaving{false};    // one thread prints the line and ends the process
std::atomic<std::size_t> g_saved{0};   // rows on disk, for the line
std::atomic<std::size_t> g_total{0};
std::atomic<bool> g_have_file{false};  // g_file and g_lock_file are set (once, before g_have_file)
const std::string* g_file = nullptr;       // never freed: the watchdog may read them at exit
const std::string* g_lock_file = nullptr;
constexpr auto kInterruptGrace = std::chrono::milliseconds(500);
constexpr auto kWorkerGrace = std::chrono::milliseconds(800);  // < mpirun's 1 s before SIGKILL

static_assert(std::atomic<int>::is_always_lock_free, "the signal handler stores into an atomic int");

extern "C" void on_interrupt(int sig) {
  int none = 0;
  g_signal.compare_exchange_strong(none, sig);
}

/// Rows are being written: the watchdog does not end the process meanwhile.
struct WritingRows {
  WritingRows() { ++g_writing; }
  ~WritingRows() { --g_writing; }
  WritingRows(const WritingRows&) = delete;
  WritingRows& operator=(const WritingRows&) = delete;
};

/// Prints the interrupt line, removes the lock file (still held) and ends the process with
/// 128 + the signal, without waiting for a case that runs (no destructors, no MPI_Finalize:
/// the launcher ends the other ranks).
[[noreturn]] void leave_interrupted(int sig) {
  if (g_leaving.exchange(true))
    for (;;) std::this_thread::sleep_for(std::chrono::seconds(1));  // the other thread leaves
  if (g_have_file) {
    std::fprintf(stderr, "lubsweep: interrupted: %zu of %zu cases saved in %s; run the same command to resume\n",
                 g_saved.load(), g_total.load(), g_file->c_str());
    ::unlink(g_lock_file->c_str());
  } else {
    std::fprintf(stderr, "lubsweep: interrupted; nothing written\n");
  }
  std::fflush(stdout);
  std::fflush(stderr);
  std::_Exit(kExitInterrupted + sig);
}

/// Rank 0: leaves kInterruptGrace after a signal, unless rows are being written, if the
/// coordinator's loop has not. A worker: leaves kWorkerGrace after a signal, silently. mpirun,
/// signalled, sends SIGTERM to every rank at once and SIGKILL to all as soon as one has
/// died: the workers' grace lets rank 0 write its rows and end first.
void watchdog(int rank) {
  while (g_signal.load() == 0) std::this_thread::sleep_for(std::chrono::milliseconds(20));
  if (rank != 0) {
    std::this_thread::sleep_for(kWorkerGrace);
    std::_Exit(kExitInterrupted + g_signal.load());
  }
  std::this_thread::sleep_for(kInterruptGrace);
  while (g_writing.load() > 0) std::this_thread::sleep_for(std::chrono::milliseconds(5));
  leave_interrupted(g_signal.load());
}

bool under_launcher() {
  for (const char* v : {"OMPI_COMM_WORLD_SIZE", "PMIX_RANK", "PMI_RANK"})
    if (std::getenv(v)) return true;
  return false;
}

double seconds_since(Clock::time_point t0) { return std::chrono::duration<double>(Clock::now() - t0).count(); }

bool file_exists(const std::string& path) {
  struct stat s;
  return ::stat(path.c_str(), &s) == 0;
}

/// Rank 0: validation before any work. Returns 0 to go on, or an exit status.
int prepare(const Options& o, Grid& grid, ResumeState& resume, bool& reuse_file, OutputLock& lock) {
  try {
    grid = load_grid(o.grid);
  } catch (const InputError& e) {
    std::fprintf(stderr, "lubsweep: %s: %s\n", o.grid.c_str(), e.what());
    return kExitBadInput;
  }
  // Plausibility warnings: once per grid (each distinct one), stored in the study file; errors under --strict.
  for (const std::string& w : grid.warnings)
    std::fprintf(stderr, "lubsweep: %s%s%s\n", o.strict ? (o.grid + ": ").c_str() : "warning: ", w.c_str(),
                 o.strict ? "; refused under --strict" : "");
  if (o.strict && !grid.warnings.empty()) return kExitBadInput;
  if (o.check) return 0;
  if (const auto problem = output_path_problem(o.output)) {
    std::fprintf(stderr, "lubsweep: %s\n", problem->c_str());
    return kExitBadInput;
  }
  // One sweep per output file: the lock is held until this sweep ends (run_sweep).
  try {
    lock = OutputLock(o.output);
  } catch (const InputError& e) {
    std::fprintf(stderr, "lubsweep: %s\n", e.what());
    return kExitBadInput;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "lubsweep: %s\n", e.what());
    return kExitBadInput;
  }
  reuse_file = false;
  if (file_exists(o.output) && !o.restart) {
    try {
      resume = read_existing(o.output, grid, o.retry_failed, build_revision(), o.drop_other_cases);
      reuse_file = true;
    } catch (const InputError& e) {
      std::fprintf(stderr, "lubsweep: %s\n", e.what());
      return kExitBadInput;
    } catch (const std::exception& e) {
      std::fprintf(stderr, "lubsweep: -o %s: cannot read it: %s (use --restart to overwrite it)\n", o.output.c_str(),
                   e.what());
      return kExitBadInput;
    }
  }
  return 0;
}

void list_cases(const Grid& g) {
  std::printf("%s: %zu cases, %zu axes, %zu sub-grids\n", g.file.c_str(), g.cases.size(), g.axes.size(),
              g.blocks.size());
  for (const Block& b : g.blocks) {
    std::printf("  grid %-16s %-9s %zu cases", b.name.c_str(), b.factorial ? "factorial" : "list", b.case_ids.size());
    if (b.factorial && !b.shape.empty()) {
      std::printf(" (");
      for (std::size_t i = 0; i < b.shape.size(); ++i)
        std::printf("%s%zu %s", i ? " x " : "", b.shape[i], g.axes[static_cast<std::size_t>(b.axes[i])].name.c_str());
      std::printf(")");
    }
    std::printf("\n");
  }
  for (const Case& c : g.cases) std::printf("  %s %.12s  %s\n", c.name.c_str(), c.hash.c_str(), c.label.c_str());
}

/// The opening lines on stderr: what runs, what the file holds.
void print_start(const Options& o, const Grid& grid, const ResumeState& resume, bool reuse_file, int nranks,
                 std::size_t to_run) {
  if (!o.quiet) {
    std::fprintf(stderr, "lubsweep: %s: %zu cases on %d rank%s", o.grid.c_str(), grid.cases.size(), nranks,
                 nranks > 1 ? "s" : "");
    if (reuse_file)
      std::fprintf(stderr, "; %s holds %zu of them (%zu to run)", o.output.c_str(), resume.done.size(), to_run);
    std::fprintf(stderr, "\n");
    if (resume.other_rows)
      std::fprintf(stderr, "lubsweep: dropping %zu rows of %s that are not cases of this grid\n", resume.other_rows,
                   o.output.c_str());
    if (resume.incompatible_rows)
      std::fprintf(stderr, "lubsweep: %s has not every result column of this build (another version?): its %zu rows are not reused\n",
                   o.output.c_str(), resume.incompatible_rows);
    if (resume.other_revision)
      std::fprintf(stderr, "lubsweep: %zu rows of %s were computed by another build revision: running them again\n",
                   resume.other_revision, o.output.c_str());
    if (resume.retried) std::fprintf(stderr, "lubsweep: running %zu failed cases again\n", resume.retried);
  }
}

int finish(const Options& o, const Grid& grid, StudyWriter& writer, const Progress& progress, Clock::time_point t0);

/// Rank 0: hands out the cases (scheduler.hpp), computes some, writes the file.
int coordinate(const Options& o, const Grid& grid, const ResumeState& resume, bool reuse_file,
               CoordinatorTransport& transport) {
  const auto t0 = Clock::now();
  const std::deque<int> queue = cases_to_run(grid, resume.done);
  std::size_t done_failed = 0;
  for (const auto& [id, r] : resume.done) done_failed += !r.ok();
  print_start(o, grid, resume, reuse_file, transport.workers() + 1, queue.size());
  if (!g_have_file) {  // for the interrupt line
    g_file = new std::string(o.output);
    g_lock_file = new std::string(OutputLock::lock_path(o.output));
    g_total = grid.cases.size();
    g_saved = resume.done.size();
    g_have_file = true;
  }

  std::unique_ptr<StudyWriter> writer;
  try {
    writer = std::make_unique<StudyWriter>(o.output, grid, resume.done, reuse_file ? o.output : std::string());
  } catch (const std::exception& e) {
    std::fprintf(stderr, "lubsweep: cannot write %s: %s\n", o.output.c_str(), e.what());
    transport.abort(kExitIoError);
  }

  Progress progress(grid.cases.size(), resume.done.size(), done_failed);
  long new_rows = 0;
  Schedule s;
  s.on_failure = grid.on_failure;
  // Rank 0 runs a case from its canonical JSON, as the other ranks do.
  s.local = [](const Task& t) { return run_task(t, 0); };
  // Continuation (simulation.steady = continuation): each case waits for its parent's orbit.
  s.parents = continuation_parents(grid);
  for (const auto& [id, r] : resume.done) s.finished[id] = r.orbit_seed;
  const auto write = [&](auto&& what) {
    try {
      const WritingRows busy;
      what();
      g_saved = writer->rows() - writer->pending();
    } catch (const std::exception& e) {
      std::fprintf(stderr, "lubsweep: cannot write %s: %s\n", o.output.c_str(), e.what());
      transport.abort(kExitIoError);
    }
  };
  // Every turn of the scheduler's loop (~1 ms while it waits): the rows held are written
  // once due, whatever runs next; on SIGINT/SIGTERM, every row held is written and the
  // file closed, the workers are told to stop, and the process ends (leave_interrupted).
  s.tick = [&] {
    if (const int sig = g_signal.load()) {
      write([&] { writer->flush(); });
      {
        const WritingRows busy;
        writer.reset();  // closes the file
      }
      for (int w = 1; w <= transport.workers(); ++w) transport.send_stop(w);
      leave_interrupted(sig);
    }
    write([&] { writer->flush_if_due(); });
  };
  s.record = [&](const CaseResult& r) {
    const Case& c = grid.cases.at(static_cast<std::size_t>(r.case_id));
    write([&] { writer->append(r); });
    const std::string line = progress.record(c, r, seconds_since(t0));
    if (!o.quiet) std::fprintf(stderr, "lubsweep: %s\n", line.c_str());
    if (o.kill_after >= 0 && ++new_rows >= o.kill_after) {  // tests only: killed with these rows on disk
      writer->flush();
      std::raise(SIGKILL);
    }
  };
  s.on_abort = [&](const CaseResult& r) {
    std::fprintf(stderr, "lubsweep: %s failed (%s: %s); on_failure = abort: stopping\n",
                 grid.cases.at(static_cast<std::size_t>(r.case_id)).name.c_str(), r.status.c_str(), r.message.c_str());
  };
  try {
    schedule(grid, queue, transport, s);
  } catch (const TransportError& e) {
    std::fprintf(stderr, "lubsweep: %s\n", e.what());
    transport.abort(kExitIoError);
  }

  return finish(o, grid, *writer, progress, t0);
}

/// Rank 0, every case run: the file rewritten canonically, the last lines and the summary.
int finish(const Options& o, const Grid& grid, StudyWriter& writer, const Progress& progress, Clock::time_point t0) {
  const bool complete = writer.complete();
  try {
    const WritingRows busy;
    writer.finalize();
    g_saved = writer.rows();
  } catch (const std::exception& e) {
    std::fprintf(stderr, "lubsweep: cannot write %s: %s\n", o.output.c_str(), e.what());
    return kExitIoError;
  }
  if (!o.quiet)
    std::fprintf(stderr, "lubsweep: wrote %s: %zu of %zu cases, %zu not ok, %s\n", o.output.c_str(), progress.done(),
                 grid.cases.size(), progress.failed(), format_duration(seconds_since(t0)).c_str());
  if (o.summary) {
    try {
      print_summary(o.output, stdout);
    } catch (const std::exception& e) {
      std::fprintf(stderr, "lubsweep: %s: %s\n", o.output.c_str(), e.what());
      return kExitIoError;
    }
  }
  return complete ? kExitOk : kExitCaseFailed;
}

}  // namespace

void end_with_launcher() {
  if (!under_launcher()) return;
  const char* rank = std::getenv("OMPI_COMM_WORLD_RANK");
  if (!rank) rank = std::getenv("PMIX_RANK");
  if (!rank) rank = std::getenv("PMI_RANK");
  // Rank 0 saves the rows it holds (on_interrupt, from setup_process on); the others hold
  // nothing. A rank unknown here takes SIGTERM too (then it leaves after kWorkerGrace).
  const int sig = rank == nullptr || std::string(rank) == "0" ? SIGTERM : SIGKILL;
  const pid_t parent = ::getppid();
  ::prctl(PR_SET_PDEATHSIG, sig);
  if (::getppid() != parent) std::raise(sig);  // gone before prctl
}

void setup_process(int rank) {
  struct sigaction sa{};
  sa.sa_handler = on_interrupt;
  sigemptyset(&sa.sa_mask);
  sa.sa_flags = SA_RESTART;
  ::sigaction(SIGINT, &sa, nullptr);
  ::sigaction(SIGTERM, &sa, nullptr);
  std::signal(SIGPIPE, SIG_IGN);  // stderr may be a pipe to a launcher that is gone
  std::thread(watchdog, rank).detach();
}

int run_sweep(const Options& o) {
  int rank = 0;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);

  if (!o.summary_of.empty()) {
    if (rank != 0) return 0;
    try {
      print_summary(o.summary_of, stdout);
    } catch (const std::exception& e) {
      std::fprintf(stderr, "lubsweep: --summary %s: %s\n", o.summary_of.c_str(), e.what());
      return kExitBadInput;
    }
    return 0;
  }

  Grid grid;
  ResumeState resume;
  bool reuse_file = false;
  OutputLock lock;  // rank 0: held for the sweep's lifetime
  int code = 0;
  if (rank == 0) code = prepare(o, grid, resume, reuse_file, lock);
  if (o.check) {
    if (rank == 0 && code == 0) list_cases(grid);
    return code;
  }
  if (broadcast_code(MPI_COMM_WORLD, code) != 0) return rank == 0 ? code : 0;

  int status = 0;
  if (rank == 0) {
    MpiCoordinator transport(MPI_COMM_WORLD);
    status = coordinate(o, grid, resume, reuse_file, transport);
  } else {
    MpiWorker transport(MPI_COMM_WORLD);
    // Each rank parses a case's scene once, from the task's canonical JSON.
    serve(transport, [rank](const Task& t) { return run_task(t, rank); });
  }
  polite_barrier(MPI_COMM_WORLD);
  return status;
}

}  // namespace lub::sweep
