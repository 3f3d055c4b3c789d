// The film's approach law near the wall: see drift_law.hpp.
#include "lub/steady/drift_law.hpp"

#include <algorithm>
#include <cmath>

namespace lub::steady {

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

DriftLaw unknown(std::string why) {
  DriftLaw law;
  law.why = std::move(why);
  return law;
}

/// The film at which the law's drift equals the secant's slope between h_a > h_b: for
/// dh/dN = −a h^p exactly, h*^p = (p − 1)(h_a − h_b) / (h_b^(1−p) − h_a^(1−p)) (the
/// logarithmic mean at p = 1); ln h*.
double log_secant_film(double h_a, double h_b, double p) {
  if (std::abs(p - 1.0) < 1e-6) return std::log((h_a - h_b) / std::log(h_a / h_b));
  const double r = (p - 1.0) / (std::pow(h_b, 1.0 - p) - std::pow(h_a, 1.0 - p));
  return (std::log(r) + std::log(h_a - h_b)) / p;
}

/// The straight line ln(−s) = ln a + p ln h* through the secants of films h at cycles N
/// (from index `from` on): (ln a, p) and their covariance. h* first the geometric mean of
/// each secant's films, then the film where the fitted law's drift is the secant's slope
/// (the geometric mean's bias is second order in the films' ratio, the same sign at every
/// secant: it would pass into a). False where the film does not fall between two points.
bool fit_secants(const std::vector<double>& N, const std::vector<double>& h, size_t from, Eigen::Vector2d& beta,
                 Eigen::Matrix2d& covariance) {
  const size_t m = h.size() - 1 - from;
  Eigen::MatrixXd X(static_cast<Eigen::Index>(m), 2);
  Eigen::VectorXd y(static_cast<Eigen::Index>(m));
  for (size_t k = 0; k < m; ++k) {
    const size_t i = from + k;
    const double dn = N[i + 1] - N[i];
    const double s = (h[i + 1] - h[i]) / dn;
    if (!(dn > 0.0) || !(s < 0.0)) return false;
    const auto r = static_cast<Eigen::Index>(k);
    X(r, 0) = 1.0;
    X(r, 1) = 0.5 * (std::log(h[i]) + std::log(h[i + 1]));
    y(r) = std::log(-s);
  }
  constexpr int kRefits = 3;
  for (int pass = 0;; ++pass) {
    const Eigen::Matrix2d XtX = X.transpose() * X;
    beta = XtX.ldlt().solve(X.transpose() * y);
    if (pass == kRefits || !(beta(1) > 0.1 && beta(1) < 10.0)) {
      // Residual variance with m − 2 degrees of freedom.
      const double s2 = m > 2 ? (y - X * beta).squaredNorm() / static_cast<double>(m - 2) : 0.0;
      covariance = s2 * XtX.inverse();
      return true;
    }
    for (size_t k = 0; k < m; ++k)
      X(static_cast<Eigen::Index>(k), 1) = log_secant_film(h[from + k], h[from + k + 1], beta(1));
  }
}

/// ΔN from h0 to h1 under the law whose drift at h0 has size s0 (given as ln s0), exponent p.
double crossing(double log_s0, double p, double h0, double h1) {
  const double s0 = std::exp(log_s0);  // |dh/dN| at h0 [m/cycle]
  if (std::abs(p - 1.0) < 1e-9) return h0 * std::log(h0 / h1) / s0;
  // ∫_{h1}^{h0} dh / (s0 (h/h0)^p) = h0^p (h1^(1−p) − h0^(1−p)) / (s0 (p − 1))
  return h0 * (std::pow(h1 / h0, 1.0 - p) - 1.0) / (s0 * (p - 1.0));
}

}  // namespace

DriftLaw fit_drift_law(const std::vector<double>& cycles, const std::vector<double>& film_m) {
  const size_t n = std::min(cycles.size(), film_m.size());
  if (n < 5) return unknown("fewer than 5 films measured along the flow");
  for (size_t i = 0; i < n; ++i)
    if (!(film_m[i] > 0.0) || !std::isfinite(cycles[i])) return unknown("a film along the flow was not measured");
  const std::vector<double> N(cycles.begin(), cycles.begin() + static_cast<std::ptrdiff_t>(n));
  const std::vector<double> h(film_m.begin(), film_m.begin() + static_cast<std::ptrdiff_t>(n));
  const auto [lo, hi] = std::minmax_element(h.begin(), h.end());
  if (*hi / *lo < kDriftLawMinFilmRatio) return unknown("the film changes by less than 15 % along the flow");
  Eigen::Vector2d beta;
  Eigen::Matrix2d cov;
  if (!fit_secants(N, h, 0, beta, cov)) return unknown("the film does not fall between every two points along the flow");
  DriftLaw law;
  law.known = true;
  law.log_coefficient = beta(0);
  law.exponent = beta(1);
  law.covariance = cov;
  law.film_low_m = *lo;
  law.film_high_m = *hi;
  // The nearer half (the later points, the smaller films): its own exponent.
  if (n >= 10) {
    Eigen::Vector2d near;
    Eigen::Matrix2d near_cov;
    if (fit_secants(N, h, n / 2, near, near_cov)) law.exponent_spread = std::abs(near(1) - beta(1));
  }
  return law;
}

DriftCrossing cycles_to_film(const DriftLaw& law, double h0_m, double h1_m, double drift_relative_error) {
  DriftCrossing out;
  if (!law.known || !(h1_m > 0.0) || !(h1_m < h0_m)) return out;
  if (h1_m < law.film_low_m / kDriftLawReach) {
    out.beyond_reach = true;
    return out;
  }
  const double p = law.exponent, lh0 = std::log(h0_m);
  const double log_s0 = law.log_coefficient + p * lh0;  // the law's drift at h0
  out.cycles = crossing(log_s0, p, h0_m, h1_m);
  // var(ln s0) = [1, ln h0] C [1, ln h0]ᵀ + e²; var(p) = C_pp + spread².
  const Eigen::Vector2d at(1.0, lh0);
  const double e = std::isfinite(drift_relative_error) ? drift_relative_error : 0.0;
  const double var_s = at.dot(law.covariance * at) + e * e;
  const double var_p = law.covariance(1, 1) + law.exponent_spread * law.exponent_spread;
  constexpr double dp = 1e-6;
  const double g_s = -out.cycles;  // d ΔN / d ln s0
  const double g_p = (crossing(log_s0, p + dp, h0_m, h1_m) - crossing(log_s0, p - dp, h0_m, h1_m)) / (2.0 * dp);
  const double var = g_s * g_s * var_s + g_p * g_p * var_p;
  out.error = var >= 0.0 ? 2.0 * std::sqrt(var) : kNaN;
  return out;
}

}  // namespace lub::steady
