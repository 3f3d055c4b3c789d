// The sweep's transport over MPI (transport.hpp): rank 0 coordinates, every other rank of
// the communicator is a worker. Waits poll (MPI_Iprobe) with short sleeps instead of
// blocking, because Open MPI's blocking receive spins a core at 100 % and rank 0 shares
// its core with its own worker thread.
#pragma once

#include <mpi.h>

#include "lub/sweep/transport.hpp"

namespace lub::sweep {

class MpiCoordinator final : public CoordinatorTransport {
 public:
  /// Rank 0 of `comm`; the workers are ranks 1..size-1.
  explicit MpiCoordinator(MPI_Comm comm);
  int workers() const override;
  std::optional<WorkerMessage> poll(std::chrono::microseconds timeout) override;
  void send_task(int worker, const Task& task) override;
  void send_stop(int worker) override;
  [[noreturn]] void abort(int code) override;

 private:
  MPI_Comm comm_;
  int size_ = 1;
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
