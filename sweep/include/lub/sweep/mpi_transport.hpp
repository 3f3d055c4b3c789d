// The sweep's transport over MPI (transport.hpp): rank 0 coordinates, every other rank of
// the communicator is a worker. Waits poll (MPI_Iprobe) with short sleeps instead of
// blocking, because Open MPI's blocking receive spins a core at 100 % and rank 0 shares
// its core with its own worker thread. The coordinator's sends do not block either: a task
// larger than Open MPI's eager limit (a scene is ~2.6 kB of JSON) goes by rendezvous, and a
// blocking MPI_Send of a case handed out ahead (Schedule::prefetch) would spin rank 0's core
// until the worker finishes the case it computes; they are MPI_Isend, their buffers kept
// until MPI_Test says they have gone.
#pragma once

#include <mpi.h>

#include <list>
#include <string>

#include "lub/sweep/transport.hpp"

namespace lub::sweep {

class MpiCoordinator final : public CoordinatorTransport {
 public:
  /// Rank 0 of `comm`; the workers are ranks 1..size-1.
  explicit MpiCoordinator(MPI_Comm comm);
  /// Waits (politely) until every send has gone.
  ~MpiCoordinator() override;
  MpiCoordinator(const MpiCoordinator&) = delete;
  MpiCoordinator& operator=(const MpiCoordinator&) = delete;
  int workers() const override;
  std::optional<WorkerMessage> poll(std::chrono::microseconds timeout) override;
  void send_task(int worker, const Task& task) override;
  void send_stop(int worker) override;
  [[noreturn]] void abort(int code) override;

 private:
  struct Send {
    MPI_Request request = MPI_REQUEST_NULL;
    std::string bytes;  // kept until the send completes
  };
  void send(int worker, int tag, std::string bytes);
  void reap();  // forgets the sends that have completed
  MPI_Comm comm_;
  int size_ = 1;
  std::list<Send> sends_;  // in flight (a list: the buffers must not move)
};

class MpiWorker final : public WorkerTransport {
 public:
  /// A rank > 0 of `comm`, talking to rank 0.
  explicit MpiWorker(MPI_Comm comm);
  void send_ready() override;
  std::optional<Task> receive() override;
  void send_result(const CaseResult& result) override;

 private:
  MPI_Comm comm_;
};

/// Rank 0's `code`, on every rank of `comm`.
int broadcast_code(MPI_Comm comm, int code);
/// A barrier that sleeps while it waits.
void polite_barrier(MPI_Comm comm);

}  // namespace lub::sweep
