#include "lub/sweep/transport.hpp"

#include <condition_variable>
#include <cstdint>
#include <deque>
#include <mutex>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

namespace lub::sweep {

using nlohmann::json;

std::string encode(const Task& t) {
  json parameters = json::array();
  for (const AxisParameter& p : t.parameters)
    parameters.push_back({{"name", p.name}, {"unit", p.unit}, {"pointer", p.pointer},
                          {"base_pointer", p.base_pointer}, {"sign", p.sign}});
  const std::vector<std::uint8_t> bytes =
      json::to_msgpack({{"case_id", t.case_id}, {"scene", t.scene}, {"from_case", t.from_case},
                        {"from_scene", t.from_scene}, {"from_orbit", t.from_orbit}, {"parameters", parameters}});
  return std::string(bytes.begin(), bytes.end());
}

Task decode_task(const std::string& bytes) {
  try {
    const json m = json::from_msgpack(bytes);
    if (!m.is_object() || !m.contains("case_id") || !m["case_id"].is_number_integer() || !m.contains("scene") ||
        !m["scene"].is_string())
      throw std::runtime_error("malformed task message: needs an integer case_id and a string scene");
    Task t{m["case_id"].get<int>(), m["scene"].get<std::string>(), -1, "", {}, {}};
    if (m.contains("from_case")) t.from_case = m["from_case"].get<int>();
    if (m.contains("from_scene")) t.from_scene = m["from_scene"].get<std::string>();
    if (m.contains("from_orbit")) t.from_orbit = m["from_orbit"].get<std::vector<double>>();
    if (m.contains("parameters"))
      for (const json& p : m["parameters"])
        t.parameters.push_back({p.at("name").get<std::string>(), p.at("unit").get<std::string>(),
                                p.at("pointer").get<std::string>(), p.at("base_pointer").get<std::string>(),
                                p.at("sign").get<double>()});
    return t;
  } catch (const json::exception& e) {
    throw std::runtime_error(std::string("malformed task message: ") + e.what());
  }
}

namespace {

/// A queue that one side fills and the other drains, waiting while it is empty.
template <class T>
class Mailbox {
 public:
  void put(T v) {
    {
      std::lock_guard<std::mutex> l(m_);
      q_.push_back(std::move(v));
    }
    cv_.notify_one();
  }
  /// The oldest item, waiting at most `timeout`.
  std::optional<T> take(std::chrono::microseconds timeout) {
    std::unique_lock<std::mutex> l(m_);
    if (!cv_.wait_for(l, timeout, [this] { return !q_.empty(); })) return std::nullopt;
    return pop();
  }
  /// The oldest item, waiting as long as it takes.
  T take() {
    std::unique_lock<std::mutex> l(m_);
    cv_.wait(l, [this] { return !q_.empty(); });
    return pop();
  }

 private:
  T pop() {
    T v = std::move(q_.front());
    q_.pop_front();
    return v;
  }
  std::mutex m_;
  std::condition_variable cv_;
  std::deque<T> q_;
};

}  // namespace

struct InProcessTransport::Shared {
  explicit Shared(int n) : to_worker(static_cast<std::size_t>(n) + 1) {}
  Mailbox<WorkerMessage> to_coordinator;
  std::vector<Mailbox<std::optional<Task>>> to_worker;  ///< [1..n]; nullopt: stop
};

class InProcessTransport::Coordinator final : public CoordinatorTransport {
 public:
  Coordinator(Shared& s, int n) : s_(s), n_(n) {}
  int workers() const override { return n_; }
  std::optional<WorkerMessage> poll(std::chrono::microseconds timeout) override {
    return s_.to_coordinator.take(timeout);
  }
  void send_task(int worker, const Task& task) override { box(worker).put(task); }
  void send_stop(int worker) override { box(worker).put(std::nullopt); }
  [[noreturn]] void abort(int code) override {
    throw std::runtime_error(fmt::format("in-process sweep aborted (exit status {})", code));
  }

 private:
  Mailbox<std::optional<Task>>& box(int worker) { return s_.to_worker.at(static_cast<std::size_t>(worker)); }
  Shared& s_;
  int n_;
};

class InProcessTransport::Worker final : public WorkerTransport {
 public:
  Worker(Shared& s, int id) : s_(s), id_(id) {}
  void send_ready() override { s_.to_coordinator.put(WorkerMessage{id_, std::nullopt}); }
  std::optional<Task> receive() override { return s_.to_worker.at(static_cast<std::size_t>(id_)).take(); }
  void send_result(const CaseResult& result) override { s_.to_coordinator.put(WorkerMessage{id_, result}); }

 private:
  Shared& s_;
  int id_;
};

InProcessTransport::InProcessTransport(int workers)
    : shared_(std::make_unique<Shared>(workers)), coordinator_(std::make_unique<Coordinator>(*shared_, workers)) {
  for (int i = 1; i <= workers; ++i) workers_.push_back(std::make_unique<Worker>(*shared_, i));
}

InProcessTransport::~InProcessTransport() = default;

CoordinatorTransport& InProcessTransport::coordinator() { return *coordinator_; }

WorkerTransport& InProcessTransport::worker(int i) { return *workers_.at(static_cast<std::size_t>(i - 1)); }

}  // namespace lub::sweep
