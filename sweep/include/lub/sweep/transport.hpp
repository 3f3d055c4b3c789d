// How the coordinator and the workers of a sweep talk: a small interface with two sides,
// so that the scheduling (scheduler.hpp) is the same code under MPI (mpi_transport.hpp,
// one worker per rank > 0) and in one process (InProcessTransport below: threads and
// queues, for tests without mpirun).
//
//   worker                        coordinator
//   send_ready()          ──►     poll() → {worker, no result}
//   receive() → Task      ◄──     send_task(worker, task)
//   send_result(r)        ──►     poll() → {worker, r}
//   ...
//   receive() → nullopt   ◄──     send_stop(worker)
#pragma once

#include <chrono>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "lub/sweep/case_result.hpp"

namespace lub::sweep {

/// A case handed to a worker: its id and its effective scene (canonical JSON); for a
/// continued case, the scene of the case it continues from and that case's orbit
/// (pack_seed, lub/run/run.hpp).
struct Task {
  int case_id = -1;
  std::string scene;
  int from_case = -1;               ///< the case it continues from (-1: none)
  std::string from_scene;           ///< "" : not continued
  std::vector<double> from_orbit;   ///< the packed seed of the case it continues from
  /// The grid's numeric axes as parameters of the scene: a located orbit's steady metrics
  /// are differentiated with respect to each (Grid::parameters; empty: none asked).
  std::vector<AxisParameter> parameters;
};

/// Byte encoding of a task between processes (MessagePack, like a result). decode_task
/// throws std::runtime_error on a malformed buffer.
std::string encode(const Task& t);
Task decode_task(const std::string& bytes);

/// What a worker tells the coordinator: that it is ready (its first message), or a result.
struct WorkerMessage {
  int worker = -1;                   ///< who sent it (MPI: its rank), the address of the reply
  std::optional<CaseResult> result;  ///< nullopt: ready for a task
};

/// A worker's message that cannot be read: the sweep cannot go on.
class TransportError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// The coordinator's side. Every worker sends one message (ready), then one per task it is
/// given; each message is answered with a task or with stop, after which the worker sends
/// nothing more.
class CoordinatorTransport {
 public:
  virtual ~CoordinatorTransport() = default;
  /// How many workers are at the other end (not counting the coordinator's own).
  virtual int workers() const = 0;
  /// The next worker message, waiting at most `timeout` (zero: only look). Throws
  /// TransportError if a message cannot be read.
  virtual std::optional<WorkerMessage> poll(std::chrono::microseconds timeout) = 0;
  virtual void send_task(int worker, const Task& task) = 0;
  virtual void send_stop(int worker) = 0;
  /// Ends the whole sweep now with exit status `code`, workers included (MPI_Abort): for
  /// a study file that can no longer be written.
  [[noreturn]] virtual void abort(int code) = 0;
};

/// A worker's side.
class WorkerTransport {
 public:
  virtual ~WorkerTransport() = default;
  virtual void send_ready() = 0;
  /// Waits for the coordinator's answer: a task, or nullopt for stop.
  virtual std::optional<Task> receive() = 0;
  virtual void send_result(const CaseResult& result) = 0;
};

/// Both sides in one process: workers 1..n are meant to run on threads, messages go
/// through queues. abort() throws std::runtime_error instead of ending the process.
class InProcessTransport {
 public:
  explicit InProcessTransport(int workers);
  ~InProcessTransport();
  InProcessTransport(const InProcessTransport&) = delete;
  InProcessTransport& operator=(const InProcessTransport&) = delete;

  CoordinatorTransport& coordinator();
  /// Worker `i` in 1..workers.
  WorkerTransport& worker(int i);

 private:
  struct Shared;
  class Coordinator;
  class Worker;
  std::unique_ptr<Shared> shared_;
  std::unique_ptr<Coordinator> coordinator_;
  std::vector<std::unique_ptr<Worker>> workers_;
};

}  // namespace lub::sweep
