#include "lub/sweep/scheduler.hpp"

#include <algorithm>
#include <chrono>
#include <condition_variable>
#include <memory>
#include <mutex>
#include <optional>
#include <stdexcept>
#include <set>
#include <thread>

namespace lub::sweep {

namespace {

/// The coordinator's own computing: one case at a time on a thread, so that the calling
/// thread stays free to serve the other workers and to record results.
class LocalWorker {
 public:
  explicit LocalWorker(std::function<CaseResult(const Task&)> run)
      : run_(std::move(run)), thread_([this] { loop(); }) {}
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
  void give(Task t) {
    {
      std::lock_guard<std::mutex> l(m_);
      task_ = std::move(t);
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
      cv_.wait(l, [this] { return task_.has_value() || quit_; });
      if (!task_) return;
      const Task t = std::move(*task_);
      task_.reset();
      l.unlock();
      CaseResult r = run_(t);
      l.lock();
      result_ = std::move(r);
      done_cv_.notify_one();
    }
  }

  std::function<CaseResult(const Task&)> run_;
  std::mutex m_;
  std::condition_variable cv_, done_cv_;
  bool quit_ = false, busy_ = false;
  std::optional<Task> task_;
  std::optional<CaseResult> result_;
  std::thread thread_;  // last: starts after the members it uses
};

/// Which queued case may start (continuation: once its parent's result is in) and the task
/// that carries its nearest ancestor's orbit.
class ContinuationOrder {
 public:
  ContinuationOrder(const Grid& grid, const Schedule& s) : grid_(grid), parents_(s.parents), orbits_(s.finished) {}

  /// Takes the first ready case off the queue, as a task; nullopt while none is ready.
  std::optional<Task> next(std::deque<int>& queue) {
    if (queue.empty()) return std::nullopt;
    auto it = std::find_if(queue.begin(), queue.end(), [this](int id) {
      return parent(id) < 0 || orbits_.count(parent(id)) > 0;
    });
    // Nothing ready and nothing running: no result will make one ready (a parent outside
    // the queue): the first case goes without its parent.
    if (it == queue.end() && running_ == 0) it = queue.begin();
    if (it == queue.end()) return std::nullopt;
    const int id = *it;
    queue.erase(it);
    ++running_;
    return task_of(id);
  }
  void done(const CaseResult& r) {
    --running_;
    orbits_[r.case_id] = r.orbit_seed;
  }

 private:
  int parent(int id) const { return parents_.empty() ? -1 : parents_.at(static_cast<std::size_t>(id)); }
  Task task_of(int id) const {
    const Case& c = grid_.cases.at(static_cast<std::size_t>(id));
    Task t;
    t.case_id = c.id;
    t.scene = c.scene;
    t.parameters = grid_.parameters;
    // The nearest ancestor with an orbit (a parent that found none passes on its own start).
    for (int p = parent(id); p >= 0; p = parent(p)) {
      const auto it = orbits_.find(p);
      if (it != orbits_.end() && !it->second.empty()) {
        t.from_case = p;
        t.from_scene = grid_.cases.at(static_cast<std::size_t>(p)).scene;
        t.from_orbit = it->second;
        break;
      }
    }
    return t;
  }

  const Grid& grid_;
  const std::vector<int>& parents_;
  std::map<int, std::vector<double>> orbits_;  ///< the orbits of the cases done so far
  int running_ = 0;                            ///< cases handed out and not yet returned
};

}  // namespace

std::deque<int> cases_to_run(const Grid& grid, const std::map<int, CaseResult>& done) {
  std::deque<int> queue;
  for (const Case& c : grid.cases)
    if (!done.count(c.id)) queue.push_back(c.id);
  return queue;
}

bool schedule(const Grid& grid, std::deque<int> queue, CoordinatorTransport& transport, const Schedule& s) {
  if (!s.local && transport.workers() == 0) throw std::invalid_argument("schedule: no worker to run the cases");
  bool aborting = false;
  // A result is judged first (a failure under abort stops the hand-out at once), its worker
  // given its next case, and only then the result recorded: the worker computes while the
  // coordinator writes.
  auto judge = [&](const CaseResult& r) {
    if (!r.ok() && s.on_failure == FailurePolicy::abort_on_failure && !aborting) {
      aborting = true;
      if (s.on_abort) s.on_abort(r);
    }
  };
  ContinuationOrder order(grid, s);
  auto next = [&]() -> std::optional<Task> { return aborting ? std::nullopt : order.next(queue); };
  const auto note = [&](const CaseResult& r) { order.done(r); };

  std::optional<LocalWorker> local;
  if (s.local) local.emplace(s.local);
  const auto local_busy = [&] { return local && local->busy(); };
  int remote_active = transport.workers();
  // Prefetch: a remote worker holds the case it computes and, while the queue is long, the
  // next one, so that it starts that one the moment it sends a result instead of waiting a
  // round trip and the coordinator's next look (up to ~1 ms each with the idle waits below;
  // 13 % of a 15 ms case). Near the end of the queue (fewer than two cases per worker
  // left) one case each: a long case queued behind another must not idle the others. Not
  // with on_failure = abort: there a failure must stop every case not yet started, and a
  // queued case could start before the stop reaches its worker.
  const int depth = s.on_failure == FailurePolicy::abort_on_failure ? 1 : s.prefetch;
  std::vector<int> outstanding(static_cast<std::size_t>(transport.workers()) + 1, 0);  // by worker id
  std::set<int> ready_workers;  // workers that have said they are ready
  const auto top_up = [&](int worker) {
    int& held = outstanding.at(static_cast<std::size_t>(worker));
    const auto long_queue = [&] { return queue.size() >= 2 * static_cast<std::size_t>(transport.workers()); };
    while (held < 1 || (held < depth && long_queue())) {
      std::optional<Task> t = next();
      if (!t) break;
      transport.send_task(worker, *t);
      ++held;
    }
    if (held == 0 && (queue.empty() || aborting)) {
      transport.send_stop(worker);
      --remote_active;
      outstanding.at(static_cast<std::size_t>(worker)) = -1;  // stopped
    }
  };
  // Workers waiting for a case whose parent is still running: topped up after each result.
  const auto top_up_waiting = [&] {
    for (int w = 1; w < static_cast<int>(outstanding.size()); ++w)
      if (outstanding[static_cast<std::size_t>(w)] == 0 && ready_workers.count(w)) top_up(w);
  };
  // Idle waits grow from 50 µs to 1 ms: a worker waiting for its next case waits at most
  // ~1 ms, and the polling costs the coordinator's core ~1 % (Open MPI would spin at 100 %).
  // No wait is longer, so s.tick runs at least every ~1 ms.
  auto idle = std::chrono::microseconds(50);
  for (;;) {
    if (s.tick) s.tick();
    bool progressed = false;
    if (local) {
      std::optional<CaseResult> r = local->take();
      if (r) judge(*r), note(*r), progressed = true;
      if (r && remote_active > 0) top_up_waiting();
      if (!local->busy())
        if (std::optional<Task> t = next()) local->give(std::move(*t)), progressed = true;
      if (r) s.record(*r);
    }
    if (remote_active > 0) {
      // While the local worker computes, only look: its result must not wait for a message.
      const auto wait = progressed || local_busy() ? std::chrono::microseconds(0) : idle;
      if (auto m = transport.poll(wait)) {
        progressed = true;
        ready_workers.insert(m->worker);
        if (m->result) {
          judge(*m->result);
          note(*m->result);
          --outstanding.at(static_cast<std::size_t>(m->worker));
        }
        top_up(m->worker);
        if (m->result) top_up_waiting();
        if (m->result) s.record(*m->result);
      }
    }
    if (remote_active == 0 && !local_busy() && (queue.empty() || aborting)) break;
    // Every remote worker idle, waiting for parents that the local worker runs: once the
    // queue is empty (or aborting) they are told to stop.
    if (remote_active > 0 && (queue.empty() || aborting)) top_up_waiting();
    if (progressed) {
      idle = std::chrono::microseconds(50);
    } else {
      if (local_busy()) local->wait_for_result(idle);
      idle = std::min(idle * 2, std::chrono::microseconds(1000));
    }
  }
  return aborting;
}

void serve(WorkerTransport& transport, const std::function<CaseResult(const Task&)>& run) {
  transport.send_ready();
  while (const std::optional<Task> task = transport.receive()) transport.send_result(run(*task));
}

}  // namespace lub::sweep
