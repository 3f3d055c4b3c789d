// lubsweep's interrupt handling (internal to lubsweep_lib): what SIGINT and SIGTERM do,
// as one object per process (signals.cpp; setup_process in lub/sweep/sweep.hpp installs it).
//
// The handler only records the signal. On rank 0 the coordinator's loop acts on it
// (leave), or, when rank 0 is elsewhere (start-up, the final rewrite, a wait on other
// ranks), the watchdog thread does kGrace after the signal unless rows are being written.
// A worker rank leaves kWorkerGrace after the signal, silently.
#pragma once

#include <atomic>
#include <chrono>
#include <cstddef>
#include <string>

namespace lub::sweep::detail {

class Interrupts {
 public:
  static constexpr auto kGrace = std::chrono::milliseconds(500);
  static constexpr auto kWorkerGrace = std::chrono::milliseconds(800);  // < mpirun's 1 s before SIGKILL

  /// The process's one (the one the signal handler records into).
  static Interrupts& process();

  /// The first SIGINT or SIGTERM received, 0 if none.
  int signal() const { return signal_.load(); }
  /// Records `sig` if it is the first (async-signal-safe: the handler's whole work).
  void record(int sig) noexcept;

  /// Names the study file for the interrupt line: `output`, its lock file (removed on
  /// leaving), the grid's case count and the rows already on disk. The first call only.
  void name_file(const std::string& output, const std::string& lock_file, std::size_t total, std::size_t saved);
  /// The rows on disk now.
  void saved(std::size_t rows) { saved_ = rows; }

  /// Rows are being written while one lives: the watchdog does not end the process meanwhile.
  class Writing {
   public:
    explicit Writing(Interrupts& i) : i_(i) { ++i_.writing_; }
    ~Writing() { --i_.writing_; }
    Writing(const Writing&) = delete;
    Writing& operator=(const Writing&) = delete;

   private:
    Interrupts& i_;
  };
  Writing writing() { return Writing(*this); }

  /// Prints the interrupt line, removes the lock file (still held) and ends the process
  /// with 128 + `sig`, without waiting for a case that runs (no destructors, no
  /// MPI_Finalize: the launcher ends the other ranks).
  [[noreturn]] void leave(int sig);

  /// The watchdog thread's body: waits for a signal, then leaves as the header says.
  [[noreturn]] void watch(int rank);

 private:
  Interrupts() = default;

  std::atomic<int> signal_{0};          // the first SIGINT or SIGTERM
  std::atomic<int> writing_{0};         // > 0 while rows are appended to the study file
  std::atomic<bool> leaving_{false};    // one thread prints the line and ends the process
  std::atomic<std::size_t> saved_{0};   // rows on disk, for the line
  std::atomic<std::size_t> total_{0};
  std::atomic<bool> have_file_{false};  // file_ and lock_file_ are set (once, before have_file_)
  const std::string* file_ = nullptr;   // never freed: the watchdog may read them at exit
  const std::string* lock_file_ = nullptr;
};

}  // namespace lub::sweep::detail
