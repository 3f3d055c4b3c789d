// The sweep's own cost per case, without the cases: the scheduler, the MPI transport and the
// study file's writer run a real grid (its scenes travel as tasks, results of every column
// come back and are written), but each case is a stand-in that spins for --case-us
// microseconds and returns NaN metrics. What it prints feeds the scaling model
// (tools/perf/scaling_model.py):
//  - the coordinator's service per result, µs of its thread's CPU time: rank 0 serving remote
//    workers only (its own worker off), cases of zero cost, with and without the writer
//    (batched as lubsweep batches): what bounds rank 0's throughput at many ranks;
//  - round trip per case, µs of wall: prefetch 1 and one worker, which then waits for each
//    answer: message latency both ways, the idle waits and the service;
//  - size: bytes per case of the finished study file (no series) and rank 0's peak memory
//    (the grid, every result, the writer) for the grid given.
//
//   mpirun -np 2 build/tests/bench/bench_sweep_overhead [GRID.json] [--cases N]
// (the grid: configs/grids/cheap_4096.json by default; --cases 0: all of
// its cases). Prints one JSON object on rank 0.
#include <mpi.h>

#include <chrono>
#include <cmath>
#include <deque>
#include <map>
#include <memory>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <limits>
#include <string>
#include <vector>

#include <sys/resource.h>
#include <sys/stat.h>
#include <unistd.h>

#include "lub/sweep/case_result.hpp"
#include "lub/sweep/grid.hpp"
#include "lub/sweep/mpi_transport.hpp"
#include "lub/sweep/scheduler.hpp"
#include "lub/sweep/study_file.hpp"

using namespace lub::sweep;
using Clock = std::chrono::steady_clock;

namespace {

CaseResult stand_in(int case_id, int rank, double case_us) {
  const auto until = Clock::now() + std::chrono::duration<double, std::micro>(case_us);
  while (Clock::now() < until) {
  }
  CaseResult r;
  r.case_id = case_id;
  r.rank = rank;
  r.status = lub::sweep::CaseStatus::ok;
  r.classification = lub::sweep::CaseClass::not_converged;
  r.revision = lub::build_revision();
  r.values.assign(result_fields().size(), std::numeric_limits<double>::quiet_NaN());
  return r;
}

double thread_cpu_us() {
  timespec ts{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
  return ts.tv_sec * 1e6 + ts.tv_nsec * 1e-3;
}

struct PerCase {
  double wall_us = 0, cpu_us = 0;  // rank 0: wall and its calling thread's CPU time per case
  double finalize_s = 0;           // the study file's final rewrite
};

/// One sweep of the first `n` cases: rank 0's wall and CPU per case [µs] (0 elsewhere).
PerCase sweep_once(const Grid& g, int n, int prefetch, bool local, bool write, double case_us, const std::string& out) {
  int rank = 0;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  MPI_Barrier(MPI_COMM_WORLD);
  if (rank != 0) {
    MpiWorker w(MPI_COMM_WORLD);
    serve(w, [&](const Task& t) { return stand_in(t.case_id, rank, case_us); });
    MPI_Barrier(MPI_COMM_WORLD);
    return {};
  }
  std::deque<int> queue;
  for (int i = 0; i < n; ++i) queue.push_back(i);
  std::unique_ptr<StudyWriter> writer;
  if (write) writer = std::make_unique<StudyWriter>(out, g, std::map<int, CaseResult>{}, "");
  const auto t0 = Clock::now();
  const double c0 = thread_cpu_us();
  {
    MpiCoordinator transport(MPI_COMM_WORLD);
    Schedule s;
    s.prefetch = prefetch;
    if (local) s.local = [&](const Task& t) { return stand_in(t.case_id, 0, case_us); };
    s.record = [&](const CaseResult& r) {
      if (writer) writer->append(r);
    };
    schedule(g, queue, transport, s);
  }
  if (writer) writer->flush();
  PerCase pc;
  pc.wall_us = std::chrono::duration<double, std::micro>(Clock::now() - t0).count() / n;
  pc.cpu_us = (thread_cpu_us() - c0) / n;
  if (writer) {  // the canonical rewrite at the end, as lubsweep leaves the file
    const auto f0 = Clock::now();
    writer->finalize();
    pc.finalize_s = std::chrono::duration<double>(Clock::now() - f0).count();
  }
  MPI_Barrier(MPI_COMM_WORLD);
  return pc;
}

}  // namespace

int main(int argc, char** argv) {
  MPI_Init(&argc, &argv);
  int rank = 0, size = 1;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  MPI_Comm_size(MPI_COMM_WORLD, &size);
  std::string grid_path = std::string(LUB_SOURCE_DIR) + "/configs/grids/cheap_4096.json";
  int n = 2000;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--cases" && i + 1 < argc) n = std::atoi(argv[++i]);
    else grid_path = a;
  }
  if (size < 2) {
    if (rank == 0) std::fprintf(stderr, "bench_sweep_overhead: run it with mpirun -np 2 (or more)\n");
    MPI_Finalize();
    return 2;
  }
  const Grid g = load_grid(grid_path);
  if (n <= 0 || n > static_cast<int>(g.cases.size())) n = static_cast<int>(g.cases.size());
  const std::string out = "/tmp/bench_sweep_overhead_" + std::to_string(::getpid()) + ".h5";
  const PerCase pipelined = sweep_once(g, n, 2, false, false, 0.0, out);
  const PerCase one_by_one = sweep_once(g, n, 1, false, false, 0.0, out);
  const PerCase writing = sweep_once(g, n, 2, false, true, 0.0, out);
  if (rank == 0) {
    struct stat st {};
    const double file_bytes = ::stat(out.c_str(), &st) == 0 ? double(st.st_size) : -1.0;
    std::remove(out.c_str());
    rusage ru{};
    getrusage(RUSAGE_SELF, &ru);
    std::size_t scene_bytes = 0;
    for (int i = 0; i < n; ++i) scene_bytes += g.cases[static_cast<std::size_t>(i)].scene.size();
    // service_us: the coordinator's CPU per result with the writer (what limits rank 0);
    // round_trip_us: wall per case when each waits for its answer (latency both ways,
    // the idle waits and the service); pipelined_us: wall per case with prefetch.
    std::printf(
        "{\"ranks\": %d, \"cases\": %d, \"service_us\": %.2f, \"service_messages_us\": %.2f, "
        "\"writer_us_per_row\": %.2f, \"round_trip_us\": %.2f, \"pipelined_us\": %.2f, "
        "\"task_bytes\": %.0f, \"result_bytes\": %zu, \"file_bytes_per_case\": %.0f, "
        "\"finalize_s\": %.3f, \"rank0_max_rss_kb\": %ld}\n",
        size, n, writing.cpu_us, pipelined.cpu_us, writing.cpu_us - pipelined.cpu_us, one_by_one.wall_us,
        pipelined.wall_us, double(scene_bytes) / n, encode(stand_in(0, 0, 0.0)).size(), file_bytes / n,
        writing.finalize_s, ru.ru_maxrss);
  }
  MPI_Finalize();
  return 0;
}
