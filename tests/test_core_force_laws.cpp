// Tests of the hydrodynamic force laws (core/src/bearing/force_laws.cpp).
//
// Each closed form is checked against quadrature of its own pressure field, transcribed
// again here directly from the paper (Eqs. 3 and 5) so that a slip in the library's
// pressure functions cannot hide a slip in the forces. The printed Pinkus–Sternlicht law
// has no full pressure field to integrate; its limits and its known defects
// (docs/theory/force-laws.md) are pinned down numerically instead.
//
// Tolerances are relative to a force scale and each carries its reason.

#include "fixtures/film_quadrature.hpp"
#include "fixtures/bearing_fixture.hpp"
#include "fixtures/force_law_check.hpp"
#include "lub/bearing/film_force.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <optional>
#include <string>
#include <vector>

namespace {

using lub::BearingGeometry;
using lub::BearingState;
using lub::FilmForce;
using lub::ForceLaw;

constexpr double kPi = 3.14159265358979323846;

// The paper's slider-crank joint and the quadrature check (tests/fixtures/).
using bearing_fixture::kMu;
using bearing_fixture::long_coef;
using bearing_fixture::short_coef;
using bearing_fixture::state;
using bearing_fixture::test_geometry;
using bearing_fixture::worst_error_against_quadrature;

// --- Reference transcriptions of the paper's pressure fields (ε > 0) ------------------

// Eq. (3), written with h, ∂h/∂θ and ė as printed.
double ref_pressure_short(const BearingGeometry& g, const BearingState& s, double theta,
                          double z) {
  const double c = g.clearance_m();
  const double L = g.length_m;
  const double h = c * (1.0 + s.eps * std::cos(theta));
  const double dh_dtheta = -c * s.eps * std::sin(theta);
  const double e_dot = c * s.eps_dot;
  return -3.0 * kMu / (h * h * h) * (L * L / 4.0 - z * z) *
         (s.wedge * dh_dtheta + 2.0 * e_dot * std::cos(theta));
}

// Eq. (5) as printed (divides by ε: only for ε > 0).
double ref_pressure_long(const BearingGeometry& g, const BearingState& s, double theta) {
  const double e = s.eps;
  const double rc = g.journal_radius_m / g.clearance_m();
  const double ec = 1.0 + e * std::cos(theta);
  return 6.0 * kMu * rc * rc *
         (s.wedge * (2.0 + e * std::cos(theta)) * e * std::sin(theta) /
              ((2.0 + e * e) * ec * ec) +
          s.eps_dot / e * (1.0 / (ec * ec) - 1.0 / ((1.0 + e) * (1.0 + e))));
}

// --- Quadrature --------------------------------------------------------------------

// Quadrature (shared with the other force-law tests): tests/fixtures/film_quadrature.hpp.
using filmquad::Force2;
using filmquad::gauss_force;
using filmquad::positive_part_force;
using filmquad::trapezoid_force;

// Long-bearing pressure times L (units Pa m), from the reference transcription for ε > 0
// and from the library at ε = 0 (where Eq. 5 as printed is 0/0).
auto long_integrand(const BearingGeometry& g, const BearingState& s) {
  return [g, s](double th) {
    const double p = s.eps > 0.0 ? ref_pressure_long(g, s, th) : lub::pressure_long(g, kMu, s, th);
    return p * g.length_m;
  };
}

// Short-bearing pressure integrated over z ∈ [−L/2, L/2] (units Pa m) by 3-point
// Gauss–Legendre, exact for the quadratic z-dependence of Eq. (3).
auto short_integrand(const BearingGeometry& g, const BearingState& s) {
  return [g, s](double th) {
    const double hl = 0.5 * g.length_m;
    const double xs[3] = {-std::sqrt(0.6), 0.0, std::sqrt(0.6)};
    const double ws[3] = {5.0 / 9.0, 8.0 / 9.0, 5.0 / 9.0};
    double sum = 0.0;
    for (int i = 0; i < 3; ++i) {
      const double z = hl * xs[i];
      const double p = s.eps > 0.0 ? ref_pressure_short(g, s, th, z)
                                   : lub::pressure_short(g, kMu, s, th, z);
      sum += ws[i] * hl * p;
    }
    return sum;
  };
}

const double kEpsGrid[] = {0.0, 0.3, 0.5, 0.8, 0.95};
// (ε̇ [1/s], w [rad/s]): pure squeeze, pure wedge, and mixed, every sign combination.
const double kMotion[][2] = {{5.0, 0.0},    {-5.0, 0.0},  {0.0, 300.0}, {0.0, -300.0},
                             {5.0, 300.0},  {-5.0, 300.0}, {5.0, -300.0}, {-5.0, -300.0}};

// Trapezoid nodes: the integrands have poles at cos θ = −1/ε, a distance acosh(1/ε)
// ≈ 0.32 from the real axis at ε = 0.95, so the error ~ exp(−0.32 n) is ≈ 1e-140 at n = 1024.
constexpr int kTrapezoidNodes = 1024;

// Closed form vs quadrature: the quadrature error is far below rounding, so the residual is
// rounding in sums of ~1e3 terms whose largest term is at most ~30× the result (ε = 0.95),
// i.e. a few 1e-14 at worst; 1e-12 of the force scale is a safe bound that still catches any
// wrong factor or exponent (observed residuals, printed below, are ~2e-15).
constexpr double kQuadTol = 1e-12;

// --- Frêne et al. full-film laws against quadrature ----------------------------------

TEST(FreneLong, EqualsFullCircleIntegralOfEq5) {
  const auto g = test_geometry();
  const double worst = worst_error_against_quadrature(
      ForceLaw::frene_long, long_coef(g), kEpsGrid, kMotion, kQuadTol, [&](const BearingState& s) {
        return trapezoid_force(long_integrand(g, s), g.journal_radius_m, kTrapezoidNodes);
      });
  std::printf("[ measured ] frene_long vs quadrature of Eq. (5): max rel err %.3g\n", worst);
}

TEST(FreneShort, EqualsIntegralOfEq3OverLengthAndCircle) {
  const auto g = test_geometry();
  const double worst = worst_error_against_quadrature(
      ForceLaw::frene_short, short_coef(g), kEpsGrid, kMotion, kQuadTol, [&](const BearingState& s) {
        return trapezoid_force(short_integrand(g, s), g.journal_radius_m, kTrapezoidNodes);
      });
  std::printf("[ measured ] frene_short vs quadrature of Eq. (3): max rel err %.3g\n", worst);
}

TEST(FreneLaws, SignsFollowThePhysics) {
  // Squeeze resists ε̇ (F_r opposite to ε̇); wedge force along sign(w). Exact sign tests.
  const auto g = test_geometry();
  for (ForceLaw law : {ForceLaw::frene_long, ForceLaw::frene_short}) {
    EXPECT_LT(lub::film_force(law, g, kMu, state(0.5, 2.0, 0.0)).radial_N, 0.0);
    EXPECT_GT(lub::film_force(law, g, kMu, state(0.5, -2.0, 0.0)).radial_N, 0.0);
    EXPECT_GT(lub::film_force(law, g, kMu, state(0.5, 0.0, 100.0)).tangential_N, 0.0);
    EXPECT_LT(lub::film_force(law, g, kMu, state(0.5, 0.0, -100.0)).tangential_N, 0.0);
    // Pure wedge has no radial part in the full-film laws (odd integrand): exactly 0.
    EXPECT_EQ(lub::film_force(law, g, kMu, state(0.5, 0.0, 100.0)).radial_N, 0.0);
  }
}

TEST(Pressure, LibraryFieldsMatchThePaperTranscription) {
  // The library writes Eq. (5)'s squeeze term without the division by ε, and Eq. (3)
  // expanded; both are algebraically equal. Tolerance 1e-13 of the field's maximum: the
  // printed form's 1/(1+ε cos θ)² − 1/(1+ε)² loses ~log10(max/value) digits only where the
  // pressure is small compared with that maximum.
  const auto g = test_geometry();
  for (double eps : {0.3, 0.5, 0.8, 0.95}) {
    for (const auto& m : kMotion) {
      const auto s = state(eps, m[0], m[1]);
      double max_long = 0.0, max_short = 0.0;
      std::vector<double> th(257);
      for (std::size_t i = 0; i < th.size(); ++i) {
        th[i] = 2.0 * kPi * i / 256.0 + 1e-3;
        max_long = std::max(max_long, std::fabs(ref_pressure_long(g, s, th[i])));
        max_short = std::max(max_short, std::fabs(ref_pressure_short(g, s, th[i], 0.0)));
      }
      for (double t : th) {
        EXPECT_NEAR(lub::pressure_long(g, kMu, s, t), ref_pressure_long(g, s, t), 1e-13 * max_long);
        for (double z : {0.0, 0.3 * g.length_m, -0.45 * g.length_m}) {
          EXPECT_NEAR(lub::pressure_short(g, kMu, s, t, z), ref_pressure_short(g, s, t, z),
                      1e-13 * max_short);
        }
      }
    }
  }
}

TEST(Pressure, LongSqueezeTermAtZeroEccentricityIsItsLimit) {
  // Limit of (ε̇/ε)[1/(1+ε cos θ)² − 1/(1+ε)²] as ε → 0 is 2 ε̇ (1 − cos θ), so
  // p(ε = 0) = 12 μ (R/c)² ε̇ (1 − cos θ). Exact formula: 1e-14 relative (a few roundings).
  // At ε = 1e-9 the field moves by O(ε) relative: 1e-8 of the scale is a 10× margin.
  const auto g = test_geometry();
  const double rc = g.journal_radius_m / g.clearance_m();
  for (double ed : {-7.0, 3.0}) {
    for (double w : {0.0, 250.0}) {
      const double scale = 24.0 * kMu * rc * rc * (std::fabs(ed) + std::fabs(w));
      for (double t = 0.0; t < 2.0 * kPi; t += 0.37) {
        const double p0 = lub::pressure_long(g, kMu, state(0.0, ed, w), t);
        EXPECT_NEAR(p0, 12.0 * kMu * rc * rc * ed * (1.0 - std::cos(t)), 1e-14 * scale);
        EXPECT_NEAR(lub::pressure_long(g, kMu, state(1e-9, ed, w), t), p0, 1e-8 * scale);
      }
    }
  }
}

TEST(FreneLaws, ContinuousAtZeroEccentricity) {
  // |∂F/∂ε| at ε = 0 is at most 6π C|w| (long) and π C_s|w|/2 (short); ∂F_r/∂ε = 0. A step
  // of 1e-9 therefore moves F by < 2e-8 of C·(|ε̇| + |w|); 1e-7 is a 5× margin, and still
  // catches any wrong special case at ε = 0 (which would be off by O(1)).
  const auto g = test_geometry();
  for (ForceLaw law : {ForceLaw::frene_long, ForceLaw::frene_short}) {
    const double C = law == ForceLaw::frene_long ? long_coef(g) : short_coef(g);
    for (const auto& m : kMotion) {
      const FilmForce f0 = lub::film_force(law, g, kMu, state(0.0, m[0], m[1]));
      const FilmForce f1 = lub::film_force(law, g, kMu, state(1e-9, m[0], m[1]));
      const double tol = 1e-7 * C * (std::fabs(m[0]) + std::fabs(m[1]));
      EXPECT_NEAR(f1.radial_N, f0.radial_N, tol) << lub::name_of(law);
      EXPECT_NEAR(f1.tangential_N, f0.tangential_N, tol) << lub::name_of(law);
    }
    // The ε = 0 value itself is the closed form at ε = 0 (squeeze only).
    const FilmForce f = lub::film_force(law, g, kMu, state(0.0, 4.0, 100.0));
    const double expect_r = law == ForceLaw::frene_long ? -12.0 * kPi * C * 4.0 : -kPi * C * 4.0;
    EXPECT_NEAR(f.radial_N, expect_r, 1e-14 * std::fabs(expect_r));  // a few roundings
    EXPECT_EQ(f.tangential_N, 0.0);
  }
}

// --- Pinkus–Sternlicht as printed ---------------------------------------------------

// Direct transcription of Eqs. (10)–(14), forming k; valid where ε > 0 and ε̇ ≠ 0.
FilmForce ref_pinkus(const BearingGeometry& g, const BearingState& s) {
  const double C = long_coef(g);
  const double e = s.eps, ed = s.eps_dot, w = s.wedge;
  const double k = std::sqrt((1.0 - e * e) * (std::pow(w / (2.0 * ed), 2) + 1.0 / (e * e)));
  const double pre = C / ((2.0 + e * e) * std::pow(1.0 - e * e, 1.5));
  FilmForce f;
  if (ed > 0.0) {
    f.radial_N = -pre * 6.0 * ed * (4.0 * k * e * e + (2.0 + e * e) * kPi * (k + 3.0) / (k + 1.5));
    f.tangential_N = pre * 6.0 * kPi * e * w * (k + 3.0) / (k + 1.5);
  } else {
    f.radial_N = -pre * 6.0 * ed * (4.0 * k * e * e - (2.0 + e * e) * kPi * k / (k + 1.5));
    f.tangential_N = pre * 6.0 * kPi * e * w * k / (k + 1.5);
  }
  return f;
}

// Half-Sommerfeld (positive-part) long-bearing force of Eq. (5) for a state.
Force2 half_sommerfeld_long(const BearingGeometry& g, const BearingState& s) {
  return positive_part_force(long_integrand(g, s), g.journal_radius_m);
}

TEST(PinkusSternlicht, MatchesPrintedEquationsAwayFromLimits) {
  // The implementation never forms k (to avoid 0/0); away from the limits it must agree
  // with Eqs. (10)–(14) as printed. Both compute the same expression in a different order
  // with only mild cancellation (bracket terms within 10× of each other here): 1e-12.
  const auto g = test_geometry();
  double worst = 0.0;
  for (double eps : {0.05, 0.3, 0.5, 0.8, 0.95}) {
    for (double ed : {-50.0, -3.0, -0.2, 0.2, 3.0, 50.0}) {
      for (double w : {-400.0, -10.0, 0.0, 10.0, 400.0}) {
        const auto s = state(eps, ed, w);
        const FilmForce f = lub::film_force(ForceLaw::pinkus_sternlicht, g, kMu, s);
        const FilmForce r = ref_pinkus(g, s);
        const double scale = std::hypot(r.radial_N, r.tangential_N);
        const double err = std::max(std::fabs(f.radial_N - r.radial_N),
                                    std::fabs(f.tangential_N - r.tangential_N)) / scale;
        worst = std::max(worst, err);
        EXPECT_LT(err, 1e-12) << "eps=" << eps << " eps_dot=" << ed << " w=" << w;
      }
    }
  }
  std::printf("[ measured ] pinkus_sternlicht vs Eqs. (10)-(14) transcribed: max rel err %.3g\n",
              worst);
}

// The ε̇ → 0⁺ limit of Eqs. (10)–(11): F_r = −12 C ε²|w|/((2+ε²)(1−ε²)),
// F_t = 6π C ε w/((2+ε²)(1−ε²)^{3/2}).
FilmForce pinkus_limit_plus(double C, double e, double w) {
  FilmForce f;
  f.radial_N = -12.0 * C * e * e * std::fabs(w) / ((2.0 + e * e) * (1.0 - e * e));
  f.tangential_N = 6.0 * kPi * C * e * w / ((2.0 + e * e) * std::pow(1.0 - e * e, 1.5));
  return f;
}

// At ε̇ = 1e-12 and |w| = 300 the distance to the limit is O(1/k) = O(2ε̇/(|w|√(1−ε²)))
// ≈ 1e-14 (F_t) and O(ε̇/(ε²|w|)) ≈ 1e-13 (F_r) relative: tolerances 1e-12.
constexpr double kTinyRate = 1e-12;
constexpr double kLimitTol = 1e-12;

TEST(PinkusSternlicht, DefectTangentialForceExceedsHalfSommerfeldByInverseOneMinusEps2) {
  // (a) As ε̇ → 0⁺, F_t → C 6πε w/((2+ε²)(1−ε²)^{3/2}); the half-Sommerfeld value (positive
  // part of Eq. 5 with pure wedge, by quadrature) is smaller by exactly the factor (1 − ε²).
  const auto g = test_geometry();
  const double C = long_coef(g);
  double worst = 0.0;
  for (double eps : {0.3, 0.5, 0.8, 0.95}) {
    for (double w : {300.0, -300.0}) {
      const FilmForce lim = pinkus_limit_plus(C, eps, w);
      for (double ed : {0.0, kTinyRate}) {
        const FilmForce f = lub::film_force(ForceLaw::pinkus_sternlicht, g, kMu, state(eps, ed, w));
        EXPECT_NEAR(f.tangential_N, lim.tangential_N, kLimitTol * std::fabs(lim.tangential_N));
      }
      const Force2 hs = half_sommerfeld_long(g, state(eps, 0.0, w));
      // Quadrature vs the closed factor: same rounding budget as the full-circle check.
      const double err = std::fabs(hs.t / lim.tangential_N - (1.0 - eps * eps));
      worst = std::max(worst, err);
      EXPECT_LT(err, kQuadTol) << "eps=" << eps << " w=" << w;
      // The factor is a real defect, not rounding: it differs from 1 by ε² >= 0.09.
      EXPECT_GT(std::fabs(hs.t - lim.tangential_N), 0.08 * std::fabs(lim.tangential_N));
    }
  }
  std::printf("[ measured ] half-Sommerfeld F_t quadrature / PS limit vs (1-eps^2): max abs err %.3g\n",
              worst);
}

TEST(PinkusSternlicht, RadialForceAtZeroRateEqualsHalfSommerfeld) {
  // (b) F_r as ε̇ → 0⁺ (and at ε̇ = 0, which takes that branch) equals the half-Sommerfeld
  // radial force, for either sign of w (the positive region is (0, π) or (π, 2π)).
  const auto g = test_geometry();
  double worst = 0.0;
  for (double eps : {0.3, 0.5, 0.8, 0.95}) {
    for (double w : {300.0, -300.0}) {
      const Force2 hs = half_sommerfeld_long(g, state(eps, 0.0, w));
      for (double ed : {0.0, kTinyRate}) {
        const FilmForce f = lub::film_force(ForceLaw::pinkus_sternlicht, g, kMu, state(eps, ed, w));
        const double err = std::fabs(f.radial_N - hs.r) / std::fabs(hs.r);
        if (ed == 0.0) worst = std::max(worst, err);
        // Quadrature rounding (1e-12, as above) plus the O(1e-13) distance to the limit.
        EXPECT_LT(err, kQuadTol + kLimitTol) << "eps=" << eps << " w=" << w << " ed=" << ed;
      }
      EXPECT_LT(hs.r, 0.0);  // the half film pushes the journal towards the centre
    }
  }
  std::printf("[ measured ] pinkus_sternlicht F_r(eps_dot=0) vs half-Sommerfeld quadrature: max rel err %.3g\n",
              worst);
}

TEST(PinkusSternlicht, DefectRadialForceJumpsInSignAcrossZeroRate) {
  // (c) F_r(ε̇ → 0⁻) = −F_r(ε̇ → 0⁺) whenever w ≠ 0; F_t is continuous.
  const auto g = test_geometry();
  const double C = long_coef(g);
  for (double eps : {0.3, 0.5, 0.8, 0.95}) {
    for (double w : {300.0, -300.0, 5.0}) {
      const FilmForce lim = pinkus_limit_plus(C, eps, w);
      const FilmForce fp = lub::film_force(ForceLaw::pinkus_sternlicht, g, kMu, state(eps, kTinyRate, w));
      const FilmForce fm = lub::film_force(ForceLaw::pinkus_sternlicht, g, kMu, state(eps, -kTinyRate, w));
      // At w = 5 the distance to the limit is 60× larger than at 300 (1/k ∝ ε̇/|w|): ≈ 1e-11
      // relative, so the tolerance is scaled by 300/|w|.
      const double tol = kLimitTol * 300.0 / std::fabs(w);
      EXPECT_NEAR(fp.radial_N, lim.radial_N, tol * std::fabs(lim.radial_N));
      EXPECT_NEAR(fm.radial_N, -lim.radial_N, tol * std::fabs(lim.radial_N));
      EXPECT_NEAR(fm.tangential_N, fp.tangential_N, tol * std::fabs(lim.tangential_N));
      EXPECT_LT(fp.radial_N, 0.0);
      EXPECT_GT(fm.radial_N, 0.0);  // the jump: the sign flips, the size does not shrink
    }
  }
}

TEST(PinkusSternlicht, ZeroRateAndZeroEccentricityLimitsAreFiniteAndAttained) {
  // (d) The value at ε̇ = 0 exactly is the ε̇ → 0⁺ limit; at ε = 0 exactly it is the ε → 0⁺
  // limit. Sequences approach the exact-zero values; differences shrink like the step.
  const auto g = test_geometry();
  const double C = long_coef(g);
  const auto ps = [&](double e, double ed, double w) {
    return lub::film_force(ForceLaw::pinkus_sternlicht, g, kMu, state(e, ed, w));
  };
  for (double eps : {1e-6, 0.3, 0.8}) {
    for (double w : {300.0, -40.0}) {
      const FilmForce f0 = ps(eps, 0.0, w);
      const FilmForce lim = pinkus_limit_plus(C, eps, w);
      // Closed-form limit vs the code at ε̇ = 0: a few roundings apart, 1e-14.
      EXPECT_NEAR(f0.radial_N, lim.radial_N, 1e-14 * std::fabs(lim.radial_N));
      EXPECT_NEAR(f0.tangential_N, lim.tangential_N, 1e-14 * std::fabs(lim.tangential_N));
      // Lipschitz bound of the distance to the limit, from Eqs. (10)–(14) with
      // 1/k <= 2|ε̇|/(√(1−ε²)|w|), 0 <= ε̇kε² − ε²√(1−ε²)|w|/2 <= ε√(1−ε²)|ε̇| and
      // (k+3)/(k+3/2) <= 2:   |F(±ε̇) − F(0±)| <= K |ε̇|,
      // K = P (4ε√(1−ε²) + 2π(2+ε²) + 3πε/√(1−ε²)),  P = 6C/((2+ε²)(1−ε²)^{3/2}),
      // plus 1e-14 of |F(0)| for rounding. F(0−) is F(0) with F_r negated.
      const double s1 = std::sqrt(1.0 - eps * eps);
      const double P = 6.0 * C / ((2.0 + eps * eps) * std::pow(1.0 - eps * eps, 1.5));
      const double K = P * (4.0 * eps * s1 + 2.0 * kPi * (2.0 + eps * eps) + 3.0 * kPi * eps / s1);
      const double round = 1e-14 * std::hypot(f0.radial_N, f0.tangential_N);
      for (double ed : {1e-3, 1e-6, 1e-9, 1e-12}) {
        const FilmForce fp = ps(eps, ed, w);
        const FilmForce fm = ps(eps, -ed, w);
        EXPECT_LE(std::hypot(fp.radial_N - f0.radial_N, fp.tangential_N - f0.tangential_N),
                  K * ed + round)
            << "eps=" << eps << " w=" << w << " ed=+" << ed;
        EXPECT_LE(std::hypot(fm.radial_N + f0.radial_N, fm.tangential_N - f0.tangential_N),
                  K * ed + round)
            << "eps=" << eps << " w=" << w << " ed=-" << ed;
      }
    }
  }
  // ε → 0 with ε̇ ≠ 0: F_r → −6πC|ε̇| on both branches, F_t → 0. At ε = 1e-9 the distance
  // is O(ε) of the scale 6πC(|ε̇| + |w|): (k+3)/(k+3/2) − 1 ≈ 1.5/k ≈ 1.5ε and
  // 4ε̇kε²/(2πε̇) ≈ 0.64ε, so ≈ 2.2e-9 of the scale; 1e-8 is a 4.5× margin.
  for (double ed : {-10.0, -0.1, 0.1, 10.0}) {
    for (double w : {0.0, 300.0, -300.0}) {
      const FilmForce f0 = ps(0.0, ed, w);
      const double expect_r = -6.0 * kPi * C * std::fabs(ed);
      EXPECT_NEAR(f0.radial_N, expect_r, 1e-14 * std::fabs(expect_r));
      EXPECT_EQ(f0.tangential_N, 0.0);
      const FilmForce f1 = ps(1e-9, ed, w);
      const double scale = 6.0 * kPi * C * (std::fabs(ed) + std::fabs(w));
      EXPECT_NEAR(f1.radial_N, f0.radial_N, 1e-8 * scale) << "ed=" << ed << " w=" << w;
      EXPECT_NEAR(f1.tangential_N, f0.tangential_N, 1e-8 * scale) << "ed=" << ed << " w=" << w;
    }
  }
  // ε̇ = 0 together with w = 0, or with ε = 0: the force is exactly 0.
  for (double eps : {0.0, 0.5}) {
    const FilmForce f = ps(eps, 0.0, 0.0);
    EXPECT_EQ(f.radial_N, 0.0);
    EXPECT_EQ(f.tangential_N, 0.0);
  }
  const FilmForce fz = ps(0.0, 0.0, 300.0);
  EXPECT_EQ(fz.radial_N, 0.0);
  EXPECT_EQ(fz.tangential_N, 0.0);
  // −0.0 takes the ε̇ >= 0 branch too.
  const FilmForce fneg0 = ps(0.5, -0.0, 300.0);
  const FilmForce fpos0 = ps(0.5, 0.0, 300.0);
  EXPECT_EQ(fneg0.radial_N, fpos0.radial_N);
  EXPECT_EQ(fneg0.tangential_N, fpos0.tangential_N);
}

TEST(PinkusSternlicht, DefectInwardMotionIsSpedUpWithoutWedge) {
  // (e) ε = 0.3, ε̇ = −10 1/s, w = 0: Eq. (12) gives F_r < 0 (towards the centre, along the
  // motion), while the full film (Frêne long) pushes back (F_r > 0). Sign tests; the
  // margins are O(1) of the force, not rounding.
  const auto g = test_geometry();
  const auto s = state(0.3, -10.0, 0.0);
  const FilmForce ps = lub::film_force(ForceLaw::pinkus_sternlicht, g, kMu, s);
  const FilmForce fl = lub::film_force(ForceLaw::frene_long, g, kMu, s);
  EXPECT_LT(ps.radial_N, 0.0);
  EXPECT_GT(fl.radial_N, 0.0);
  EXPECT_EQ(ps.tangential_N, 0.0);
  // The half film gives zero here: the squeeze pressure of Eq. (5) is <= 0 everywhere for
  // ε̇ < 0. Its positive part must be 0 up to rounding of p at the θ = 0 zero.
  const Force2 hs = half_sommerfeld_long(g, s);
  EXPECT_LT(std::hypot(hs.r, hs.t), 1e-12 * std::fabs(fl.radial_N));
}

// --- Robustness -----------------------------------------------------------------------

TEST(ForceLaws, NeverNanOrInfOverLimitGrid) {
  const auto g = test_geometry();
  const double eps_grid[] = {0.0, 1e-300, 1e-8, 0.5, 0.999};
  const double rate_grid[] = {-1e3, -1e-12, 0.0, 1e-12, 1e3};
  const double wedge_grid[] = {-1e3, 0.0, 1e3};
  for (ForceLaw law : {ForceLaw::pinkus_sternlicht, ForceLaw::frene_long, ForceLaw::frene_short}) {
    for (double e : eps_grid) {
      for (double ed : rate_grid) {
        for (double w : wedge_grid) {
          const auto s = state(e, ed, w);
          const FilmForce f = lub::film_force(law, g, kMu, s);
          EXPECT_TRUE(std::isfinite(f.radial_N) && std::isfinite(f.tangential_N))
              << lub::name_of(law) << " eps=" << e << " ed=" << ed << " w=" << w;
          for (double t : {0.0, 1.0, kPi, 4.0}) {
            EXPECT_TRUE(std::isfinite(lub::pressure_long(g, kMu, s, t)));
            EXPECT_TRUE(std::isfinite(lub::pressure_short(g, kMu, s, t, 0.0)));
            EXPECT_TRUE(std::isfinite(lub::pressure_short(g, kMu, s, t, 0.25 * g.length_m)));
          }
        }
      }
    }
  }
}

TEST(ForceLaws, DispatchMatchesIndividualFunctions) {
  const auto g = test_geometry();
  const auto s = state(0.4, -2.0, 150.0);
  const auto same = [](const FilmForce& a, const FilmForce& b) {
    return a.radial_N == b.radial_N && a.tangential_N == b.tangential_N;
  };
  EXPECT_TRUE(same(lub::film_force(ForceLaw::pinkus_sternlicht, g, kMu, s),
                   lub::film_force_pinkus_sternlicht(g, kMu, s)));
  EXPECT_TRUE(same(lub::film_force(ForceLaw::frene_long, g, kMu, s),
                   lub::film_force_frene_long(g, kMu, s)));
  EXPECT_TRUE(same(lub::film_force(ForceLaw::frene_short, g, kMu, s),
                   lub::film_force_frene_short(g, kMu, s)));
  EXPECT_DOUBLE_EQ(lub::long_bearing_coefficient(g, kMu), long_coef(g));
  EXPECT_DOUBLE_EQ(lub::short_bearing_coefficient(g, kMu), short_coef(g));
}

// --- Names ----------------------------------------------------------------------------

TEST(ForceLawNames, RoundTripAndRejectUnknown) {
  const ForceLaw all[] = {ForceLaw::pinkus_sternlicht, ForceLaw::frene_long, ForceLaw::frene_short,
                          ForceLaw::gumbel_long, ForceLaw::gumbel_short,
                          ForceLaw::pinkus_sternlicht_continuous, ForceLaw::finite_reynolds};
  const std::string names = lub::names_list<lub::ForceLaw>();
  for (ForceLaw law : all) {
    const std::optional<ForceLaw> parsed = lub::parse_name<ForceLaw>(lub::name_of(law));
    EXPECT_TRUE(parsed) << lub::name_of(law);
    if (!parsed) continue;
    EXPECT_EQ(*parsed, law);
    EXPECT_NE(names.find(std::string(lub::name_of(law))), std::string::npos) << names;
  }
  EXPECT_EQ(lub::name_of(ForceLaw::pinkus_sternlicht), "pinkus_sternlicht");
  EXPECT_EQ(lub::name_of(ForceLaw::frene_long), "frene_long");
  EXPECT_EQ(lub::name_of(ForceLaw::frene_short), "frene_short");
  EXPECT_EQ(lub::name_of(ForceLaw::gumbel_long), "gumbel_long");
  EXPECT_EQ(lub::name_of(ForceLaw::gumbel_short), "gumbel_short");
  EXPECT_EQ(lub::name_of(ForceLaw::pinkus_sternlicht_continuous), "pinkus_sternlicht_continuous");
  EXPECT_EQ(lub::name_of(ForceLaw::finite_reynolds), "finite_reynolds");
  EXPECT_EQ(names,
            "pinkus_sternlicht, frene_long, frene_short, gumbel_long, gumbel_short, "
            "pinkus_sternlicht_continuous, finite_reynolds");
  for (const char* bad : {"", "frene", "Frene_long", "frene_long ", "pinkus", "gumbel",
                          "pinkus_sternlicht,frene_long", "finite", "reynolds"}) {
    EXPECT_FALSE(lub::parse_name<ForceLaw>(bad)) << '"' << bad << '"';
  }
}

TEST(CavitationNames, RoundTripAndRejectUnknown) {
  for (lub::Cavitation c : {lub::Cavitation::gumbel, lub::Cavitation::reynolds, lub::Cavitation::sommerfeld}) {
    EXPECT_EQ(lub::parse_name<lub::Cavitation>(lub::name_of(c)), c);
  }
  EXPECT_EQ(lub::names_list<lub::Cavitation>(), "gumbel, reynolds, sommerfeld");
  EXPECT_FALSE(lub::parse_name<lub::Cavitation>("Reynolds"));
}

}  // namespace
