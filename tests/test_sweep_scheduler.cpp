// Tests of the sweep's scheduling (lub/sweep/scheduler.hpp) without mpirun: the in-process
// transport (threads and queues) with N workers besides the coordinator's own, and a fake
// case runner that records who ran what. Every case runs exactly once and is recorded
// once; on_failure = abort hands out no more work; a resumed sweep runs only what is
// missing; a result message is MessagePack and a malformed one is refused.
#include "lub/sweep/scheduler.hpp"

#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <functional>
#include <map>
#include <mutex>
#include <set>
#include <string>
#include <thread>
#include <vector>

#include "lub/sweep/case_result.hpp"
#include "lub/sweep/grid.hpp"
#include "lub/sweep/transport.hpp"

using namespace lub::sweep;

namespace {

/// A grid of `n` cases (ids 0..n-1) without scenes: the fake runner needs only the ids.
Grid fake_grid(int n, FailurePolicy policy = FailurePolicy::continue_on_failure) {
  Grid g;
  g.on_failure = policy;
  for (int i = 0; i < n; ++i) {
    Case c;
    c.id = i;
    c.name = case_name(i, static_cast<std::size_t>(n));
    c.scene = "{\"case\":" + std::to_string(i) + "}";
    g.cases.push_back(c);
  }
  return g;
}

/// The fake case runner: counts the runs of each case, fails the cases in `failing`, and
/// takes a little time so that the workers overlap.
class FakeRunner {
 public:
  explicit FakeRunner(std::set<int> failing = {}) : failing_(std::move(failing)) {}
  CaseResult run(int case_id, const std::string& scene, int rank) {
    EXPECT_EQ(scene, "{\"case\":" + std::to_string(case_id) + "}") << "the task carries the case's scene";
    {
      std::lock_guard<std::mutex> l(m_);
      ++runs_[case_id];
    }
    std::this_thread::sleep_for(std::chrono::microseconds(300 + 100 * (case_id % 7)));
    CaseResult r;
    r.case_id = case_id;
    r.rank = rank;
    r.status = failing_.count(case_id) ? CaseStatus::solver_failure : CaseStatus::ok;
    r.values = {static_cast<double>(case_id)};
    return r;
  }
  std::map<int, int> runs() {
    std::lock_guard<std::mutex> l(m_);
    return runs_;
  }

 private:
  std::set<int> failing_;
  std::mutex m_;
  std::map<int, int> runs_;
};

/// Runs `queue` of `grid` on `workers` in-process workers plus the coordinator's own;
/// returns the recorded results in arrival order and whether the sweep stopped early.
struct Outcome {
  std::vector<CaseResult> recorded;
  int aborts = 0;
  bool stopped_early = false;
};

Outcome run(const Grid& grid, std::deque<int> queue, int workers, FakeRunner& runner, bool local = true,
            const std::function<void()>& at_abort = nullptr) {
  InProcessTransport transport(workers);
  std::vector<std::thread> threads;
  for (int w = 1; w <= workers; ++w)
    threads.emplace_back([&, w] {
      serve(transport.worker(w), [&, w](const Task& t) { return runner.run(t.case_id, t.scene, w); });
    });
  Outcome out;
  Schedule s;
  s.on_failure = grid.on_failure;
  if (local) s.local = [&](const Task& t) { return runner.run(t.case_id, t.scene, 0); };
  const auto coordinator = std::this_thread::get_id();
  s.record = [&](const CaseResult& r) {
    EXPECT_EQ(std::this_thread::get_id(), coordinator) << "results are recorded on the calling thread";
    out.recorded.push_back(r);
  };
  s.on_abort = [&](const CaseResult& r) {
    ++out.aborts;
    EXPECT_FALSE(r.ok());
    if (at_abort) at_abort();
  };
  out.stopped_early = schedule(grid, std::move(queue), transport.coordinator(), s);
  for (auto& t : threads) t.join();  // schedule() returns only once every worker was told to stop
  return out;
}

}  // namespace

TEST(SweepScheduler, EveryCaseRunsExactlyOnceAndIsRecorded) {
  for (int workers : {0, 1, 3}) {
    const Grid g = fake_grid(40);
    FakeRunner runner;
    const Outcome o = run(g, cases_to_run(g, {}), workers, runner);
    EXPECT_FALSE(o.stopped_early);
    EXPECT_EQ(o.aborts, 0);
    const auto runs = runner.runs();
    ASSERT_EQ(runs.size(), 40u) << workers << " workers";
    for (const auto& [id, n] : runs) EXPECT_EQ(n, 1) << "case " << id;
    std::map<int, int> recorded;
    std::set<int> ranks;
    for (const CaseResult& r : o.recorded) {
      ++recorded[r.case_id];
      ranks.insert(r.rank);
      EXPECT_EQ(r.values, std::vector<double>{static_cast<double>(r.case_id)});
    }
    EXPECT_EQ(recorded, runs);
    if (workers == 3) {
      EXPECT_GE(ranks.size(), 2u) << "the work is shared";
    }
    EXPECT_TRUE(ranks.count(0)) << "the coordinator computes too";
  }
}

TEST(SweepScheduler, WorkersAloneWhenTheCoordinatorDoesNotCompute) {
  const Grid g = fake_grid(12);
  FakeRunner runner;
  const Outcome o = run(g, cases_to_run(g, {}), 2, runner, /*local=*/false);
  EXPECT_EQ(runner.runs().size(), 12u);
  for (const CaseResult& r : o.recorded) EXPECT_NE(r.rank, 0);
  InProcessTransport none(0);
  EXPECT_THROW(schedule(g, {0}, none.coordinator(), Schedule{}), std::invalid_argument);
}

TEST(SweepScheduler, AbortStopsHandingOutWork) {
  // Case 3 fails. The cases running or handed out at that moment (at most one per other
  // worker: 3 workers and the coordinator's own) finish and are recorded; none starts after.
  const Grid g = fake_grid(200, FailurePolicy::abort_on_failure);
  FakeRunner runner({3});
  std::size_t started_at_abort = 0;
  const Outcome o = run(g, cases_to_run(g, {}), 3, runner, true,
                        [&] { started_at_abort = runner.runs().size(); });
  EXPECT_TRUE(o.stopped_early);
  EXPECT_EQ(o.aborts, 1);
  const auto runs = runner.runs();
  EXPECT_TRUE(runs.count(3));
  EXPECT_LE(runs.size(), started_at_abort + 3) << "cases handed out after the failure";
  EXPECT_LT(runs.size(), g.cases.size());
  for (const auto& [id, n] : runs) EXPECT_EQ(n, 1) << "case " << id;
  EXPECT_EQ(o.recorded.size(), runs.size()) << "every case that ran is recorded";
  std::size_t at = 0;
  while (at < o.recorded.size() && o.recorded[at].case_id != 3) ++at;
  ASSERT_LT(at, o.recorded.size());
  EXPECT_LE(o.recorded.size() - at - 1, 3u) << "results recorded after the failure";
}

TEST(SweepScheduler, ContinueRunsEverythingDespiteFailures) {
  const Grid g = fake_grid(20);
  FakeRunner runner({0, 5, 19});
  const Outcome o = run(g, cases_to_run(g, {}), 2, runner);
  EXPECT_FALSE(o.stopped_early);
  EXPECT_EQ(o.aborts, 0);
  EXPECT_EQ(o.recorded.size(), 20u);
}

TEST(SweepScheduler, ResumeSkipsTheCasesDone) {
  const Grid g = fake_grid(10);
  std::map<int, CaseResult> done;
  for (int id : {0, 3, 4, 9}) done[id].case_id = id;
  const std::deque<int> queue = cases_to_run(g, done);
  EXPECT_EQ(queue, (std::deque<int>{1, 2, 5, 6, 7, 8}));
  FakeRunner runner;
  const Outcome o = run(g, queue, 2, runner);
  const auto runs = runner.runs();
  EXPECT_EQ(runs.size(), 6u);
  for (const auto& [id, r] : done) EXPECT_FALSE(runs.count(id)) << "case " << id << " ran again";
  EXPECT_EQ(o.recorded.size(), 6u);
  // Nothing left: no case runs, every worker is stopped.
  for (int id = 0; id < 10; ++id) done[id].case_id = id;
  FakeRunner idle;
  EXPECT_TRUE(run(g, cases_to_run(g, done), 2, idle).recorded.empty());
  EXPECT_TRUE(idle.runs().empty());
}

TEST(SweepScheduler, TaskMessageRoundTrip) {
  Task t;
  t.case_id = 7;
  t.scene = "{\"a\":1}";
  const Task d = decode_task(encode(t));
  EXPECT_EQ(d.case_id, 7);
  EXPECT_EQ(d.scene, t.scene);
  EXPECT_THROW(decode_task("junk"), std::runtime_error);
}

TEST(SweepScheduler, MalformedResultMessageIsRefusedClearly) {
  CaseResult r;
  r.case_id = 2;
  r.status = CaseStatus::ok;
  r.values = {1.0, 2.0};
  const std::string bytes = encode(r);
  EXPECT_EQ(decode(bytes).values, r.values);
  try {
    Task t;
    t.case_id = 1;
    t.scene = "x";
    decode(encode(t));  // a task is not a result
    FAIL() << "a task decoded as a result";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("not a result message"), std::string::npos) << e.what();
  }
  try {
    decode(bytes.substr(0, bytes.size() / 2));
    FAIL() << "a truncated result decoded";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("malformed result message"), std::string::npos) << e.what();
  }
}

namespace {

/// A coordinator transport driven by the test: one worker that answers every task it holds
/// at once, in order, and a log of how many tasks it held when it was given each one.
class ScriptedWorker final : public CoordinatorTransport {
 public:
  int workers() const override { return 1; }
  std::optional<WorkerMessage> poll(std::chrono::microseconds) override {
    if (!ready_sent_) {
      ready_sent_ = true;
      return WorkerMessage{1, std::nullopt};
    }
    if (held_.empty()) return std::nullopt;
    CaseResult r;
    r.case_id = held_.front();
    r.status = r.case_id == fail_ ? CaseStatus::solver_failure : CaseStatus::ok;
    held_.pop_front();
    return WorkerMessage{1, r};
  }
  void send_task(int, const Task& t) override {
    held_.push_back(t.case_id);
    held_when_given.push_back(held_.size());
  }
  void send_stop(int) override { stopped_with = held_.size(), ++stops; }
  [[noreturn]] void abort(int) override { throw std::runtime_error("abort"); }

  int fail_ = -1;
  std::vector<std::size_t> held_when_given;
  std::size_t stopped_with = 99;
  int stops = 0;

 private:
  bool ready_sent_ = false;
  std::deque<int> held_;
};

}  // namespace

TEST(SweepScheduler, RemoteWorkersHoldTheirNextCaseWhileTheQueueIsLong) {
  // 10 cases, one remote worker, no local one: while at least 2 cases per worker wait, the
  // worker holds two (it starts the next without waiting for the coordinator); the last
  // ones go one at a time; it is stopped holding nothing; every case is recorded once.
  const Grid g = fake_grid(10);
  ScriptedWorker w;
  std::vector<int> recorded;
  Schedule s;
  s.record = [&](const CaseResult& r) { recorded.push_back(r.case_id); };
  EXPECT_FALSE(schedule(g, cases_to_run(g, {}), w, s));
  EXPECT_EQ(recorded, (std::vector<int>{0, 1, 2, 3, 4, 5, 6, 7, 8, 9}));
  ASSERT_EQ(w.held_when_given.size(), 10u);
  EXPECT_EQ(w.held_when_given.front(), 1u);
  EXPECT_EQ(w.held_when_given[1], 2u) << "the second case is handed out ahead";
  EXPECT_EQ(w.held_when_given.back(), 1u) << "the last case is not queued behind another";
  EXPECT_EQ(w.stops, 1);
  EXPECT_EQ(w.stopped_with, 0u);

  // on_failure = abort: one case at a time, and nothing handed out after the failure.
  Grid ga = fake_grid(10, FailurePolicy::abort_on_failure);
  ScriptedWorker wa;
  wa.fail_ = 4;
  recorded.clear();
  s.on_failure = FailurePolicy::abort_on_failure;
  EXPECT_TRUE(schedule(ga, cases_to_run(ga, {}), wa, s));
  for (std::size_t held : wa.held_when_given) EXPECT_EQ(held, 1u);
  EXPECT_EQ(recorded, (std::vector<int>{0, 1, 2, 3, 4}));
  EXPECT_EQ(wa.stopped_with, 0u);
}

// Continuation: a case is handed out only after its parent's result is in, with the orbit
// of its nearest ancestor that found one; whatever the number of workers, nothing waits
// forever.
TEST(SweepScheduler, AContinuedCaseStartsAfterItsParentFromItsNearestAncestorsOrbit) {
  // A tree over 30 cases: case i's parent is (i - 1) / 2 (case 0 the seed).
  const int n = 30;
  std::vector<int> parents(n);
  for (int i = 0; i < n; ++i) parents[static_cast<std::size_t>(i)] = i == 0 ? -1 : (i - 1) / 2;
  const std::set<int> no_orbit = {1, 4};  // cases that find none: their children continue from higher up
  for (int workers : {0, 1, 3}) {
    const Grid g = fake_grid(n);
    std::mutex m;
    std::set<int> done;
    std::map<int, int> started_from;
    auto run_task = [&](const Task& t, int rank) {
      {
        std::lock_guard<std::mutex> l(m);
        const int p = parents[static_cast<std::size_t>(t.case_id)];
        EXPECT_TRUE(p < 0 || done.count(p)) << "case " << t.case_id << " started before its parent " << p;
        started_from[t.case_id] = t.from_case;
        if (t.from_case >= 0) {
          EXPECT_EQ(t.from_orbit, std::vector<double>{static_cast<double>(t.from_case)});
          EXPECT_EQ(t.from_scene, g.cases[static_cast<std::size_t>(t.from_case)].scene);
        }
      }
      std::this_thread::sleep_for(std::chrono::microseconds(200));
      CaseResult r;
      r.case_id = t.case_id;
      r.rank = rank;
      r.status = CaseStatus::ok;
      if (!no_orbit.count(t.case_id)) r.orbit_seed = {static_cast<double>(t.case_id)};
      std::lock_guard<std::mutex> l(m);
      done.insert(t.case_id);
      return r;
    };
    InProcessTransport transport(workers);
    std::vector<std::thread> threads;
    for (int w = 1; w <= workers; ++w)
      threads.emplace_back([&, w] { serve(transport.worker(w), [&, w](const Task& t) { return run_task(t, w); }); });
    Schedule s;
    s.local = [&](const Task& t) { return run_task(t, 0); };
    s.parents = parents;
    int recorded = 0;
    s.record = [&](const CaseResult&) { ++recorded; };
    schedule(g, cases_to_run(g, {}), transport.coordinator(), s);
    for (auto& t : threads) t.join();
    EXPECT_EQ(recorded, n) << workers << " workers";
    ASSERT_EQ(started_from.size(), static_cast<std::size_t>(n));
    EXPECT_EQ(started_from[0], -1);
    EXPECT_EQ(started_from[3], 0) << "its parent 1 found no orbit: from 1's parent";
    EXPECT_EQ(started_from[9], 0) << "4 and 1 found none: from 0";
    EXPECT_EQ(started_from[5], 2);
  }
}
