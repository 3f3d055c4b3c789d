// Hydrodynamic force laws of a lubricated revolute joint: see force_laws.hpp for the
// formulas, symbols, limits and the known defects of the printed Pinkus–Sternlicht law.
//
// These functions run inside an ODE right-hand side: no allocation, no exceptions, and
// the few branches are selects on the sign of ε̇ or guards against 0/0.
#include "lub/bearing/force_laws.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <utility>

#include "bearing/film_math.hpp"

namespace lub {
namespace {


// Long-bearing antiderivatives in ψ (see force_laws.hpp, "Laws beyond the paper").
struct LongCoefficients {
  double eps, s, alpha, beta, gamma, delta;
};
inline LongCoefficients long_coefficients(double e, double s, double ed, double w) {
  const double s2 = s * s;
  const double tp = 2.0 + e * e;
  return {e, s, e * w / (tp * s2), 2.0 * ed / (s2 * s), e * w / (tp * s2 * s), 2.0 * ed / (s2 * s2)};
}
// [α A + β B](ψ) and [γ G + δ E](ψ).
inline double long_radial_antiderivative(const LongCoefficients& k, double psi) {
  const double sp = std::sin(psi), cp = std::cos(psi);
  return k.alpha * (sp * sp - k.eps * cp) + k.beta * (0.5 * psi - 0.5 * sp * cp);
}
inline double long_tangential_antiderivative(const LongCoefficients& k, double psi) {
  const double sp = std::sin(psi), cp = std::cos(psi);
  return k.gamma * (k.s * k.s * psi + sp * cp - k.eps * sp) + k.delta * (0.5 * sp * sp + k.eps * cp);
}

// Long-bearing force over the ψ-arc [pa, pb] on which the pressure vanishes at both ends
// (by parts), in units of 6C.
inline void add_long_arc(const LongCoefficients& k, double pa, double pb, double& fr, double& ft) {
  fr -= long_radial_antiderivative(k, pb) - long_radial_antiderivative(k, pa);
  ft += long_tangential_antiderivative(k, pb) - long_tangential_antiderivative(k, pa);
}

}  // namespace

double long_bearing_coefficient(const BearingGeometry& g, double viscosity_Pa_s) {
  const double c = g.clearance_m();
  const double r = g.journal_radius_m;
  return viscosity_Pa_s * g.length_m * r * r * r / (c * c);
}

double short_bearing_coefficient(const BearingGeometry& g, double viscosity_Pa_s) {
  const double c = g.clearance_m();
  const double l = g.length_m;
  return viscosity_Pa_s * l * l * l * g.journal_radius_m / (c * c);
}

FilmForce film_force_frene_long(const BearingGeometry& g, double viscosity_Pa_s,
                                const BearingState& s) {
  const double cl = long_bearing_coefficient(g, viscosity_Pa_s);
  const double e = s.eps;
  const double om = (1.0 - e) * (1.0 + e);  // 1 − ε², accurate near ε = 1
  const double sq = std::sqrt(om);
  FilmForce f;
  f.radial_N = -12.0 * kPi * cl * s.eps_dot / (om * sq);                      // Eq. (8)
  f.tangential_N = 12.0 * kPi * cl * e * s.wedge / ((2.0 + e * e) * sq);      // Eq. (9)
  return f;
}

FilmForce film_force_frene_short(const BearingGeometry& g, double viscosity_Pa_s,
                                 const BearingState& s) {
  const double cs = short_bearing_coefficient(g, viscosity_Pa_s);
  const double e = s.eps;
  const double om = (1.0 - e) * (1.0 + e);
  const double sq = std::sqrt(om);
  FilmForce f;
  f.radial_N = -kPi * cs * s.eps_dot * (1.0 + 2.0 * e * e) / (om * om * sq);  // Eq. (6)
  f.tangential_N = kPi * cs * e * s.wedge / (2.0 * om * sq);                  // Eq. (7)
  return f;
}

FilmForce film_force_pinkus_sternlicht(const BearingGeometry& g, double viscosity_Pa_s,
                                       const BearingState& s) {
  const double cl = long_bearing_coefficient(g, viscosity_Pa_s);
  const double e = s.eps;
  const double ed = s.eps_dot;
  const double w = s.wedge;
  const double e2 = e * e;
  const double om = (1.0 - e) * (1.0 + e);  // 1 − ε²
  const double sq = std::sqrt(om);
  const double two_p = 2.0 + e2;

  // q = sqrt(ε² w²/4 + ε̇²); hypot avoids spurious underflow/overflow of the squares.
  const double q = std::hypot(0.5 * e * w, ed);
  const double sqq = sq * q;
  // 1/k from Eq. (14) without forming k. sqq = 0 only when ε̇ = 0 and ε w = 0: then the
  // numerator is 0 too and every term below that uses 1/k is multiplied by ε̇ or ε w, so
  // any finite value is right; 0 (k = ∞) is the ε̇ → 0⁺ limit for w ≠ 0.
  const double inv_k = sqq > 0.0 ? e * std::fabs(ed) / sqq : 0.0;

  // Branch: Eqs. (10)–(11) for ε̇ >= 0 (including ε̇ = ±0), Eqs. (12)–(13) for ε̇ < 0.
  const bool pos = !(ed < 0.0);
  const double sgn = pos ? 1.0 : -1.0;
  const double den = 1.0 + 1.5 * inv_k;
  // (k+3)/(k+3/2) on the ε̇ >= 0 branch, k/(k+3/2) on the ε̇ < 0 branch.
  const double ratio = (pos ? 1.0 + 3.0 * inv_k : 1.0) / den;
  // ε̇ k ε² = sgn · ε sqrt(1−ε²) sqrt(ε²w²/4 + ε̇²): finite at ε̇ = 0 and at ε = 0.
  const double edk_e2 = sgn * e * sqq;

  const double pre = 6.0 * cl / (two_p * om * sq);
  FilmForce f;
  // ε̇ >= 0: 4ε̇kε² + (2+ε²)π ε̇ (k+3)/(k+3/2);  ε̇ < 0: 4ε̇kε² − (2+ε²)π ε̇ k/(k+3/2).
  f.radial_N = -pre * (4.0 * edk_e2 + sgn * two_p * kPi * ed * ratio);  // Eqs. (10), (12)
  f.tangential_N = pre * kPi * e * w * ratio;                           // Eqs. (11), (13)
  return f;
}

FilmForce film_force_gumbel_long(const BearingGeometry& g, double viscosity_Pa_s,
                                 const BearingState& s) {
  const double e = s.eps, ed = s.eps_dot, w = s.wedge;
  const double om = (1.0 - e) * (1.0 + e);
  const double sq = std::sqrt(om);
  // g(ψ) = a sin ψ (2 − ε² − ε cos ψ) + ε̇ (1 − cos ψ)(2 − ε − ε cos ψ), a = ε w s/(2+ε²).
  const double a_raw = e * w * sq / (2.0 + e * e);
  const double scale = std::max(std::fabs(a_raw), std::fabs(ed));
  if (!(scale > 0.0)) return FilmForce{};  // ε̇ = 0 and ε w = 0: no pressure at all
  const double a = a_raw / scale, b = ed / scale;  // g is homogeneous: normalise
  const auto gfun = [&](double psi) {
    const double cp = std::cos(psi), sp = std::sin(psi);
    return a * sp * (2.0 - e * e - e * cp) + b * (1.0 - cp) * (2.0 - e - e * cp);
  };
  // Zeros of g in [0, 2π): ψ = 0 always; t = tan(ψ/2) roots of
  //   q(t) = 2b t³ + a(1+ε)(2−ε) t² + 2b(1−ε) t + a(1−ε)(2+ε)       (chart |t| <= 1)
  // and u = 1/t roots of the reversed cubic (chart |u| <= 1, ψ = π − 2 atan u).
  double z[16];
  int nz = 0;
  z[nz++] = 0.0;
  const double c_t[4] = {a * (1.0 - e) * (2.0 + e), 2.0 * b * (1.0 - e), a * (1.0 + e) * (2.0 - e), 2.0 * b};
  const double c_u[4] = {2.0 * b, a * (1.0 + e) * (2.0 - e), 2.0 * b * (1.0 - e), a * (1.0 - e) * (2.0 + e)};
  double r[6];
  int nr = detail::cubic_roots_unit_interval(c_t, r);
  for (int k = 0; k < nr; ++k) {
    double psi = 2.0 * std::atan(r[k]);
    if (psi < 0.0) psi += kTwoPi;
    z[nz++] = psi;
  }
  nr = detail::cubic_roots_unit_interval(c_u, r);
  for (int k = 0; k < nr; ++k) z[nz++] = kPi - 2.0 * std::atan(r[k]);
  for (int k = 0; k < nz; ++k)
    if (z[k] >= kTwoPi || z[k] < 0.0) z[k] = 0.0;  // ψ = 2π is ψ = 0
  std::sort(z, z + nz);
  int m = 0;  // drop duplicates (a root on the chart boundary is found twice)
  for (int k = 0; k < nz; ++k)
    if (m == 0 || z[k] - z[m - 1] > 1e-13) z[m++] = z[k];
  nz = m;

  const LongCoefficients kc = long_coefficients(e, sq, ed, w);
  const double om2 = om * om;
  // Boundary terms of the integration by parts, [p sin θ] and [−p cos θ] in units of 6C:
  // p/(6μ(R/c)²) = g/s⁴ (times `scale`), sin θ = s sin ψ/D, cos θ = (cos ψ − ε)/D,
  // D = 1 − ε cos ψ. Zero up to rounding at the computed zeros of g.
  const auto boundary = [&](double psi, double sign, double& fr, double& ft) {
    const double cp = std::cos(psi), sp = std::sin(psi);
    const double d = 1.0 - e * cp;
    const double pv = scale * gfun(psi) / om2;
    fr += sign * pv * sq * sp / d;
    ft -= sign * pv * (cp - e) / d;
  };
  double fr = 0.0, ft = 0.0;
  for (int k = 0; k < nz; ++k) {
    const double pa = z[k];
    const double pb = k + 1 < nz ? z[k + 1] : z[0] + kTwoPi;
    if (!(gfun(0.5 * (pa + pb)) > 0.0)) continue;
    add_long_arc(kc, pa, pb, fr, ft);
    boundary(pb, 1.0, fr, ft);
    boundary(pa, -1.0, fr, ft);
  }
  const double c6 = 6.0 * long_bearing_coefficient(g, viscosity_Pa_s);
  return FilmForce{c6 * fr, c6 * ft};
}

FilmForce film_force_gumbel_short(const BearingGeometry& g, double viscosity_Pa_s,
                                  const BearingState& s) {
  const double e = s.eps, ed = s.eps_dot, w = s.wedge;
  const double ew = e * w;
  if (ed == 0.0 && ew == 0.0) return FilmForce{};
  const double om = (1.0 - e) * (1.0 + e);
  const double sq = std::sqrt(om);
  // Positive half circle θ ∈ (θ₀, θ₀ + π), θ₀ = atan2(2ε̇, εw).
  const double th0 = std::atan2(2.0 * ed, ew);
  const double beta = detail::kepler_beta(e, sq);
  const double p0 = detail::psi_of_theta(th0, beta);
  const double p1 = p0 + kPi + 2.0 * std::atan(e * std::sin(th0) / sq);
  const auto E = [&](double p) {
    const double sp = std::sin(p);
    return 0.5 * sp * sp + e * std::cos(p);
  };
  const auto Q = [&](double p) {
    const double sp = std::sin(p), cp = std::cos(p);
    return (0.5 + e * e) * p + 0.5 * sp * cp - 2.0 * e * sp;
  };
  const auto B = [&](double p) { return 0.5 * p - 0.5 * std::sin(p) * std::cos(p); };
  const double dE = E(p1) - E(p0), dQ = Q(p1) - Q(p0), dB = B(p1) - B(p0);
  const double s3 = om * sq, s4 = om * om, s5 = s4 * sq;
  const double half_cs = 0.5 * short_bearing_coefficient(g, viscosity_Pa_s);
  FilmForce f;
  f.radial_N = half_cs * (ew * dE / s4 - 2.0 * ed * dQ / s5);
  f.tangential_N = half_cs * (ew * dB / s3 - 2.0 * ed * dE / s4);
  return f;
}

double pi_film_start(const BearingState& s) {
  return std::atan2((2.0 + s.eps * s.eps) * s.eps_dot, s.eps * s.wedge);
}

FilmForce film_force_pinkus_sternlicht_continuous(const BearingGeometry& g, double viscosity_Pa_s,
                                                  const BearingState& s) {
  const double e = s.eps, ed = s.eps_dot, w = s.wedge;
  if (ed == 0.0 && e * w == 0.0) return FilmForce{};  // no pressure at all
  const double om = (1.0 - e) * (1.0 + e);
  const double sq = std::sqrt(om);
  const double th1 = pi_film_start(s);
  const double p1 = detail::psi_of_theta(th1, detail::kepler_beta(e, sq));
  const double p2 = p1 + kPi + 2.0 * std::atan(e * std::sin(th1) / sq);
  const LongCoefficients kc = long_coefficients(e, sq, ed, w);
  double fr = 0.0, ft = 0.0;
  add_long_arc(kc, p1, p2, fr, ft);
  const double c6 = 6.0 * long_bearing_coefficient(g, viscosity_Pa_s);
  return FilmForce{c6 * fr, c6 * ft};
}

double pressure_short(const BearingGeometry& g, double viscosity_Pa_s, const BearingState& s,
                      double theta, double z) {
  // Eq. (3) with h = c(1 + ε cos θ), ∂h/∂θ = −c ε sin θ, ė = c ε̇:
  //   p = −3μ (L²/4 − z²) (2 ε̇ cos θ − ε w sin θ) / (c² (1 + ε cos θ)³).
  const double c = g.clearance_m();
  const double l = g.length_m;
  const double ct = std::cos(theta);
  const double st = std::sin(theta);
  const double hn = 1.0 + s.eps * ct;  // h / c
  return -3.0 * viscosity_Pa_s * (0.25 * l * l - z * z) *
         (2.0 * s.eps_dot * ct - s.eps * s.wedge * st) / (c * c * hn * hn * hn);
}

double pressure_long(const BearingGeometry& g, double viscosity_Pa_s, const BearingState& s,
                     double theta) {
  // Eq. (5). The squeeze term (ε̇/ε)[1/(1+ε cos θ)² − 1/(1+ε)²] is rewritten, exactly, as
  //   ε̇ (1 − cos θ)(2 + ε(1 + cos θ)) / ((1 + ε cos θ)² (1 + ε)²),
  // which has no division by ε and equals its limit 2 ε̇ (1 − cos θ) at ε = 0.
  const double c = g.clearance_m();
  const double rc = g.journal_radius_m / c;
  const double e = s.eps;
  const double ct = std::cos(theta);
  const double st = std::sin(theta);
  const double hn = 1.0 + e * ct;
  const double hn2 = hn * hn;
  const double ope = 1.0 + e;
  const double wedge_term = s.wedge * (2.0 + e * ct) * e * st / ((2.0 + e * e) * hn2);
  const double squeeze_term =
      s.eps_dot * (1.0 - ct) * (2.0 + e * (1.0 + ct)) / (hn2 * ope * ope);
  return 6.0 * viscosity_Pa_s * rc * rc * (wedge_term + squeeze_term);
}

double pressure_pi_film(const BearingGeometry& g, double viscosity_Pa_s, const BearingState& s,
                        double theta) {
  const double th1 = pi_film_start(s);
  double d = std::fmod(theta - th1, kTwoPi);
  if (d < 0.0) d += kTwoPi;
  if (d > kPi) return 0.0;  // outside the π film
  // Eq. (5) minus its value at θ₁, the squeeze difference written without division by ε:
  //   (ε̇/ε)[1/H² − 1/H₁²] = ε̇ (cos θ₁ − cos θ)(2 + ε(cos θ₁ + cos θ))/(H² H₁²).
  const double c = g.clearance_m();
  const double rc = g.journal_radius_m / c;
  const double e = s.eps;
  const auto wedge_shape = [e](double t) {
    const double h = 1.0 + e * std::cos(t);
    return (2.0 + e * std::cos(t)) * e * std::sin(t) / ((2.0 + e * e) * h * h);
  };
  const double c0 = std::cos(theta), c1 = std::cos(th1);
  const double h0 = 1.0 + e * c0, h1 = 1.0 + e * c1;
  const double squeeze = s.eps_dot * (c1 - c0) * (2.0 + e * (c1 + c0)) / (h0 * h0 * h1 * h1);
  return 6.0 * viscosity_Pa_s * rc * rc * (s.wedge * (wedge_shape(theta) - wedge_shape(th1)) + squeeze);
}

}  // namespace lub
