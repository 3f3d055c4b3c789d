#include "run/wall_coordinates.hpp"

#include <cmath>

namespace lub::detail {

namespace {
/// Below this |u| or |w| the ratios g'/ε and f'/ρ come from their series: the closed forms
/// lose 1e-16/x² of their value to cancellation, the series' first dropped term is ~x⁶
/// (both ~1e-12 at the switch, in a term ε² smaller than the leading one).
constexpr double kSeries = 1e-2;
}  // namespace

void to_wall_coordinates(const Eigen::Vector2d& u, const Eigen::Vector2d& u_dot, Eigen::Vector2d& w,
                         Eigen::Vector2d& w_dot) {
  const double eps = u.norm();
  const double e2 = eps * eps;
  const double g = eps > 0.0 ? std::atanh(eps) / eps : 1.0;
  // g'(ε)/ε = (ε/(1 − ε²) − atanh ε)/ε³ = 2/3 + 4ε²/5 + 6ε⁴/7 + …
  const double gp_over_eps =
      eps < kSeries ? 2.0 / 3.0 + e2 * (4.0 / 5.0 + e2 * 6.0 / 7.0) : (eps / (1.0 - e2) - std::atanh(eps)) / (e2 * eps);
  w = g * u;
  w_dot = g * u_dot + gp_over_eps * u.dot(u_dot) * u;
}

bool from_wall_coordinates(const Eigen::Vector2d& w, const Eigen::Vector2d& w_dot, Eigen::Vector2d& u,
                           Eigen::Vector2d& u_dot) {
  const double rho = w.norm();
  const double th = std::tanh(rho);
  if (!(th < 1.0)) return false;
  const double r2 = rho * rho;
  const double f = rho > 0.0 ? th / rho : 1.0;
  // f'(ρ)/ρ = (ρ sech²ρ − tanh ρ)/ρ³ = −2/3 + 8ρ²/15 − 34ρ⁴/105 + …
  const double sech2 = 1.0 - th * th;
  const double fp_over_rho =
      rho < kSeries ? -2.0 / 3.0 + r2 * (8.0 / 15.0 - r2 * 34.0 / 105.0) : (rho * sech2 - th) / (r2 * rho);
  u = f * w;
  u_dot = f * w_dot + fp_over_rho * w.dot(w_dot) * w;
  return true;
}

double wall_stretch(double eps) { return 1.0 / (1.0 - eps * eps); }

}  // namespace lub::detail
