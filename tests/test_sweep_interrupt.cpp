// A finished case reaches the study file whatever runs next, and a sweep's lock waits for a
// killed sweep that is still saving (issue 29): StudyWriter::flush_if_due writes a held row
// once its interval has passed (checked by a process killed right after, no close); the
// scheduler calls Schedule::tick while a case runs, so the coordinator looks often; a
// second OutputLock waits for the first to go. No timed assertion: time is passed in, and
// waits have generous timeouts that only a hang reaches. The signal handling itself is
// tested with real signals to a real mpirun (tests/mpi/sweep_signal_test.py).
#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <condition_variable>
#include <mutex>
#include <string>
#include <thread>

#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include "fixtures/temp_dir_test.hpp"
#include "lub/io/h5.hpp"
#include "lub/io/json_reader.hpp"
#include "lub/run/run_io.hpp"
#include "lub/sweep/case_result.hpp"
#include "lub/sweep/grid.hpp"
#include "lub/sweep/output_lock.hpp"
#include "lub/sweep/scheduler.hpp"
#include "lub/sweep/study_file.hpp"
#include "lub/sweep/transport.hpp"

using namespace lub::sweep;
using Clock = std::chrono::steady_clock;

namespace {

const std::string kScenes = std::string(LUB_SOURCE_DIR) + "/configs/scenes";

Grid two_cases() {
  return parse_grid(R"({"scene": "slider_crank.json", "study": {"max_cycles": 2, "metric_cycles": 1},
                        "axes": [{"name": "speed_rpm", "values": [5000, 500]}]})",
                    kScenes, "two.json");
}

CaseResult fake(int id) {
  CaseResult r;
  r.case_id = id;
  r.status = lub::sweep::CaseStatus::ok;
  r.revision = lub::build_revision();
  for (std::size_t i = 0; i < result_fields().size(); ++i) r.values.push_back(double(id + 1));
  return r;
}

class Interrupt : public lub_test::TempDirTest {
 protected:
  Interrupt() : TempDirTest("lub_interrupt_") {}

  /// Rows on disk after a process that appended case 0 (held: the interval is an hour),
  /// then called flush_if_due `later` after its start (if >= 0), was killed (no close).
  std::size_t rows_after_kill(const std::string& path, double later_s) {
    const Grid g = two_cases();
    const pid_t pid = ::fork();
    if (pid == 0) {
      StudyWriter w(path, g, {}, "", 3600.0);
      const auto start = Clock::now();
      w.append(fake(0));
      if (w.pending() != 1) ::_exit(3);  // held, not written
      if (w.flush_if_due(start + std::chrono::seconds(60))) ::_exit(4);  // not due yet
      if (later_s >= 0 && !w.flush_if_due(start + std::chrono::duration_cast<Clock::duration>(
                                                     std::chrono::duration<double>(later_s))))
        ::_exit(5);
      ::kill(::getpid(), SIGKILL);
      ::_exit(0);
    }
    int status = 0;
    ::waitpid(pid, &status, 0);
    EXPECT_TRUE(WIFSIGNALED(status)) << "child exit " << WEXITSTATUS(status);
    return lub::h5::File::open(path).open_table("cases").rows();
  }
};

}  // namespace

TEST_F(Interrupt, AHeldRowIsOnDiskOnceItsIntervalHasPassed) {
  EXPECT_EQ(rows_after_kill(file("held.h5"), -1), 0u) << "without the look, the held row is lost";
  EXPECT_EQ(rows_after_kill(file("due.h5"), 3601.0), 1u) << "flush_if_due after the interval writes it";
}

TEST_F(Interrupt, DefaultIntervalIsUnderOneSecond) {
  EXPECT_GT(kFlushIntervalS, 0.0);
  EXPECT_LE(kFlushIntervalS, 0.5);
}

TEST(InterruptSchedule, TheLoopLooksWhileACaseRuns) {
  // One case that runs until the scheduler has looked (tick) 5 times: without the looks it
  // would run until the 60 s safety timeout, and the test fails.
  Grid g;
  Case c;
  c.id = 0;
  c.name = "case_0";
  c.scene = "{}";
  g.cases.push_back(c);
  std::mutex m;
  std::condition_variable cv;
  int ticks_while_running = 0;
  bool running = false;
  InProcessTransport transport(0);
  Schedule s;
  s.local = [&](const Task& k) {
    std::unique_lock<std::mutex> l(m);
    running = true;
    const bool looked = cv.wait_for(l, std::chrono::seconds(60), [&] { return ticks_while_running >= 5; });
    CaseResult r;
    r.case_id = k.case_id;
    r.status = looked ? lub::sweep::CaseStatus::ok : lub::sweep::CaseStatus::error;
    return r;
  };
  s.tick = [&] {
    {
      std::lock_guard<std::mutex> l(m);
      if (running) ++ticks_while_running;
    }
    cv.notify_all();
  };
  int recorded = 0;
  s.record = [&](const CaseResult& r) {
    ++recorded;
    EXPECT_EQ(r.status, lub::sweep::CaseStatus::ok) << "the coordinator did not look while the case ran";
  };
  schedule(g, {0}, transport.coordinator(), s);
  EXPECT_EQ(recorded, 1);
  EXPECT_GE(ticks_while_running, 5);
}

TEST_F(Interrupt, ALockIsWaitedForThenTaken) {
  const std::string path = file("s.h5");
  auto first = std::make_unique<OutputLock>(path);
  EXPECT_THROW(OutputLock(path, 0.0), lub::InputError) << "held, no patience: refused at once";
  std::thread releaser([&] {
    std::this_thread::sleep_for(std::chrono::milliseconds(200));
    first.reset();
  });
  // Held when the wait starts, released 0.2 s later: taken (the patience is far longer).
  const OutputLock second(path, 120.0);
  EXPECT_TRUE(second.held());
  releaser.join();
}
