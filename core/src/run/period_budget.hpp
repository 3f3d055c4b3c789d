// A case's budget of crank periods, simulation.max_periods (internal to the run stage):
// every stage of a run asks it before it integrates, and the first stage it stops is the
// case's reason (docs/theory/steady-cycles.md, budgets).
#pragma once

#include <string>

namespace lub::detail {

class PeriodBudget {
 public:
  /// `limit`: the case's max_periods; `spent_before`: the periods the case integrated
  /// before this run (a continuation's earlier steps, its thick-film start).
  PeriodBudget(long long limit, long long spent_before) : limit_(limit), before_(spent_before) {}

  /// The periods this run may integrate in all (its own count against it).
  long long run_limit() const { return limit_ - before_; }
  /// The periods this run may still integrate, having integrated `spent` itself.
  long long left(long long spent) const { return run_limit() - spent; }
  /// Whether `n` more periods fit; if not, `what` does not run, and the budget says so.
  bool allows(long long n, long long spent, const std::string& what) {
    if (n <= left(spent)) return true;
    stopped(spent, what);
    return false;
  }
  /// The budget stopped `what` after this run integrated `spent`: the case's reason (the
  /// first stage stopped; later ones follow from it).
  void stopped(long long spent, const std::string& what) {
    if (note_.empty())
      note_ = "simulation.max_periods = " + std::to_string(limit_) + " reached (" + std::to_string(before_ + spent) +
              " periods integrated): " + what;
  }
  /// "" while the budget has stopped nothing.
  const std::string& note() const { return note_; }

 private:
  long long limit_;
  long long before_;
  std::string note_;
};

}  // namespace lub::detail
