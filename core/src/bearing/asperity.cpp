// Greenwood–Tripp asperity contact: see lub/bearing/asperity.hpp.
#include "lub/bearing/asperity.hpp"

#include <algorithm>
#include <array>
#include <cmath>

#include "common/gauss_legendre.hpp"
#include "lub/common/constants.hpp"

namespace lub {

namespace {

// The table of F_{5/2} and F_{3/2}: nodes H_i = kLow + i/kPerUnit on [kLow, kCutoff].
constexpr double kLow = -4.0;
constexpr int kPerUnit = 128;
constexpr int kNodes = static_cast<int>((kAsperityCutoffRatio - kLow) * kPerUnit) + 1;

// F_n(H) = 2/√(2π) ∫_0^U u^{2n+1} e^{−(u² + H)²/2} du (s = H + u², smooth in u) by composite
// Simpson on m panels, for each power u^{2n+1} that `powers(u, out)` writes: the integrand is
// below e^{−45} beyond u² = √90 + max(0, −H).
template <int K, class Powers>
std::array<double, K> simpson_in_u(double H, int m, Powers&& powers) {
  const double U = std::sqrt(std::sqrt(90.0) + std::max(0.0, -H));
  const double du = U / m;
  std::array<double, K> sum{}, pw{};
  for (int j = 0; j <= m; ++j) {
    const double u = j * du, s = u * u + H;
    const double g = (j == 0 || j == m ? 1.0 : (j % 2 ? 4.0 : 2.0)) * std::exp(-0.5 * s * s);
    powers(u, pw);
    for (int k = 0; k < K; ++k) sum[k] += g * pw[k];
  }
  for (double& v : sum) v *= 2.0 / std::sqrt(kTwoPi) * du / 3.0;
  return sum;
}

struct F52Table {
  std::vector<double> f52, f32;
  F52Table() : f52(kNodes), f32(kNodes) {
    // Both orders in one pass, u⁶ and u⁴ by products.
    for (int i = 0; i < kNodes; ++i) {
      const auto f = simpson_in_u<2>(kLow + static_cast<double>(i) / kPerUnit, 2000, [](double u, auto& pw) {
        pw[1] = u * u * u * u;
        pw[0] = pw[1] * u * u;
      });
      f52[i] = f[0];
      f32[i] = f[1];
    }
  }
};

const F52Table& table() {
  static const F52Table t;
  return t;
}

// The arc's rule: Gauss–Legendre nodes and weights mapped to [0, 1].
constexpr int kArcNodes = 16;
struct ArcRule {
  std::array<double, kArcNodes> x{}, w{};
  ArcRule() {
    const detail::GaussLegendre gl(kArcNodes);
    for (int i = 0; i < kArcNodes; ++i) {
      x[i] = 0.5 * (1.0 + gl.x[i]);
      w[i] = 0.5 * gl.w[i];
    }
  }
};

const ArcRule& arc_rule() {
  static const ArcRule r;
  return r;
}

}  // namespace

AsperityLaw resolve_asperity(const AsperitySpec& spec) {
  const double s = spec.roughness_m, b = spec.asperity_radius_m;
  const double nbs = spec.asperity_density_per_m2 * b * s;
  AsperityLaw law;
  law.roughness_m = s;
  law.pressure_scale_Pa = 16.0 * std::sqrt(2.0) / 15.0 * kPi * nbs * nbs * std::sqrt(s / b) * spec.composite_modulus_Pa;
  law.boundary_friction = spec.boundary_friction;
  return law;
}

double greenwood_tripp_integral(double n, double H) {
  return simpson_in_u<1>(H, 4000, [n](double u, auto& pw) { pw[0] = std::pow(u, 2.0 * n + 1.0); })[0];
}

double greenwood_tripp_f52(double H, double* derivative) {
  const F52Table& t = table();
  if (!(H < kAsperityCutoffRatio)) {
    if (derivative) *derivative = 0.0;
    return 0.0;
  }
  if (H <= kLow) {  // continued linearly (C¹): only a journal pressed through the wall sees it
    const double d = -2.5 * t.f32[0];
    if (derivative) *derivative = d;
    return t.f52[0] + d * (H - kLow);
  }
  const double x = (H - kLow) * kPerUnit;
  const int i = std::min(static_cast<int>(x), kNodes - 2);
  const double s = x - i, h = 1.0 / kPerUnit;
  const double y0 = t.f52[i], y1 = t.f52[i + 1];
  const double m0 = -2.5 * t.f32[i] * h, m1 = -2.5 * t.f32[i + 1] * h;
  const double s2 = s * s, s3 = s2 * s;
  if (derivative)
    *derivative = ((6 * s2 - 6 * s) * y0 + (3 * s2 - 4 * s + 1) * m0 + (-6 * s2 + 6 * s) * y1 + (3 * s2 - 2 * s) * m1) / h;
  return (2 * s3 - 3 * s2 + 1) * y0 + (s3 - 2 * s2 + s) * m0 + (-2 * s3 + 3 * s2) * y1 + (s3 - s2) * m1;
}

double asperity_pressure_Pa(const AsperityLaw& law, double film_m) {
  return law.pressure_scale_Pa * greenwood_tripp_f52(film_m / law.roughness_m);
}

double asperity_load_N(const AsperityLaw& law, const BearingGeometry& g, double eps) {
  // φ from the line of minimum film: h = c (1 − ε cos φ); W_a = 2 R_J L ∫_0^{φ_m} p_a cos φ dφ
  // over the arc where h < 8σ (cos φ > (1 − 8σ/c)/ε).
  const double c = g.clearance_m();
  if (!(eps > 0.0)) return 0.0;  // uniform film: the pressure cancels round the bearing
  const double x0 = (1.0 - kAsperityCutoffRatio * law.roughness_m / c) / eps;
  if (x0 >= 1.0) return 0.0;
  const double phi_m = x0 <= -1.0 ? kPi : std::acos(x0);
  const ArcRule& r = arc_rule();
  double sum = 0.0;
  for (int i = 0; i < kArcNodes; ++i) {
    const double phi = phi_m * r.x[i];
    sum += r.w[i] * asperity_pressure_Pa(law, c * (1.0 - eps * std::cos(phi))) * std::cos(phi);
  }
  return 2.0 * g.journal_radius_m * g.length_m * phi_m * sum;
}

}  // namespace lub
