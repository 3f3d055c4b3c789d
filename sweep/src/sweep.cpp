// lubsweep's orchestration (lub/sweep/sweep.hpp): rank 0 validates, coordinates the cases
// and writes the study file; the other ranks serve. The command line is in cli.cpp, the
// signal handling in signals.cpp.
#include "lub/sweep/sweep.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>
#include <mpi.h>

#include <chrono>
#include <csignal>
#include <cstdio>
#include <deque>
#include <exception>
#include <memory>
#include <sys/stat.h>

#include "lub/io/json_reader.hpp"
#include "lub/io/output_path.hpp"
#include "lub/run/run_io.hpp"
#include "lub/sweep/case_result.hpp"
#include "lub/sweep/continuation_tree.hpp"
#include "lub/sweep/grid.hpp"
#include "lub/sweep/mpi_transport.hpp"
#include "lub/sweep/output_lock.hpp"
#include "lub/sweep/progress.hpp"
#include "lub/sweep/refine.hpp"
#include "lub/sweep/scheduler.hpp"
#include "lub/sweep/study_file.hpp"
#include "signals.hpp"

namespace lub::sweep {

namespace {

using Clock = std::chrono::steady_clock;

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
    fmt::print(stderr, "lubsweep: {}: {}\n", o.grid, e.what());
    return kExitBadInput;
  }
  // Plausibility warnings: once per grid (each distinct one), stored in the study file; errors under --strict.
  for (const std::string& w : grid.warnings)
    fmt::print(stderr, "lubsweep: {}{}{}\n", o.strict ? o.grid + ": " : "warning: ", w,
               o.strict ? "; refused under --strict" : "");
  if (o.strict && !grid.warnings.empty()) return kExitBadInput;
  // Validity notes (a force law outside its assumptions): once per grid, never refused.
  for (const std::string& n : grid.notes) fmt::print(stderr, "lubsweep: note: {}\n", n);
  if (o.check) return 0;
  if (const auto problem = output_path_problem(o.output)) {
    fmt::print(stderr, "lubsweep: {}\n", *problem);
    return kExitBadInput;
  }
  // One sweep per output file: the lock is held until this sweep ends (run_sweep).
  try {
    lock = OutputLock(o.output);
  } catch (const InputError& e) {
    fmt::print(stderr, "lubsweep: {}\n", e.what());
    return kExitBadInput;
  } catch (const std::exception& e) {
    fmt::print(stderr, "lubsweep: {}\n", e.what());
    return kExitBadInput;
  }
  reuse_file = false;
  if (file_exists(o.output) && !o.restart) {
    try {
      resume = read_existing(o.output, grid, o.retry_failed, build_revision(), o.drop_other_cases);
      reuse_file = true;
    } catch (const InputError& e) {
      fmt::print(stderr, "lubsweep: {}\n", e.what());
      return kExitBadInput;
    } catch (const std::exception& e) {
      fmt::print(stderr, "lubsweep: -o {}: cannot read it: {} (use --restart to overwrite it)\n", o.output, e.what());
      return kExitBadInput;
    }
  }
  return 0;
}

void list_cases(const Grid& g) {
  fmt::print("{}: {} cases, {} axes, {} sub-grids\n", g.file, g.cases.size(), g.axes.size(), g.blocks.size());
  for (const Block& b : g.blocks) {
    fmt::print("  grid {:<16} {:<9} {} cases", b.name, b.factorial ? "factorial" : "list", b.case_ids.size());
    if (b.factorial && !b.shape.empty()) {
      fmt::print(" (");
      for (std::size_t i = 0; i < b.shape.size(); ++i)
        fmt::print("{}{} {}", i ? " x " : "", b.shape[i], g.axes[static_cast<std::size_t>(b.axes[i])].name);
      fmt::print(")");
    }
    fmt::print("\n");
  }
  for (const Case& c : g.cases) fmt::print("  {} {:.12}  {}\n", c.name, c.hash, c.label);
}

/// The opening lines on stderr: what runs, what the file holds.
void print_start(const Options& o, const Grid& grid, const ResumeState& resume, bool reuse_file, int nranks,
                 std::size_t to_run) {
  if (!o.quiet) {
    fmt::print(stderr, "lubsweep: {}: {} cases on {} rank{}", o.grid, grid.cases.size(), nranks, nranks > 1 ? "s" : "");
    if (reuse_file)
      fmt::print(stderr, "; {} holds {} of them ({} to run)", o.output, resume.done.size(), to_run);
    fmt::print(stderr, "\n");
    if (resume.other_rows)
      fmt::print(stderr, "lubsweep: dropping {} rows of {} that are not cases of this grid\n", resume.other_rows,
                 o.output);
    if (resume.incompatible_rows)
      fmt::print(stderr,
                 "lubsweep: {} has not every result column of this build (another version?): its {} rows are not "
                 "reused\n",
                 o.output, resume.incompatible_rows);
    if (resume.other_revision)
      fmt::print(stderr, "lubsweep: {} rows of {} were computed by another build revision: running them again\n",
                 resume.other_revision, o.output);
    if (resume.retried) fmt::print(stderr, "lubsweep: running {} failed cases again\n", resume.retried);
  }
  // Dropped ones are said even with --quiet: they took work to make.
  if (reuse_file && !resume.added_groups.empty() && resume.done.size() < grid.cases.size())
    fmt::print(stderr,
               "lubsweep: {}'s /{} belong to its earlier cases, not to this grid's {}: they are not kept (run "
               "lubsweep refine or python3 -m lubjoint.boundaries again once the study is complete)\n",
               o.output, fmt::join(resume.added_groups, ", /"), grid.cases.size());
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
  detail::Interrupts& interrupts = detail::Interrupts::process();
  interrupts.name_file(o.output, OutputLock::lock_path(o.output), grid.cases.size(), resume.done.size());

  std::unique_ptr<StudyWriter> writer;
  try {
    writer = std::make_unique<StudyWriter>(o.output, grid, resume.done, reuse_file ? o.output : std::string());
  } catch (const std::exception& e) {
    fmt::print(stderr, "lubsweep: cannot write {}: {}\n", o.output, e.what());
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
      const auto busy = interrupts.writing();
      what();
      interrupts.saved(writer->rows() - writer->pending());
    } catch (const std::exception& e) {
      fmt::print(stderr, "lubsweep: cannot write {}: {}\n", o.output, e.what());
      transport.abort(kExitIoError);
    }
  };
  // Every turn of the scheduler's loop (~1 ms while it waits): the rows held are written
  // once due, whatever runs next; on SIGINT/SIGTERM, every row held is written and the
  // file closed, the workers are told to stop, and the process ends (Interrupts::leave).
  s.tick = [&] {
    if (const int sig = interrupts.signal()) {
      write([&] { writer->flush(); });
      {
        const auto busy = interrupts.writing();
        writer.reset();  // closes the file
      }
      for (int w = 1; w <= transport.workers(); ++w) transport.send_stop(w);
      interrupts.leave(sig);
    }
    write([&] { writer->flush_if_due(); });
  };
  s.record = [&](const CaseResult& r) {
    const Case& c = grid.cases.at(static_cast<std::size_t>(r.case_id));
    write([&] { writer->append(r); });
    const std::string line = progress.record(c, r, seconds_since(t0));
    if (!o.quiet) fmt::print(stderr, "lubsweep: {}\n", line);
    if (o.kill_after >= 0 && ++new_rows >= o.kill_after) {  // tests only: killed with these rows on disk
      writer->flush();
      std::raise(SIGKILL);
    }
  };
  s.on_abort = [&](const CaseResult& r) {
    fmt::print(stderr, "lubsweep: {} failed ({}: {}); on_failure = abort: stopping\n",
               grid.cases.at(static_cast<std::size_t>(r.case_id)).name, r.status.str(), r.message);
  };
  try {
    schedule(grid, queue, transport, s);
  } catch (const TransportError& e) {
    fmt::print(stderr, "lubsweep: {}\n", e.what());
    transport.abort(kExitIoError);
  }

  return finish(o, grid, *writer, progress, t0);
}

/// Rank 0, every case run: the file rewritten canonically, the last lines and the summary.
int finish(const Options& o, const Grid& grid, StudyWriter& writer, const Progress& progress, Clock::time_point t0) {
  const bool complete = writer.complete();
  try {
    const auto busy = detail::Interrupts::process().writing();
    writer.finalize();
    detail::Interrupts::process().saved(writer.rows());
  } catch (const std::exception& e) {
    fmt::print(stderr, "lubsweep: cannot write {}: {}\n", o.output, e.what());
    return kExitIoError;
  }
  if (!o.quiet)
    fmt::print(stderr, "lubsweep: wrote {}: {} of {} cases, {} not ok, {}\n", o.output, progress.done(),
               grid.cases.size(), progress.failed(), format_duration(seconds_since(t0)));
  if (o.summary) {
    try {
      print_summary(o.output, stdout);
    } catch (const std::exception& e) {
      fmt::print(stderr, "lubsweep: {}: {}\n", o.output, e.what());
      return kExitIoError;
    }
  }
  return complete ? kExitOk : kExitCaseFailed;
}

}  // namespace

int run_sweep(const Options& o) {
  int rank = 0;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  if (o.refine) return run_refine(o, MPI_COMM_WORLD);

  if (!o.summary_of.empty()) {
    if (rank != 0) return 0;
    try {
      print_summary(o.summary_of, stdout);
    } catch (const std::exception& e) {
      fmt::print(stderr, "lubsweep: --summary {}: {}\n", o.summary_of, e.what());
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
