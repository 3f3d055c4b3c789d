#include "lub/sweep/mpi_transport.hpp"

#include <algorithm>
#include <cstdlib>
#include <iterator>
#include <thread>

#include <fmt/format.h>

namespace lub::sweep {

namespace {

enum Tag : int { kTagReady = 1, kTagResult = 2, kTagTask = 3, kTagStop = 4 };

using Clock = std::chrono::steady_clock;

/// Looks for a message from `source` for up to `timeout`: MPI_Iprobe, then sleeps growing
/// from 20 µs to 1 ms between probes. A negative timeout waits as long as it takes.
bool probe(MPI_Comm comm, int source, std::chrono::microseconds timeout, MPI_Status& st) {
  const auto until = Clock::now() + timeout;
  auto idle = std::chrono::microseconds(20);
  for (;;) {
    int flag = 0;
    MPI_Iprobe(source, MPI_ANY_TAG, comm, &flag, &st);
    if (flag) return true;
    if (timeout.count() >= 0) {
      const auto left = std::chrono::duration_cast<std::chrono::microseconds>(until - Clock::now());
      if (left.count() <= 0) return false;
      idle = std::min(idle, left);
    }
    std::this_thread::sleep_for(idle);
    idle = std::min(idle * 2, std::chrono::microseconds(1000));
  }
}

/// Receives the probed message as bytes.
std::string receive_bytes(MPI_Comm comm, const MPI_Status& probed) {
  int n = 0;
  MPI_Get_count(&probed, MPI_BYTE, &n);
  std::string buf(static_cast<std::size_t>(n), '\0');
  MPI_Recv(buf.data(), n, MPI_BYTE, probed.MPI_SOURCE, probed.MPI_TAG, comm, MPI_STATUS_IGNORE);
  return buf;
}

/// Waits for `request` with MPI_Test and sleeps growing from 20 µs to 1 ms (a blocking wait
/// would spin the core).
void polite_wait(MPI_Request& request) {
  auto idle = std::chrono::microseconds(20);
  for (;;) {
    int done = 0;
    MPI_Test(&request, &done, MPI_STATUS_IGNORE);
    if (done) return;
    std::this_thread::sleep_for(idle);
    idle = std::min(idle * 2, std::chrono::microseconds(1000));
  }
}

/// A worker's send: returns once the message has gone (the coordinator probes often).
void send_bytes(MPI_Comm comm, int dest, int tag, const std::string& bytes) {
  MPI_Request request;
  MPI_Isend(bytes.data(), static_cast<int>(bytes.size()), MPI_BYTE, dest, tag, comm, &request);
  polite_wait(request);
}

}  // namespace

MpiCoordinator::MpiCoordinator(MPI_Comm comm) : comm_(comm) { MPI_Comm_size(comm_, &size_); }

MpiCoordinator::~MpiCoordinator() {
  for (Send& s : sends_) polite_wait(s.request);
}

void MpiCoordinator::send(int worker, int tag, std::string bytes) {
  reap();
  Send& s = sends_.emplace_back();
  s.bytes = std::move(bytes);
  MPI_Isend(s.bytes.data(), static_cast<int>(s.bytes.size()), MPI_BYTE, worker, tag, comm_, &s.request);
}

void MpiCoordinator::reap() {
  for (auto it = sends_.begin(); it != sends_.end();) {
    int done = 0;
    MPI_Test(&it->request, &done, MPI_STATUS_IGNORE);
    it = done ? sends_.erase(it) : std::next(it);
  }
}

int MpiCoordinator::workers() const { return size_ - 1; }

std::optional<WorkerMessage> MpiCoordinator::poll(std::chrono::microseconds timeout) {
  reap();
  MPI_Status st;
  if (!probe(comm_, MPI_ANY_SOURCE, timeout, st)) return std::nullopt;
  const std::string bytes = receive_bytes(comm_, st);
  WorkerMessage m{st.MPI_SOURCE, std::nullopt};
  if (st.MPI_TAG == kTagResult) {
    try {
      m.result = decode(bytes);
    } catch (const std::exception& e) {
      throw TransportError(fmt::format("rank {}: {}", st.MPI_SOURCE, e.what()));
    }
  }
  return m;
}

void MpiCoordinator::send_task(int worker, const Task& task) { send(worker, kTagTask, encode(task)); }

void MpiCoordinator::send_stop(int worker) { send(worker, kTagStop, std::string()); }

void MpiCoordinator::abort(int code) {
  MPI_Abort(comm_, code);
  std::abort();  // MPI_Abort does not return
}

MpiWorker::MpiWorker(MPI_Comm comm) : comm_(comm) {}

void MpiWorker::send_ready() { send_bytes(comm_, 0, kTagReady, std::string()); }

std::optional<Task> MpiWorker::receive() {
  MPI_Status st;
  probe(comm_, 0, std::chrono::microseconds(-1), st);
  const std::string bytes = receive_bytes(comm_, st);
  if (st.MPI_TAG == kTagStop) return std::nullopt;
  return decode_task(bytes);
}

void MpiWorker::send_result(const CaseResult& result) { send_bytes(comm_, 0, kTagResult, encode(result)); }

int broadcast_code(MPI_Comm comm, int code) {
  MPI_Bcast(&code, 1, MPI_INT, 0, comm);
  return code;
}

void polite_barrier(MPI_Comm comm) {
  MPI_Request req;
  MPI_Ibarrier(comm, &req);
  int done = 0;
  for (int spins = 0;; ++spins) {
    MPI_Test(&req, &done, MPI_STATUS_IGNORE);
    if (done) return;
    std::this_thread::sleep_for(std::chrono::microseconds(spins < 50 ? 20 : 1000));
  }
}

}  // namespace lub::sweep
