#include "lub/sweep/sweep.hpp"

#include <mpi.h>

#include <algorithm>
#include <chrono>
#include <condition_variable>
#include <csignal>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <deque>
#include <exception>
#include <mutex>
#include <sys/stat.h>
#include <thread>
#include <unistd.h>

#include "lub/io/json_reader.hpp"
#include "lub/io/output_path.hpp"
#include "lub/run/run_io.hpp"
#include "lub/sweep/case_result.hpp"
#include "lub/sweep/grid.hpp"
#include "lub/sweep/output_lock.hpp"
#include "lub/sweep/progress.hpp"
#include "lub/sweep/study_file.hpp"

namespace lub::sweep {

const char* const kUsage =
    "usage: mpirun -np N lubsweep GRID.json -o STUDY.h5 [options]\n"
    "       lubsweep --summary STUDY.h5\n"
    "\n"
    "Runs every case of GRID.json (see README, \"Writing a grid\") and writes STUDY.h5:\n"
    "/cases (one row per case: axis values, status, metrics, solver statistics), /grids\n"
    "(case ids over each sub-grid's axes, with dimension scales), /scenes, /series.\n"
    "Every rank computes, rank 0 included; rank 0 alone writes the file.\n"
    "\n"
    "  -o, --output STUDY.h5   the study file (required). If it exists and is a study\n"
    "                          file, the cases it already holds (matched by the hash of\n"
    "                          their scene) are not run again: re-running a killed sweep\n"
    "                          resumes it\n"
    "  --restart               ignore an existing output file and start afresh\n"
    "  --retry-failed          run again the cases the file records as not ok\n"
    "  --check                 validate the grid and list its cases; run nothing\n"
    "  --summary STUDY.h5      print the study's table and exit\n"
    "  --no-summary            no table at the end\n"
    "  -q, --quiet             no progress lines on stderr\n"
    "  --version               print the version and exit\n"
    "\n"
    "Exit status: 0 the study is complete (a case that could not be integrated is a\n"
    "result: recorded with its status and message); 3 it stopped early (on_failure =\n"
    "abort): re-run to resume; 2 bad input (grid, options, output: nothing written);\n"
    "1 the file could not be written.\n";

std::optional<std::string> parse_options(const std::vector<std::string>& args, Options& o, bool& help,
                                         std::string& help_text) {
  help = false;
  for (std::size_t i = 0; i < args.size(); ++i) {
    const std::string& a = args[i];
    auto value = [&]() -> std::optional<std::string> {
      if (i + 1 >= args.size()) return std::nullopt;
      return args[++i];
    };
    if (a == "-h" || a == "--help") {
      help = true;
      help_text = kUsage;
      return std::nullopt;
    } else if (a == "--version") {
      help = true;
      help_text = "lubsweep " + program_version() + " (" + build_revision() + ")\n";
      return std::nullopt;
    } else if (a == "-o" || a == "--output") {
      auto v = value();
      if (!v) return a + " needs a file name";
      o.output = *v;
    } else if (a == "--summary") {
      auto v = value();
      if (!v) return a + " needs a study file";
      o.summary_of = *v;
    } else if (a == "--restart") {
      o.restart = true;
    } else if (a == "--retry-failed") {
      o.retry_failed = true;
    } else if (a == "--check") {
      o.check = true;
    } else if (a == "--no-summary") {
      o.summary = false;
    } else if (a == "-q" || a == "--quiet") {
      o.quiet = true;
    } else if (!a.empty() && a[0] == '-') {
      return "unknown option " + a;
    } else if (o.grid.empty()) {
      o.grid = a;
    } else {
      return "more than one grid given (" + o.grid + ", " + a + ")";
    }
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

enum Tag : int { kTagReady = 1, kTagResult = 2, kTagTask = 3, kTagStop = 4 };

using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point t0) { return std::chrono::duration<double>(Clock::now() - t0).count(); }

/// Waits for a message from `source` without busy-polling a core: MPI_Iprobe, a few
/// yields, then short sleeps (Open MPI's blocking receive spins at 100 % CPU).
void wait_message(int source, MPI_Status& st) {
  int flag = 0;
  auto idle = std::chrono::microseconds(20);
  for (;;) {
    MPI_Iprobe(source, MPI_ANY_TAG, MPI_COMM_WORLD, &flag, &st);
    if (flag) return;
    std::this_thread::sleep_for(idle);
    idle = std::min(idle * 2, std::chrono::microseconds(1000));
  }
}

/// Receives the probed message as bytes.
std::string receive(const MPI_Status& probed) {
  int n = 0;
  MPI_Get_count(&probed, MPI_BYTE, &n);
  std::string buf(static_cast<std::size_t>(n), '\0');
  MPI_Recv(buf.data(), n, MPI_BYTE, probed.MPI_SOURCE, probed.MPI_TAG, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
  return buf;
}

void send(int dest, int tag, const std::string& bytes) {
  MPI_Send(bytes.data(), static_cast<int>(bytes.size()), MPI_BYTE, dest, tag, MPI_COMM_WORLD);
}

/// A barrier that sleeps while it waits.
void polite_barrier() {
  MPI_Request req;
  MPI_Ibarrier(MPI_COMM_WORLD, &req);
  int done = 0;
  for (int spins = 0;; ++spins) {
    MPI_Test(&req, &done, MPI_STATUS_IGNORE);
    if (done) return;
    std::this_thread::sleep_for(std::chrono::microseconds(spins < 50 ? 20 : 1000));
  }
}

int broadcast_code(int code) {
  MPI_Bcast(&code, 1, MPI_INT, 0, MPI_COMM_WORLD);
  return code;
}

/// A task message: the case id, then its scene.
std::string task_message(const Case& c) {
  std::string m(sizeof(std::int64_t), '\0');
  const std::int64_t id = c.id;
  std::memcpy(m.data(), &id, sizeof id);
  return m + c.scene;
}

/// Ranks > 0: ask for work, run it, return the result, until told to stop.
void worker_loop(int rank) {
  send(0, kTagReady, std::string());
  for (;;) {
    MPI_Status st;
    wait_message(0, st);
    const std::string msg = receive(st);
    if (st.MPI_TAG == kTagStop) return;
    std::int64_t id = -1;
    std::memcpy(&id, msg.data(), sizeof id);
    const CaseResult r = run_case(static_cast<int>(id), msg.substr(sizeof id), rank);
    send(0, kTagResult, encode(r));
  }
}

/// Rank 0's own computing: one case at a time on a thread, so that the main thread stays
/// free to serve the other ranks and write the file.
class LocalWorker {
 public:
  LocalWorker() : thread_([this] { loop(); }) {}
  LocalWorker(const LocalWorker&) = delete;
  LocalWorker& operator=(const LocalWorker&) = delete;
  ~LocalWorker() {
    {
      std::lock_guard<std::mutex> l(m_);
      quit_ = true;
    }
    cv_.notify_one();
    thread_.join();
  }
  bool busy() const { return busy_; }
  void give(const Case& c) {
    {
      std::lock_guard<std::mutex> l(m_);
      task_id_ = c.id;
      task_scene_ = c.scene;
      has_task_ = true;
    }
    busy_ = true;
    cv_.notify_one();
  }
  /// Sleeps up to `d`, waking at once when a result is ready.
  void wait_for_result(std::chrono::microseconds d) {
    std::unique_lock<std::mutex> l(m_);
    done_cv_.wait_for(l, d, [this] { return result_.has_value(); });
  }
  /// The finished result, if any.
  std::optional<CaseResult> take() {
    std::lock_guard<std::mutex> l(m_);
    if (!result_) return std::nullopt;
    std::optional<CaseResult> r = std::move(result_);
    result_.reset();
    busy_ = false;
    return r;
  }

 private:
  void loop() {
    std::unique_lock<std::mutex> l(m_);
    for (;;) {
      cv_.wait(l, [this] { return has_task_ || quit_; });
      if (!has_task_) return;
      has_task_ = false;
      const int id = task_id_;
      const std::string scene = std::move(task_scene_);
      l.unlock();
      CaseResult r = run_case(id, scene, 0);
      l.lock();
      result_ = std::move(r);
      done_cv_.notify_one();
    }
  }

  std::mutex m_;
  std::condition_variable cv_, done_cv_;
  bool has_task_ = false, quit_ = false, busy_ = false;
  int task_id_ = -1;
  std::string task_scene_;
  std::optional<CaseResult> result_;
  std::thread thread_;  // last: starts after the members it uses
};

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
      resume = read_existing(o.output, grid, o.retry_failed, build_revision());
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

/// Rank 0: hands out the cases, computes some, writes the file.
int coordinate(const Options& o, const Grid& grid, const ResumeState& resume, bool reuse_file, int nranks) {
  const auto t0 = Clock::now();
  std::deque<int> queue;
  std::size_t done_failed = 0;
  for (const Case& c : grid.cases)
    if (!resume.done.count(c.id)) queue.push_back(c.id);
  for (const auto& [id, r] : resume.done) done_failed += !r.ok();

  if (!o.quiet) {
    std::fprintf(stderr, "lubsweep: %s: %zu cases on %d rank%s", o.grid.c_str(), grid.cases.size(), nranks,
                 nranks > 1 ? "s" : "");
    if (reuse_file)
      std::fprintf(stderr, "; %s holds %zu of them (%zu to run)", o.output.c_str(), resume.done.size(), queue.size());
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

  std::unique_ptr<StudyWriter> writer;
  try {
    writer = std::make_unique<StudyWriter>(o.output, grid, resume.done, reuse_file ? o.output : std::string());
  } catch (const std::exception& e) {
    std::fprintf(stderr, "lubsweep: cannot write %s: %s\n", o.output.c_str(), e.what());
    MPI_Abort(MPI_COMM_WORLD, kExitIoError);
  }

  Progress progress(grid.cases.size(), resume.done.size(), done_failed);
  bool aborting = false;
  long new_rows = 0;
  auto record = [&](const CaseResult& r) {
    const Case& c = grid.cases.at(static_cast<std::size_t>(r.case_id));
    try {
      writer->append(r);
    } catch (const std::exception& e) {
      std::fprintf(stderr, "lubsweep: cannot write %s: %s\n", o.output.c_str(), e.what());
      MPI_Abort(MPI_COMM_WORLD, kExitIoError);
    }
    const std::string line = progress.record(c, r, seconds_since(t0));
    if (!o.quiet) std::fprintf(stderr, "lubsweep: %s\n", line.c_str());
    if (!r.ok() && grid.on_failure == FailurePolicy::abort_on_failure && !aborting) {
      aborting = true;
      std::fprintf(stderr, "lubsweep: %s failed (%s: %s); on_failure = abort: stopping\n", c.name.c_str(),
                   r.status.c_str(), r.message.c_str());
    }
    if (o.kill_after >= 0 && ++new_rows >= o.kill_after) std::raise(SIGKILL);  // tests only
  };
  auto next = [&]() -> int {
    if (aborting || queue.empty()) return -1;
    const int id = queue.front();
    queue.pop_front();
    return id;
  };

  {
    LocalWorker local;
    int remote_active = nranks - 1;
    // Idle waits grow from 50 µs to 1 ms: a rank waiting for its next case waits at most
    // ~1 ms, and the polling costs rank 0's core ~1 % (Open MPI would spin at 100 %).
    auto idle = std::chrono::microseconds(50);
    for (;;) {
      bool progressed = false;
      if (auto r = local.take()) {
        record(*r);
        progressed = true;
      }
      if (!local.busy()) {
        const int id = next();
        if (id >= 0) local.give(grid.cases[static_cast<std::size_t>(id)]), progressed = true;
      }
      int flag = 0;
      MPI_Status st;
      MPI_Iprobe(MPI_ANY_SOURCE, MPI_ANY_TAG, MPI_COMM_WORLD, &flag, &st);
      if (flag) {
        progressed = true;
        const std::string msg = receive(st);
        if (st.MPI_TAG == kTagResult) {
          CaseResult r;
          try {
            r = decode(msg);
          } catch (const std::exception& e) {
            std::fprintf(stderr, "lubsweep: rank %d: %s\n", st.MPI_SOURCE, e.what());
            MPI_Abort(MPI_COMM_WORLD, kExitIoError);
          }
          record(r);
        }
        const int id = next();
        if (id >= 0) {
          send(st.MPI_SOURCE, kTagTask, task_message(grid.cases[static_cast<std::size_t>(id)]));
        } else {
          send(st.MPI_SOURCE, kTagStop, std::string());
          --remote_active;
        }
      }
      if (remote_active == 0 && !local.busy() && (queue.empty() || aborting)) break;
      if (progressed) {
        idle = std::chrono::microseconds(50);
      } else {
        if (local.busy())
          local.wait_for_result(idle);
        else
          std::this_thread::sleep_for(idle);
        idle = std::min(idle * 2, std::chrono::microseconds(1000));
      }
    }
  }

  const bool complete = writer->complete();
  try {
    writer->finalize();
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

int run_sweep(const Options& o) {
  int rank = 0, nranks = 1;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  MPI_Comm_size(MPI_COMM_WORLD, &nranks);

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
  if (broadcast_code(code) != 0) return rank == 0 ? code : 0;

  int status = 0;
  if (rank == 0)
    status = coordinate(o, grid, resume, reuse_file, nranks);
  else
    worker_loop(rank);
  polite_barrier();
  return status;
}

}  // namespace lub::sweep
