// Hydrodynamic force laws of a lubricated revolute joint: see force_laws.hpp for the
// formulas, symbols, limits and the known defects of the printed Pinkus–Sternlicht law.
//
// These functions run inside an ODE right-hand side: no allocation, no exceptions, and
// the few branches are selects on the sign of ε̇ or guards against 0/0.
#include "lub/force_laws.hpp"

#include <array>
#include <cmath>
#include <utility>

namespace lub {
namespace {

constexpr double kPi = 3.14159265358979323846;

constexpr std::array<std::pair<ForceLaw, std::string_view>, 3> kNames{{
    {ForceLaw::pinkus_sternlicht, "pinkus_sternlicht"},
    {ForceLaw::frene_long, "frene_long"},
    {ForceLaw::frene_short, "frene_short"},
}};

}  // namespace

std::string_view to_string(ForceLaw law) {
  for (const auto& [l, name] : kNames) {
    if (l == law) return name;
  }
  return "unknown";
}

bool parse_force_law(std::string_view name, ForceLaw& law) {
  for (const auto& [l, n] : kNames) {
    if (n == name) {
      law = l;
      return true;
    }
  }
  return false;
}

std::string force_law_names() {
  std::string out;
  for (const auto& entry : kNames) {
    if (!out.empty()) out += ", ";
    out += entry.second;
  }
  return out;
}

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

FilmForce film_force(ForceLaw law, const BearingGeometry& g, double viscosity_Pa_s,
                     const BearingState& s) {
  switch (law) {
    case ForceLaw::pinkus_sternlicht:
      return film_force_pinkus_sternlicht(g, viscosity_Pa_s, s);
    case ForceLaw::frene_long:
      return film_force_frene_long(g, viscosity_Pa_s, s);
    case ForceLaw::frene_short:
      return film_force_frene_short(g, viscosity_Pa_s, s);
  }
  return FilmForce{};  // unreachable for a valid enumerator
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

}  // namespace lub
