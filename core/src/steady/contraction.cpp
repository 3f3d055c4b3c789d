// Contraction of a transient towards its steady cycle: see contraction.hpp.
#include "lub/steady/contraction.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace lub::steady {

namespace {

// Least-squares slope and value at the last point of y against 0, 1, …, n−1.
void fit_line(const std::vector<double>& y, double& slope, double& last_value) {
  const double n = static_cast<double>(y.size());
  double sx = 0, sy = 0, sxx = 0, sxy = 0;
  for (size_t i = 0; i < y.size(); ++i) {
    const double x = static_cast<double>(i);
    sx += x, sy += y[i], sxx += x * x, sxy += x * y[i];
  }
  const double den = n * sxx - sx * sx;
  slope = den > 0 ? (n * sxy - sx * sy) / den : 0.0;
  last_value = (sy - slope * sx) / n + slope * (n - 1);
}

}  // namespace

ContractionEstimate estimate_contraction(const std::vector<double>& distances, int window, double floor) {
  ContractionEstimate e;
  std::vector<double> logs;
  for (auto it = distances.rbegin(); it != distances.rend() && static_cast<int>(logs.size()) < window; ++it) {
    if (!(*it >= 0.0)) break;  // the first cycle (no previous one) or unknown
    logs.push_back(std::log(std::max(*it, floor)));
  }
  if (logs.size() < 4 || floor <= 0.0) return e;
  std::reverse(logs.begin(), logs.end());
  e.known = true;
  e.last = std::exp(logs.back());
  if (std::all_of(logs.begin(), logs.end(), [&](double l) { return l <= std::log(floor) + 1e-12; })) {
    // Every distance at the noise floor: nothing left to converge that the integration
    // could resolve.
    e.rate = 0.0;
    e.remaining = floor;
    return e;
  }
  double slope = 0.0, fitted_last = 0.0;
  fit_line(logs, slope, fitted_last);
  e.rate = std::exp(slope);
  // The larger of the last distance and the line's value there: a complex dominant pair
  // puts δ_k at a trough of its oscillation as often as at a crest.
  const double d = std::max(e.last, std::exp(fitted_last));
  e.remaining = e.rate < 1.0 ? d * e.rate / (1.0 - e.rate) : std::numeric_limits<double>::infinity();
  return e;
}

bool transient_converged(const ContractionEstimate& e, double tolerance) {
  return e.known && e.rate < 1.0 && e.remaining <= tolerance;
}

double trend_per_cycle(const std::vector<double>& values, int window) {
  const size_t n = std::min(values.size(), static_cast<size_t>(std::max(window, 0)));
  if (n < 2) return 0.0;
  std::vector<double> y(values.end() - static_cast<std::ptrdiff_t>(n), values.end());
  double slope = 0.0, last = 0.0;
  fit_line(y, slope, last);
  return slope;
}

double cycles_to_converge(const ContractionEstimate& e, double tolerance) {
  if (!e.known || e.rate >= 1.0) return std::numeric_limits<double>::infinity();
  if (e.remaining <= tolerance) return 0.0;
  if (e.rate <= 0.0) return 1.0;
  return std::log(tolerance / e.remaining) / std::log(e.rate);
}

}  // namespace lub::steady
