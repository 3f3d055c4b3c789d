// lubsweep refine (lub/sweep/refine.hpp): rank 0 reads the study (refine_study.cpp), plans
// each round from what the file holds and the rounds before (Planner), hands the round's
// new cases to every rank (scheduler.hpp over MPI, a fresh coordinator each round, while the
// other ranks serve it) and appends their rows to /refinement/cases in case-id order.
#include "lub/sweep/refine.hpp"

#include <fmt/format.h>
#include <mpi.h>

#include <chrono>
#include <csignal>
#include <cstdio>
#include <deque>
#include <map>
#include <optional>

#include "grid_parts.hpp"
#include "lub/io/json_reader.hpp"
#include "lub/run/run_io.hpp"
#include "lub/scene/scene.hpp"
#include "lub/sweep/hash.hpp"
#include "lub/sweep/mpi_transport.hpp"
#include "lub/sweep/output_lock.hpp"
#include "lub/sweep/progress.hpp"
#include "lub/sweep/scheduler.hpp"
#include "lub/sweep/study_file.hpp"
#include "lub/sweep/sweep.hpp"
#include "refine_parts.hpp"
#include "signals.hpp"
#include "study_parts.hpp"

namespace lub::sweep {

namespace {

using nlohmann::json;
using detail::RefinedRow;
using detail::RefineStudy;
using Clock = std::chrono::steady_clock;

/// Rank 0's word to the others before each round: another round to serve, or the end.
constexpr int kServeRound = 1;
constexpr int kNoMoreRounds = 0;
/// Rank 0's word after its checks when there is nothing to do (exit 0 on every rank).
constexpr int kNothingToDo = -1;

/// A case a round adds: the edge it refines, its id, whether the file holds its row already.
struct Planned {
  RefineCandidate candidate;
  int id = -1;
  bool held = false;
};

/// The refinement's rounds, each from the study's rows and the refinement's so far.
class Planner {
 public:
  Planner(RefineStudy& s, std::vector<RefinedRow> held, double tolerance, long budget)
      : s_(s), held_(std::move(held)), tolerance_(tolerance), budget_(budget), frontier_(s.lattice) {}

  /// The next round's cases, best first (none: the budget is spent or nothing scores). Each
  /// is added to the study's grid; a case the file holds, with its point. Throws
  /// lub::InputError if the file holds another case in its place.
  std::vector<Planned> next_round() {
    std::vector<Planned> out;
    if (spent_ >= budget_) return out;
    std::vector<RefineCandidate> candidates = scored(frontier_);
    rank_candidates(candidates);
    if (static_cast<long>(candidates.size()) > budget_ - spent_)
      candidates.resize(static_cast<std::size_t>(budget_ - spent_));
    std::vector<RefineEdge> halves;
    for (const RefineCandidate& c : candidates) {
      const std::size_t place = static_cast<std::size_t>(spent_++);
      Case k = make_case(c, static_cast<int>(s_.study_cases + place));
      const bool held = place < held_.size();
      if (held && held_[place].point.hash != k.hash)
        throw InputError(fmt::format("{}: /refinement/cases row {} holds another case than this refinement selects "
                                     "({} at {} between cases {} and {}): delete /refinement to start again",
                                     s_.path, place, k.name, s_.grid.axes.at(c.edge.axis).name, c.edge.a, c.edge.b));
      RefinePoint p = held ? held_[place].point : RefinePoint{};
      p.id = k.id;
      p.scene = k.scene;
      p.axis_values = k.axis_values;
      s_.points.push_back(std::move(p));
      halves.push_back({c.edge.a, k.id, c.edge.axis, c.edge.round + 1});
      halves.push_back({k.id, c.edge.b, c.edge.axis, c.edge.round + 1});
      out.push_back({c, k.id, held});
      s_.grid.cases.push_back(std::move(k));
    }
    frontier_ = std::move(halves);
    rounds_ += !out.empty();
    return out;
  }
  /// A new case's row, written: its point, for the next round.
  void absorb(RefinePoint p) {
    p.scene = s_.points.at(static_cast<std::size_t>(p.id)).scene;
    s_.points.at(static_cast<std::size_t>(p.id)) = std::move(p);
  }
  long spent() const { return spent_; }
  int rounds() const { return rounds_; }

 private:
  double lambda(int id, int axis) const {
    const json& v = s_.points.at(static_cast<std::size_t>(id)).axis_values.at(static_cast<std::size_t>(axis));
    return v.is_number() ? v.get<double>() : std::nan("");
  }
  std::vector<RefineCandidate> scored(const std::vector<RefineEdge>& edges) const {
    std::vector<RefineCandidate> out;
    for (const RefineEdge& e : edges) {
      const double la = lambda(e.a, e.axis), lb = lambda(e.b, e.axis);
      if (!(std::isfinite(la) && std::isfinite(lb))) continue;
      const auto c = score_edge(e, s_.points.at(static_cast<std::size_t>(e.a)), s_.points.at(static_cast<std::size_t>(e.b)),
                                la, lb, s_.parameter.at(static_cast<std::size_t>(e.axis)), tolerance_);
      if (c) out.push_back(*c);
    }
    return out;
  }
  /// The case at the edge's midpoint: case_a's scene with the axis there, and no channels
  /// (a refinement case keeps no series).
  Case make_case(const RefineCandidate& c, int id) const {
    const Axis& axis = s_.grid.axes.at(static_cast<std::size_t>(c.edge.axis));
    const double value = refine_midpoint(lambda(c.edge.a, c.edge.axis), lambda(c.edge.b, c.edge.axis),
                                         s_.geometric.at(static_cast<std::size_t>(c.edge.axis)));
    json scene = json::parse(s_.points.at(static_cast<std::size_t>(c.edge.a)).scene);
    detail::apply_value(scene, axis, json(value), "refine: " + axis.name);
    if (scene.contains("outputs") && scene["outputs"].is_object()) scene["outputs"]["channels"] = json::array();
    Case k;
    k.id = id;
    k.name = case_name(id, static_cast<std::size_t>(id) + 1);
    k.scene = canonical_json(scene);
    k.hash = sha256_hex(k.scene);
    try {  // what the sweep asks of a case's scene, it asks the parsed scene
      k.steady = parse_scene(scene).simulation.steady;
    } catch (const InputError&) {  // the run says so: invalid_scene
    }
    k.axis_values = s_.points.at(static_cast<std::size_t>(c.edge.a)).axis_values;
    k.axis_values.at(static_cast<std::size_t>(c.edge.axis)) = value;
    k.label = fmt::format("{}={:.6g} between {} and {} ({})", axis.name, value,
                          s_.grid.cases.at(static_cast<std::size_t>(c.edge.a)).name,
                          s_.grid.cases.at(static_cast<std::size_t>(c.edge.b)).name, name_of(c.reason));
    return k;
  }

  RefineStudy& s_;
  std::vector<RefinedRow> held_;
  double tolerance_;
  long budget_;
  std::vector<RefineEdge> frontier_;
  long spent_ = 0;
  int rounds_ = 0;
};

/// Appends rows to /refinement/cases, creating the group on the first (the file is not
/// opened for writing before).
class RefineWriter {
 public:
  RefineWriter(const RefineStudy& s, double tolerance) : s_(s), tolerance_(tolerance) {}
  void append(const h5::Row& row) {
    if (!file_.valid()) open();
    table_.append(row);  // and flushes: a killed refinement keeps every row written
  }
  const std::vector<h5::Column>& columns() {
    if (columns_.empty()) {
      columns_ = case_columns(s_.grid);
      for (const h5::Column& c : detail::refine_extra_columns()) columns_.push_back(c);
    }
    return columns_;
  }

 private:
  void open() {
    file_ = h5::File::open(s_.path, h5::File::Mode::ReadWrite);
    if (file_.exists("refinement/cases")) {
      table_ = file_.open_table("refinement/cases");
      return;
    }
    h5::Group g = file_.require_group("refinement");
    g.set_attribute(detail::kToleranceAttribute, tolerance_);
    g.set_attribute("study_cases", static_cast<std::int64_t>(s_.study_cases));
    g.set_attribute("long_name",
                    "cases added by lubsweep refine between lattice neighbours whose labels differ or whose steady "
                    "metrics change faster than their sensitivities predict (docs/guide/lubsweep.md)");
    table_ = detail::create_cases_table(g, s_.grid, detail::refine_extra_columns());
  }

  const RefineStudy& s_;
  double tolerance_;
  h5::File file_;
  h5::Table table_;
  std::vector<h5::Column> columns_;
};

/// What a run of rounds did, for its last line.
struct Tally {
  long new_rows = 0;
  long long periods = 0;
};

/// The periods a result integrated: its steady stage's and its sensitivities'.
long long periods_of(const CaseResult& r) {
  const auto fields = result_fields();
  long long p = r.sensitivity_periods;
  for (std::size_t i = 0; i < fields.size() && i < r.values.size(); ++i)
    if (fields[i].name == "periods_integrated" && std::isfinite(r.values[i])) p += static_cast<long long>(r.values[i]);
  return p;
}

/// Runs one round's new cases (`queue`, consecutive ids) on every rank; their rows go to
/// the file in id order as soon as every lower id's is in.
void run_round(MPI_Comm comm, const Options& o, RefineStudy& s, Planner& plan,
               const std::map<int, RefineCandidate>& chosen, std::deque<int> queue, RefineWriter& writer,
               Progress& progress, Clock::time_point t0, Tally& tally) {
  MpiCoordinator transport(comm);
  detail::Interrupts& interrupts = detail::Interrupts::process();
  std::map<int, CaseResult> waiting;
  int next = queue.front();
  Schedule sc;
  sc.local = [](const Task& t) { return run_task(t, 0); };
  // A case whose scene asks for continuation starts from its edge's lower end's orbit, as
  // the study's cases start from a neighbour's: a parent fixed before the round runs.
  sc.parents.assign(s.grid.cases.size(), -1);
  for (const auto& [id, c] : chosen)
    if (s.grid.cases.at(static_cast<std::size_t>(id)).steady == SteadyMethod::continuation) {
      sc.parents.at(static_cast<std::size_t>(id)) = c.edge.a;
      sc.finished[c.edge.a] = s.points.at(static_cast<std::size_t>(c.edge.a)).orbit_seed;
    }
  sc.tick = [&] {
    if (const int sig = interrupts.signal()) {
      for (int w = 1; w <= transport.workers(); ++w) transport.send_stop(w);
      interrupts.leave(sig);  // every row written is on disk (each append flushes)
    }
  };
  sc.record = [&](const CaseResult& r) {
    const std::string line = progress.record(s.grid.cases.at(static_cast<std::size_t>(r.case_id)), r,
                                             std::chrono::duration<double>(Clock::now() - t0).count());
    if (!o.quiet) fmt::print(stderr, "lubsweep: {}\n", line);
    tally.periods += periods_of(r);
    waiting[r.case_id] = r;
    for (auto it = waiting.find(next); it != waiting.end(); it = waiting.find(next)) {
      const h5::Row row = detail::refine_row(s, it->second, chosen.at(next));
      try {
        const auto busy = interrupts.writing();
        writer.append(row);
      } catch (const std::exception& e) {
        fmt::print(stderr, "lubsweep: refine: cannot write {}: {}\n", s.path, e.what());
        transport.abort(kExitIoError);
      }
      plan.absorb(detail::point_of(s, writer.columns(), row));
      waiting.erase(it);
      ++next;
      interrupts.saved(static_cast<std::size_t>(next) - s.study_cases);
      ++tally.new_rows;
      if (o.kill_after >= 0 && tally.new_rows >= o.kill_after) std::raise(SIGKILL);  // tests only
    }
  };
  schedule(s.grid, std::move(queue), transport, sc);
}

/// Rank 0, once the checks passed: the rounds, then the last lines and the table.
int coordinate_refine(MPI_Comm comm, const Options& o, RefineStudy& s, std::vector<RefinedRow> held) {
  const auto t0 = Clock::now();
  std::size_t held_failed = 0;
  for (const RefinedRow& r : held) held_failed += !r.point.ok;
  Progress progress(static_cast<std::size_t>(o.refine_budget), held.size(), held_failed);
  detail::Interrupts::process().name_file(s.path, OutputLock::lock_path(s.path),
                                          static_cast<std::size_t>(o.refine_budget), held.size());
  Planner plan(s, std::move(held), o.refine_tolerance, o.refine_budget);
  RefineWriter writer(s, o.refine_tolerance);
  Tally tally;
  try {
    for (std::vector<Planned> round = plan.next_round(); !round.empty(); round = plan.next_round()) {
      std::deque<int> queue;
      std::map<int, RefineCandidate> chosen;
      for (const Planned& p : round)
        if (!p.held) queue.push_back(p.id), chosen[p.id] = p.candidate;
      if (queue.empty()) continue;
      broadcast_code(comm, kServeRound);
      run_round(comm, o, s, plan, chosen, std::move(queue), writer, progress, t0, tally);
    }
  } catch (const InputError& e) {
    broadcast_code(comm, kNoMoreRounds);
    fmt::print(stderr, "lubsweep: refine: {}\n", e.what());
    return kExitBadInput;
  }
  broadcast_code(comm, kNoMoreRounds);
  if (!o.quiet)
    fmt::print(stderr, "lubsweep: refine: {}: {} new cases, {} in /refinement/cases (--budget {}) from {} round{}, {} "
                       "periods, {}; {}\n",
               s.path, tally.new_rows, plan.spent(), o.refine_budget, plan.rounds(), plan.rounds() == 1 ? "" : "s",
               tally.periods,
               format_duration(std::chrono::duration<double>(Clock::now() - t0).count()),
               plan.spent() >= o.refine_budget ? "the budget is spent" : "no edge scores any more");
  print_refinement(s.path, stdout);
  return kExitOk;
}

/// Rank 0's checks before any work: the study, what /refinement holds, the budget, the
/// lock. Returns 0 to go on, kNothingToDo, or an exit status; the file is not opened for
/// writing here.
int prepare_refine(const Options& o, std::optional<RefineStudy>& s, std::vector<RefinedRow>& held, OutputLock& lock) {
  try {
    s = detail::read_refine_study(o.refine_study);
    held = detail::read_refined(*s, o.refine_tolerance);
  } catch (const std::exception& e) {
    fmt::print(stderr, "lubsweep: refine: {}\n", e.what());
    return kExitBadInput;
  }
  if (s->lattice.empty()) {
    fmt::print(stderr, "lubsweep: refine: {}: no lattice edge along a numeric axis of a physical number (its axes: "
                       "force laws, settings or counts only): nothing to refine\n", s->path);
    return kNothingToDo;
  }
  if (static_cast<long>(held.size()) >= o.refine_budget) {
    fmt::print(stderr, "lubsweep: refine: {}: the budget is already spent: /refinement/cases holds {} cases, --budget "
                       "{}; nothing to run (a larger --budget continues)\n", s->path, held.size(), o.refine_budget);
    return kNothingToDo;
  }
  if (s->grid.parameters.empty())
    fmt::print(stderr, "lubsweep: refine: note: {} has no sensitivities (its grid has study.sensitivities = false): "
                       "the metric criterion needs them; refining where the labels (classification, "
                       "below_safe_film) differ only\n", s->path);
  try {
    lock = OutputLock(s->path);
  } catch (const std::exception& e) {
    fmt::print(stderr, "lubsweep: refine: {}\n", e.what());
    return kExitBadInput;
  }
  if (!o.quiet)
    fmt::print(stderr, "lubsweep: refine {}: {} study cases, {} lattice edges; /refinement/cases holds {}; --budget {}, "
                       "--metric-tolerance {:g}\n", s->path, s->study_cases, s->lattice.size(), held.size(),
               o.refine_budget, o.refine_tolerance);
  return 0;
}

}  // namespace

int run_refine(const Options& o, MPI_Comm comm) {
  int rank = 0;
  MPI_Comm_rank(comm, &rank);
  std::optional<RefineStudy> s;
  std::vector<RefinedRow> held;
  OutputLock lock;  // rank 0: held while the refinement runs
  int code = 0;
  if (rank == 0) code = prepare_refine(o, s, held, lock);
  code = broadcast_code(comm, code);
  if (code != 0) return rank == 0 && code != kNothingToDo ? code : 0;
  int status = 0;
  if (rank == 0) {
    status = coordinate_refine(comm, o, *s, std::move(held));
  } else {
    while (broadcast_code(comm, kNoMoreRounds) == kServeRound) {
      MpiWorker transport(comm);
      serve(transport, [rank](const Task& t) { return run_task(t, rank); });
    }
  }
  polite_barrier(comm);
  return status;
}

}  // namespace lub::sweep
