// lubsweep's signals (lub/sweep/sweep.hpp: end_with_launcher, setup_process): the
// interrupt object (signals.hpp), its handler and watchdog, and the parent-death signal
// under an MPI launcher.
#include "signals.hpp"

#include <fmt/format.h>

#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <thread>
#include <sys/prctl.h>
#include <unistd.h>

#include "lub/sweep/sweep.hpp"

namespace lub::sweep {

namespace detail {

static_assert(std::atomic<int>::is_always_lock_free, "the signal handler stores into an atomic int");

Interrupts& Interrupts::process() {
  static Interrupts* const one = new Interrupts();  // never freed: the watchdog may run at exit
  return *one;
}

void Interrupts::record(int sig) noexcept {
  int none = 0;
  signal_.compare_exchange_strong(none, sig);
}

void Interrupts::name_file(const std::string& output, const std::string& lock_file, std::size_t total,
                           std::size_t saved) {
  if (have_file_) return;
  file_ = new std::string(output);
  lock_file_ = new std::string(lock_file);
  total_ = total;
  saved_ = saved;
  have_file_ = true;
}

void Interrupts::leave(int sig) {
  if (leaving_.exchange(true))
    for (;;) std::this_thread::sleep_for(std::chrono::seconds(1));  // the other thread leaves
  if (have_file_) {
    fmt::print(stderr, "lubsweep: interrupted: {} of {} cases saved in {}; run the same command to resume\n",
               saved_.load(), total_.load(), *file_);
    ::unlink(lock_file_->c_str());
  } else {
    fmt::print(stderr, "lubsweep: interrupted; nothing written\n");
  }
  std::fflush(stdout);
  std::fflush(stderr);
  std::_Exit(kExitInterrupted + sig);
}

/// mpirun, signalled, sends SIGTERM to every rank at once and SIGKILL to all as soon as one
/// has died: the workers' grace lets rank 0 write its rows and end first.
void Interrupts::watch(int rank) {
  while (signal_.load() == 0) std::this_thread::sleep_for(std::chrono::milliseconds(20));
  if (rank != 0) {
    std::this_thread::sleep_for(kWorkerGrace);
    std::_Exit(kExitInterrupted + signal_.load());
  }
  std::this_thread::sleep_for(kGrace);
  while (writing_.load() > 0) std::this_thread::sleep_for(std::chrono::milliseconds(5));
  leave(signal_.load());
}

}  // namespace detail

namespace {

extern "C" void on_interrupt(int sig) { detail::Interrupts::process().record(sig); }

bool under_launcher() {
  for (const char* v : {"OMPI_COMM_WORLD_SIZE", "PMIX_RANK", "PMI_RANK"})
    if (std::getenv(v)) return true;
  return false;
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
  detail::Interrupts& interrupts = detail::Interrupts::process();  // made before the handler can run
  struct sigaction sa{};
  sa.sa_handler = on_interrupt;
  sigemptyset(&sa.sa_mask);
  sa.sa_flags = SA_RESTART;
  ::sigaction(SIGINT, &sa, nullptr);
  ::sigaction(SIGTERM, &sa, nullptr);
  std::signal(SIGPIPE, SIG_IGN);  // stderr may be a pipe to a launcher that is gone
  std::thread([&interrupts, rank] { interrupts.watch(rank); }).detach();
}

}  // namespace lub::sweep
