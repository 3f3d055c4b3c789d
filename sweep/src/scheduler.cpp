#include "lub/sweep/scheduler.hpp"

#include <algorithm>
#include <chrono>
#include <condition_variable>
#include <memory>
#include <mutex>
#include <optional>
#include <stdexcept>
#include <thread>

namespace lub::sweep {

namespace {

/// The coordinator's own computing: one case at a time on a thread, so that the calling
/// thread stays free to serve the other workers and to record results.
class LocalWorker {
 public:
  explicit LocalWorker(std::function<CaseResult(const Case&)> run)
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
  void give(const Case& c) {
    {
      std::lock_guard<std::mutex> l(m_);
      task_ = &c;
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
      cv_.wait(l, [this] { return task_ != nullptr || quit_; });
      if (task_ == nullptr) return;
      const Case* c = task_;
      task_ = nullptr;
      l.unlock();
      CaseResult r = run_(*c);
      l.lock();
      result_ = std::move(r);
      done_cv_.notify_one();
    }
  }

  std::function<CaseResult(const Case&)> run_;
  std::mutex m_;
  std::condition_variable cv_, done_cv_;
  bool quit_ = false, busy_ = false;
  const Case* task_ = nullptr;
  std::optional<CaseResult> result_;
  std::thread thread_;  // last: starts after the members it uses
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
  auto record = [&](const CaseResult& r) {
    s.record(r);
    if (!r.ok() && s.on_failure == FailurePolicy::abort_on_failure && !aborting) {
      aborting = true;
      if (s.on_abort) s.on_abort(r);
    }
  };
  auto next = [&]() -> const Case* {
    if (aborting || queue.empty()) return nullptr;
    const int id = queue.front();
    queue.pop_front();
    return &grid.cases.at(static_cast<std::size_t>(id));
  };

  std::optional<LocalWorker> local;
  if (s.local) local.emplace(s.local);
  const auto local_busy = [&] { return local && local->busy(); };
  int remote_active = transport.workers();
  // Idle waits grow from 50 µs to 1 ms: a worker waiting for its next case waits at most
  // ~1 ms, and the polling costs the coordinator's core ~1 % (Open MPI would spin at 100 %).
  auto idle = std::chrono::microseconds(50);
  for (;;) {
    bool progressed = false;
    if (local) {
      if (auto r = local->take()) {
        record(*r);
        progressed = true;
      }
      if (!local->busy())
        if (const Case* c = next()) local->give(*c), progressed = true;
    }
    if (remote_active > 0) {
      // While the local worker computes, only look: its result must not wait for a message.
      const auto wait = progressed || local_busy() ? std::chrono::microseconds(0) : idle;
      if (auto m = transport.poll(wait)) {
        progressed = true;
        if (m->result) record(*m->result);
        if (const Case* c = next()) {
          transport.send_task(m->worker, Task{c->id, c->scene});
        } else {
          transport.send_stop(m->worker);
          --remote_active;
        }
      }
    }
    if (remote_active == 0 && !local_busy() && (queue.empty() || aborting)) break;
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
