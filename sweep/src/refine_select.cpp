// The refinement's selection rule (lub/sweep/refine.hpp): where a new case goes on an edge,
// whether an edge scores, and the order of the edges that do. Pure functions of the rows.
#include <algorithm>
#include <cmath>
#include <tuple>

#include "lub/run/run.hpp"
#include "lub/sweep/refine.hpp"

namespace lub::sweep {

namespace {

/// max/min of positive numbers (1 for fewer than two).
double spread(const std::vector<double>& v) {
  if (v.size() < 2) return 1.0;
  const auto [lo, hi] = std::minmax_element(v.begin(), v.end());
  return *hi / *lo;
}

/// An error bar as an allowance: NaN (not computed) allows nothing.
double bar(double e) { return std::isfinite(e) ? std::abs(e) : 0.0; }

/// The labels of two ends that differ (classification, below_safe_film), and the first.
std::optional<std::pair<int, RefineReason>> label_difference(const RefinePoint& a, const RefinePoint& b) {
  int count = 0;
  RefineReason first = RefineReason::metric;
  if (a.classification != b.classification) ++count, first = RefineReason::classification;
  if (a.below_safe_film >= 0.0 && b.below_safe_film >= 0.0 && a.below_safe_film != b.below_safe_film) {
    if (count == 0) first = RefineReason::below_safe_film;
    ++count;
  }
  if (count == 0) return std::nullopt;
  return std::make_pair(count, first);
}

}  // namespace

bool geometric_axis(const std::vector<double>& levels) {
  if (levels.empty() || levels.front() <= 0.0) return false;
  if (levels.size() < 3) return true;
  std::vector<double> ratios, steps;
  for (std::size_t i = 1; i < levels.size(); ++i) {
    ratios.push_back(levels[i] / levels[i - 1]);
    steps.push_back(levels[i] - levels[i - 1]);
  }
  return spread(ratios) <= spread(steps);
}

double refine_midpoint(double a, double b, bool geometric) {
  if (geometric && a > 0.0 && b > 0.0) return std::sqrt(a * b);
  return 0.5 * (a + b);
}

std::optional<RefineCandidate> score_edge(const RefineEdge& edge, const RefinePoint& a, const RefinePoint& b,
                                          double lambda_a, double lambda_b, int parameter, double tolerance) {
  if (!a.ok || !b.ok) return std::nullopt;
  if (const auto labels = label_difference(a, b))
    return RefineCandidate{edge, labels->second, static_cast<double>(labels->first), ""};
  if (parameter < 0) return std::nullopt;
  const auto& metrics = steady_metrics();
  const std::size_t base = static_cast<std::size_t>(parameter) * metrics.size();
  const double dl = lambda_b - lambda_a;
  double worst = 1.0;
  std::string which;
  for (std::size_t i = 0; i < metrics.size(); ++i) {
    if (metrics[i].angle) continue;  // an angle's change wraps: no trapezoid for it
    const double ma = a.metric.at(i), mb = b.metric.at(i);
    const double sa = a.slope.at(base + i), sb = b.slope.at(base + i);
    if (!(std::isfinite(ma) && std::isfinite(mb) && std::isfinite(sa) && std::isfinite(sb))) continue;
    const double miss = std::abs((mb - ma) - 0.5 * (sa + sb) * dl);
    const double allowed = bar(a.metric_error.at(i)) + bar(b.metric_error.at(i)) +
                           0.5 * std::abs(dl) * (bar(a.slope_error.at(base + i)) + bar(b.slope_error.at(base + i))) +
                           tolerance * std::max(std::abs(ma), std::abs(mb));
    if (allowed > 0.0 && miss / allowed > worst) worst = miss / allowed, which = metrics[i].name;
  }
  if (which.empty()) return std::nullopt;
  return RefineCandidate{edge, RefineReason::metric, worst - 1.0, which};
}

void rank_candidates(std::vector<RefineCandidate>& candidates) {
  const auto key = [](const RefineCandidate& c) {
    return std::make_tuple(c.reason == RefineReason::metric, -c.score, c.edge.a, c.edge.b, c.edge.axis);
  };
  std::stable_sort(candidates.begin(), candidates.end(),
                   [&](const RefineCandidate& x, const RefineCandidate& y) { return key(x) < key(y); });
}

}  // namespace lub::sweep
