// The steady stage on systems whose periodic orbits and Floquet multipliers are known in
// closed form: an affine period map, a damped linear oscillator under periodic forcing
// integrated by CVODE, and the contraction estimate on synthetic transients.
#include <gtest/gtest.h>

#include <cmath>
#include <complex>
#include <limits>

#include "lub/integrators/integrator.hpp"
#include "lub/steady/contraction.hpp"
#include "lub/steady/periodic_orbit.hpp"

namespace {

constexpr double kPi = 3.14159265358979323846;

// P(z) = A z + b with A = r R(θ) ⊕ diag(d): multipliers r e^{±iθ} and d; fixed point
// (I − A)⁻¹ b. `fail_beyond`: the map cannot be evaluated where |z|∞ exceeds it.
class AffineMap final : public lub::steady::CycleMap {
 public:
  AffineMap(double r, double theta, double d, double fail_beyond = 1e300) : fail_(fail_beyond) {
    A_.setZero(3, 3);
    A_ << r * std::cos(theta), -r * std::sin(theta), 0, r * std::sin(theta), r * std::cos(theta), 0, 0, 0, d;
    b_ = Eigen::Vector3d(0.3, -0.2, 0.1);
  }
  int dim() const override { return 3; }
  int apply(const double* z, double* Pz) override {
    const Eigen::Map<const Eigen::Vector3d> zv(z);
    if (zv.lpNorm<Eigen::Infinity>() > fail_) {
      ++failures;
      return 1;
    }
    Eigen::Map<Eigen::Vector3d> out(Pz);
    out = A_ * zv + b_;
    return 0;
  }
  Eigen::Vector3d fixed_point() const { return (Eigen::Matrix3d::Identity() - A_).lu().solve(b_); }
  int failures = 0;  ///< evaluations refused outside the domain

 private:
  Eigen::MatrixXd A_;
  Eigen::Vector3d b_;
  double fail_;
};

/// Shooting on an AffineMap to round-off: unit scales, difference steps of 1e-2.
lub::steady::ShootingOptions affine_options() {
  lub::steady::ShootingOptions o;
  o.scales = {1.0, 1.0, 1.0};
  o.tolerance = 1e-13;
  o.step = 1e-2;
  return o;
}

TEST(PeriodicOrbit, AffineMapFixedPointAndMultipliersToRoundOff) {
  // A slowly turning, weakly damped pair (like Frêne long's) and a fast decaying mode.
  AffineMap P(0.998, 0.93, 1e-3);
  const lub::steady::ShootingOptions o = affine_options();
  const auto sh = lub::steady::solve_periodic_orbit(P, Eigen::Vector3d(0.5, 0.5, 0.5), o);
  ASSERT_EQ(sh.outcome, lub::steady::ShootingOutcome::converged) << sh.message;
  // A linear residual: Newton with the exact Jacobian (differences of an affine map are
  // exact up to round-off) lands on the fixed point in one step; the iteration limit would
  // show a wrong Jacobian.
  EXPECT_LE(sh.iterations, 3);
  EXPECT_LT((sh.z - P.fixed_point()).lpNorm<Eigen::Infinity>(), 1e-10);  // (I − A)⁻¹ ~ 1/0.002 × 1e-13
  lub::steady::MonodromyOptions mo{o.scales, 1e-2, true};
  const auto mono = lub::steady::monodromy_by_differences(P, sh.z, sh.Pz, mo);
  ASSERT_EQ(mono.failed, 0);
  const auto mu = lub::steady::floquet_multipliers(mono.M);
  ASSERT_EQ(mu.size(), 3u);
  // Round-off of a difference quotient with step 1e-2 on values of order 1: ~1e-14.
  EXPECT_NEAR(std::abs(mu[0]), 0.998, 1e-13);
  EXPECT_NEAR(std::abs(mu[1]), 0.998, 1e-13);
  EXPECT_NEAR(std::abs(std::arg(mu[0])), 0.93, 1e-13);
  EXPECT_NEAR(std::arg(mu[0]), -std::arg(mu[1]), 1e-13);
  EXPECT_NEAR(std::abs(mu[2]), 1e-3, 1e-13);
}

TEST(PeriodicOrbit, WalkingOutOfTheDomainIsReportedAsSuch) {
  // An unstable affine map whose fixed point lies outside the domain |z| <= 0.5: Newton
  // heads for it and every trial beyond the domain fails.
  AffineMap P(1.5, 0.0, 1.5, 0.5);
  lub::steady::ShootingOptions o;
  o.scales = {1.0, 1.0, 1.0};
  o.max_newton_step = 10.0;
  // (I − A)⁻¹ b = −2 b: (−0.6, 0.4, −0.2), |z| = 0.6 > 0.5.
  const auto sh = lub::steady::solve_periodic_orbit(P, Eigen::Vector3d(0.0, 0.0, 0.0), o);
  EXPECT_NE(sh.outcome, lub::steady::ShootingOutcome::converged);
  EXPECT_EQ(sh.outcome, lub::steady::ShootingOutcome::left_domain) << sh.message;
}

TEST(PeriodicOrbit, AStepToleranceAtTheMapsNoiseEndsTheLineSearchThere) {
  // A map whose fixed point lies under noise of 1e-6 (a deterministic function of z, as an
  // adaptive integration's step sequence is): Newton reaches the noise, then its line search
  // backtracks, a map a trial. With the shortest step at the noise it stops there, at a
  // residual as good, in fewer maps; the fixed point of the smooth part is still found.
  class Noisy final : public lub::steady::CycleMap {
   public:
    int dim() const override { return 2; }
    int apply(const double* z, double* Pz) override {
      for (int i = 0; i < 2; ++i)
        Pz[i] = 0.5 + 0.9 * (z[i] - 0.5) + 1e-6 * std::sin(1e9 * z[i] + 3.0 * z[1 - i]);
      return 0;
    }
  };
  lub::steady::ShootingOptions o;
  o.scales = {1.0, 1.0};
  o.tolerance = 1e-12;  // below the noise: never reached
  o.noise_factor = 1.0;
  o.step = 1e-2;
  o.max_iterations = 50;
  Noisy P;
  const auto fine = lub::steady::solve_periodic_orbit(P, Eigen::Vector2d(0.2, 0.7), o);
  o.step_tolerance = 1e-6;
  const auto coarse = lub::steady::solve_periodic_orbit(P, Eigen::Vector2d(0.2, 0.7), o);
  ASSERT_NE(fine.outcome, lub::steady::ShootingOutcome::converged);
  ASSERT_NE(coarse.outcome, lub::steady::ShootingOutcome::converged);
  EXPECT_LT(coarse.maps, fine.maps);
  // Both within the noise (2e-6 in P − z) over 1 − μ = 0.1 of the point.
  EXPECT_LT(std::abs(coarse.z(0) - 0.5), 2e-5);
  EXPECT_LT(std::abs(coarse.z(1) - 0.5), 2e-5);
  EXPECT_LT(coarse.residual, 1e-5);
}

TEST(PeriodicOrbit, ANewtonWhoseResidualStopsHalvingIsStoppedAndOneThatConvergesIsNot) {
  // P(z) − z = (0.5 + 0.1 sin 5 z₀, −0.5 z₁): no fixed point (the first component stays
  // above 0.4), so the residual can never halve from its start; Newton wanders where the
  // first component's slope turns. With stagnation_maps it stops after that many trial
  // periods without progress, not_converged (not a walk out of the domain), its best
  // iterate kept; without, it spends its iterations.
  class NoFixedPoint final : public lub::steady::CycleMap {
   public:
    int dim() const override { return 2; }
    int apply(const double* z, double* Pz) override {
      Pz[0] = z[0] + 0.5 + 0.1 * std::sin(5.0 * z[0]);
      Pz[1] = 0.5 * z[1];
      return 0;
    }
  };
  lub::steady::ShootingOptions o;
  o.scales = {1.0, 1.0};
  o.step = 1e-3;
  NoFixedPoint P;
  const auto spent = lub::steady::solve_periodic_orbit(P, Eigen::Vector2d(0.1, 0.3), o);
  o.stagnation_maps = 5;
  o.stagnation_floor = 1e-4;
  const auto stopped = lub::steady::solve_periodic_orbit(P, Eigen::Vector2d(0.1, 0.3), o);
  EXPECT_EQ(stopped.outcome, lub::steady::ShootingOutcome::not_converged) << stopped.message;
  EXPECT_NE(stopped.message.find("did not halve in 5"), std::string::npos) << stopped.message;
  EXPECT_LT(stopped.maps, spent.maps);
  EXPECT_LE(stopped.residual, 0.61);  // its best iterate: the start's residual or better
  // A Newton that converges halves its residual every iteration: the same result.
  AffineMap A(0.998, 0.93, 1e-3);
  lub::steady::ShootingOptions a = affine_options();
  const auto free = lub::steady::solve_periodic_orbit(A, Eigen::Vector3d(0.5, 0.5, 0.5), a);
  a.stagnation_maps = 5;
  a.stagnation_floor = 1e-4;
  const auto watched = lub::steady::solve_periodic_orbit(A, Eigen::Vector3d(0.5, 0.5, 0.5), a);
  ASSERT_EQ(watched.outcome, lub::steady::ShootingOutcome::converged);
  EXPECT_EQ(watched.maps, free.maps);
  EXPECT_EQ((watched.z - free.z).lpNorm<Eigen::Infinity>(), 0.0);
}

// x'' + 2ζω x' + ω² x = F cos(Ω t), one forcing period T = 2π/Ω per map, by CVODE BDF.
class ForcedOscillator final : public lub::OdeSystem {
 public:
  double zeta = 0.05, omega = 7.0, F = 3.0, Omega = 2.0;
  int size() const override { return 2; }
  int rhs(double t, const double* y, double* yd) override {
    yd[0] = y[1];
    yd[1] = F * std::cos(Omega * t) - 2 * zeta * omega * y[1] - omega * omega * y[0];
    return 0;
  }
};

class OscillatorMap final : public lub::steady::CycleMap {
 public:
  explicit OscillatorMap(double rtol) : rtol_(rtol) {}
  ForcedOscillator sys;
  int dim() const override { return 2; }
  int apply(const double* z, double* Pz) override {
    const double T = 2 * kPi / sys.Omega;
    lub::IntegratorSettings s;
    s.method = lub::Method::cvode_bdf;
    s.rtol = rtol_;
    s.atol = {rtol_, rtol_ * sys.omega};
    s.t_stop = T;
    auto integ = lub::make_integrator(s, sys, 0.0, std::vector<double>{z[0], z[1]});
    double t = 0.0;
    while (t < T * (1 - 1e-15))
      if (integ->step(t) == lub::StepOutcome::failure) return 1;
    Pz[0] = integ->y()[0];
    Pz[1] = integ->y()[1];
    return 0;
  }

 private:
  double rtol_;
};

TEST(PeriodicOrbit, ForcedDampedOscillatorMatchesItsClosedForm) {
  OscillatorMap P(1e-12);
  const ForcedOscillator& s = P.sys;
  // The steady response X cos(Ωt − φ): z* = (X cos φ, X Ω sin φ).
  const std::complex<double> H = 1.0 / std::complex<double>(s.omega * s.omega - s.Omega * s.Omega,
                                                            2 * s.zeta * s.omega * s.Omega);
  const double X = s.F * std::abs(H), phi = -std::arg(H);
  const Eigen::Vector2d z_exact(X * std::cos(phi), X * s.Omega * std::sin(phi));
  lub::steady::ShootingOptions o;
  o.scales = {X, X * s.omega};
  o.tolerance = 1e-10;
  o.step = 1e-2;
  const auto sh = lub::steady::solve_periodic_orbit(P, Eigen::Vector2d(0.0, 0.0), o);
  ASSERT_EQ(sh.outcome, lub::steady::ShootingOutcome::converged) << sh.message;
  // The orbit to the integration's accuracy (rtol 1e-12 over one period, amplified by
  // (I − M)⁻¹ ~ 1 here: the multipliers are small).
  EXPECT_LT((sh.z - z_exact).cwiseQuotient(Eigen::Vector2d(X, X * s.omega)).lpNorm<Eigen::Infinity>(), 1e-8);
  // Multipliers e^{λT}, λ = −ζω ± iω√(1 − ζ²): modulus e^{−ζωT}, angle ω√(1 − ζ²) T mod 2π.
  // The map is linear: a difference step of the state's own size has no truncation error
  // and divides the integration error by the most.
  lub::steady::MonodromyOptions mo{o.scales, 1.0, true};
  const auto mono = lub::steady::monodromy_by_differences(P, sh.z, sh.Pz, mo);
  const auto mu = lub::steady::floquet_multipliers(mono.M);
  const double T = 2 * kPi / s.Omega;
  const double modulus = std::exp(-s.zeta * s.omega * T);
  const double angle = std::remainder(s.omega * std::sqrt(1 - s.zeta * s.zeta) * T, 2 * kPi);
  ASSERT_EQ(mu.size(), 2u);
  // The quotients carry only the integration error: CVODE's global error over a period
  // at rtol 1e-12 is ~1e-9 of the state (with a step of 1e-2 of the state the multipliers
  // were off by 1.3e-7); over a step of the state's size, 1e-8 holds.
  EXPECT_NEAR(std::abs(mu[0]), modulus, 1e-8 * modulus + 1e-10);
  EXPECT_NEAR(std::abs(mu[1]), modulus, 1e-8 * modulus + 1e-10);
  EXPECT_NEAR(std::abs(std::arg(mu[0])), std::abs(angle), 1e-8);
}

TEST(Contraction, GeometricDistancesGiveTheirRateAndRemainingDistance) {
  std::vector<double> d = {-1.0};  // the first cycle has no distance
  for (int k = 1; k <= 20; ++k) d.push_back(0.4 * std::pow(0.9, k));
  const auto e = lub::steady::estimate_contraction(d, 10, 1e-12);
  ASSERT_TRUE(e.known);
  EXPECT_NEAR(e.rate, 0.9, 1e-12);
  EXPECT_NEAR(e.remaining, d.back() * 0.9 / 0.1, 1e-12);
  EXPECT_FALSE(lub::steady::transient_converged(e, 1e-3));
  EXPECT_TRUE(lub::steady::transient_converged(e, 0.5));  // remaining 0.437
  // Cycles still needed to reach 1e-3: log(1e-3 / remaining) / log 0.9.
  EXPECT_NEAR(lub::steady::cycles_to_converge(e, 1e-3), std::log(1e-3 / e.remaining) / std::log(0.9), 1e-9);
}

TEST(Contraction, ASlowDriftBelowTheOldThresholdIsNotSteady) {
  // δ = 2e-4 per cycle, shrinking 1 % per cycle: each cycle repeats the last within the
  // old 1e-3 threshold, but the orbit is still 2e-2 from its limit.
  std::vector<double> d;
  for (int k = 0; k < 20; ++k) d.push_back(2e-4 * std::pow(0.99, k));
  const auto e = lub::steady::estimate_contraction(d, 10, 1e-12);
  ASSERT_TRUE(e.known);
  EXPECT_GT(e.remaining, 1e-2);
  EXPECT_FALSE(lub::steady::transient_converged(e, 1e-3));
  // A distance that does not shrink at all: unbounded.
  const auto flat = lub::steady::estimate_contraction(std::vector<double>(12, 1e-4), 10, 1e-12);
  EXPECT_GE(flat.rate, 1.0);
  EXPECT_FALSE(lub::steady::transient_converged(flat, 1e-3));
}

TEST(Contraction, AComplexPairIsNotMistakenForConvergenceAtATrough) {
  // δ_k = ρ^k |cos(kθ)|: the last value sits near a zero of the cosine.
  std::vector<double> d;
  const double theta = 0.93;
  int last = 0;
  for (int k = 1; k < 60; ++k)
    if (std::abs(std::cos(k * theta)) < 0.05) last = k;
  for (int k = 1; k <= last; ++k) d.push_back(1e-2 * std::pow(0.98, k) * (std::abs(std::cos(k * theta)) + 1e-3));
  const auto e = lub::steady::estimate_contraction(d, 10, 1e-12);
  ASSERT_TRUE(e.known);
  EXPECT_GT(e.remaining, 10 * d.back());  // not fooled by the small last distance
  EXPECT_FALSE(lub::steady::transient_converged(e, 1e-3));
}

TEST(Contraction, NoiseFloorAndTooFewCycles) {
  EXPECT_FALSE(lub::steady::estimate_contraction({-1.0, 1e-3, 1e-4}, 10, 1e-9).known);
  const auto e = lub::steady::estimate_contraction(std::vector<double>(8, 1e-12), 10, 1e-9);
  ASSERT_TRUE(e.known);
  EXPECT_TRUE(lub::steady::transient_converged(e, 1e-3));
  EXPECT_NEAR(lub::steady::trend_per_cycle({5.0, 4.0, 3.0, 2.0}, 10), -1.0, 1e-14);
  EXPECT_EQ(lub::steady::trend_per_cycle({5.0}, 10), 0.0);
}

}  // namespace

namespace {

// A slow manifold in closed form: z = (s, f), s creeping towards its limit s* by a factor
// 1 − κ(s) each period (κ small and changing along the way, as a film's thinning rate
// does near the wall), f slaved to s and decaying fast.
//   s' = s* + (1 − κ(s)) (s − s*),  κ(s) = 2e-3 (1 + s²),   f' = 0.2 f + 0.1 sin s.
// The plain iteration needs ~ln(1e6)/κ ≈ 5000 periods to get to 1e-6 of s*.
class SlowManifoldMap final : public lub::steady::CycleMap {
 public:
  static constexpr double kLimit = 1.5;
  int dim() const override { return 2; }
  int apply(const double* z, double* Pz) override {
    ++maps;
    const double s = z[0], f = z[1];
    if (s > wall) {
      ++failures;
      return 1;
    }
    const double kappa = 2e-3 * (1.0 + s * s);
    Pz[0] = kLimit + (1.0 - kappa) * (s - kLimit);
    Pz[1] = 0.2 * f + 0.1 * std::sin(s);
    return 0;
  }
  long long maps = 0;
  double wall = 1e300;  ///< s beyond it cannot be evaluated
  int failures = 0;
};

TEST(AndersonFixedPoint, CrossesASlowManifoldInTensOfPeriods) {
  SlowManifoldMap P;
  lub::steady::AndersonOptions o;
  o.residual_scales = {1.0, 1.0};
  o.tolerance = 1e-10;
  o.max_maps = 100;
  const auto r = lub::steady::anderson_fixed_point(P, Eigen::Vector2d(-1.0, 0.0), o);
  ASSERT_EQ(r.outcome, lub::steady::ShootingOutcome::converged);
  // The fixed point: s*, f* = 0.1 sin s* / 0.8. The residual 1e-10 over 1 − μ_s (κ(s*) =
  // 6.5e-3) bounds the distance to it.
  EXPECT_NEAR(r.z(0), SlowManifoldMap::kLimit, 1e-10 / 6.5e-3);
  EXPECT_NEAR(r.z(1), 0.1 * std::sin(SlowManifoldMap::kLimit) / 0.8, 1e-9);
  // Secant-like: tens of periods where the plain iteration needs thousands.
  EXPECT_LE(r.maps, 40);
  EXPECT_EQ(r.maps, P.maps);
}

TEST(AndersonFixedPoint, RestartsFromTheFlowWhereAnExtrapolationLeavesTheDomain) {
  // The slow manifold with a wall just beyond its limit (s > s* + 1e-4 cannot be
  // evaluated, as a journal beyond the clearance): the flow approaches s* from below and
  // never gets there, the secant extrapolation overshoots it. Each overshoot restarts the
  // history from P(z_best), and the iteration still converges.
  SlowManifoldMap P;
  P.wall = SlowManifoldMap::kLimit + 1e-4;
  lub::steady::AndersonOptions o;
  o.residual_scales = {1.0, 1.0};
  o.tolerance = 1e-10;
  o.max_maps = 200;
  const auto r = lub::steady::anderson_fixed_point(P, Eigen::Vector2d(-1.0, 0.0), o);
  ASSERT_EQ(r.outcome, lub::steady::ShootingOutcome::converged) << r.maps << " maps, residual " << r.residual;
  EXPECT_NEAR(r.z(0), SlowManifoldMap::kLimit, 1e-10 / 6.5e-3);
  EXPECT_GT(P.failures, 0) << "no extrapolation crossed the wall: the restart was not exercised";
  // A start the map cannot evaluate ends at once, left_domain.
  const auto bad = lub::steady::anderson_fixed_point(P, Eigen::Vector2d(2.0, 0.0), o);
  EXPECT_EQ(bad.outcome, lub::steady::ShootingOutcome::left_domain);
  EXPECT_EQ(bad.maps, 1);
}

TEST(AndersonFixedPoint, StopsWhereTheMapIsOnlyNoise) {
  // A map whose fixed point is hidden under noise of 1e-6: the best residual stops
  // improving, and `stall` maps later the iteration ends, not_converged, near the point.
  class Noisy final : public lub::steady::CycleMap {
   public:
    int dim() const override { return 1; }
    int apply(const double* z, double* Pz) override {
      k = k * 1103515245u + 12345u;
      Pz[0] = 0.5 + 0.99 * (z[0] - 0.5) + 1e-6 * (static_cast<double>((k >> 16) & 0x7fff) / 32767.0 - 0.5);
      return 0;
    }
    unsigned k = 1;
  } P;
  lub::steady::AndersonOptions o;
  o.residual_scales = {1.0};
  o.tolerance = 1e-12;
  o.max_maps = 500;
  o.stall = 12;
  const auto r = lub::steady::anderson_fixed_point(P, Eigen::VectorXd::Constant(1, -3.0), o);
  EXPECT_EQ(r.outcome, lub::steady::ShootingOutcome::not_converged);
  EXPECT_LT(r.maps, 100);
  EXPECT_NEAR(r.z(0), 0.5, 1e-6 / 0.01);  // the noise over 1 − μ
}

}  // namespace

namespace {

TEST(Monodromy, AStepThroughTheWallIsTakenAgainSmaller) {
  // The affine map fails beyond |z|∞ = fp + 5e-3: the difference step 1e-2 from the fixed
  // point crosses that wall, 1e-3 does not. With retries the monodromy is A (differences of
  // an affine map are exact to round-off); without, the perturbed period's failure is
  // reported.
  AffineMap probe(0.998, 0.93, 1e-3);
  const Eigen::Vector3d fp = probe.fixed_point();
  AffineMap P(0.998, 0.93, 1e-3, fp.lpNorm<Eigen::Infinity>() + 5e-3);
  Eigen::VectorXd Pz(3);
  ASSERT_EQ(P.apply(fp.data(), Pz.data()), 0);
  lub::steady::MonodromyOptions mo{{1.0, 1.0, 1.0}, 1e-2, true, 2};
  const auto m = lub::steady::monodromy_by_differences(P, fp, Pz, mo);
  ASSERT_EQ(m.failed, 0);
  EXPECT_GT(P.failures, 0);
  const auto mu = lub::steady::floquet_multipliers(m.M);
  EXPECT_NEAR(std::abs(mu.front()), 0.998, 1e-9);
  mo.retries = 0;
  EXPECT_EQ(lub::steady::monodromy_by_differences(P, fp, Pz, mo).failed, 1);
}

}  // namespace

namespace {

// A curved slow manifold onto which one period projects: z = (a, b),
//   a' = a* + μ (a − a*),   b' = κ a'²,
// μ = 0.9999 (a multiplier close to 1) and 0 (the squeeze film's ~1e-10): every image
// lies on b = κ a², the fixed point is (a*, κ a*²). A Newton step from a point of the
// manifold 1e-2 from a* lands on a* but leaves the manifold by κ·(1e-2)²: its residual
// (1e-4) is 100 times the start's (μ − 1)·1e-2 ≈ 1e-6 (Frêne short near the wall, the
// error bars' re-solve: |μ| 0.99991, a step of 7e-3 c, residuals 1e-6 → 6e-6 c).
class CurvedManifoldMap final : public lub::steady::CycleMap {
 public:
  static constexpr double kA = 0.3, kMu = 0.9999, kKappa = 1.0;
  int dim() const override { return 2; }
  int apply(const double* z, double* Pz) override {
    ++maps;
    Pz[0] = kA + kMu * (z[0] - kA);
    Pz[1] = kKappa * Pz[0] * Pz[0];
    return 0;
  }
  static Eigen::Vector2d on_manifold(double a) { return {a, kKappa * a * a}; }
  /// ∂P/∂z at z.
  static Eigen::Matrix2d monodromy(const Eigen::Vector2d& z) {
    const double a1 = kA + kMu * (z(0) - kA);
    Eigen::Matrix2d M;
    M << kMu, 0.0, 2.0 * kKappa * a1 * kMu, 0.0;
    return M;
  }
  long long maps = 0;
};

TEST(NewtonPicard, ConvergesAlongACurvedSlowManifoldWhereALineSearchStalls) {
  const Eigen::Vector2d z0 = CurvedManifoldMap::on_manifold(CurvedManifoldMap::kA + 1e-2);
  const Eigen::MatrixXd J = CurvedManifoldMap::monodromy(z0) - Eigen::Matrix2d::Identity();
  const Eigen::Vector2d fixed = CurvedManifoldMap::on_manifold(CurvedManifoldMap::kA);

  // The error bars' re-solve as it was: KINSOL, chord steps on the start's Jacobian and
  // a line search, six iterations. Its steps are cut to a fraction of the way.
  CurvedManifoldMap kin_map;
  lub::steady::ShootingOptions so;
  so.scales = {1.0, 1.0};
  so.tolerance = 1e-11;
  so.step = 1e-4;
  so.max_iterations = 6;
  so.initial_jacobian = &J;
  so.noise_factor = 1.0;
  const auto kin = lub::steady::solve_periodic_orbit(kin_map, z0, so);
  EXPECT_NE(kin.outcome, lub::steady::ShootingOutcome::converged);
  EXPECT_GT((kin.z - fixed).lpNorm<Eigen::Infinity>(), 1e-4);

  // Newton–Picard: the period after the Newton point puts it back on the manifold; the
  // map is linear along it, so one iteration lands on the fixed point to round-off.
  CurvedManifoldMap np_map;
  lub::steady::NewtonPicardOptions no;
  no.residual_scales = {1.0, 1.0};
  no.tolerance = 1e-11;
  const auto np = lub::steady::newton_picard(np_map, z0, J, no);
  ASSERT_EQ(np.outcome, lub::steady::ShootingOutcome::converged) << np.message;
  EXPECT_FALSE(np.at_noise_floor);
  EXPECT_EQ(np.iterations, 1);
  EXPECT_EQ(np.maps, 3);  // the start's period, the Newton point's, the new iterate's
  EXPECT_LT((np.z - fixed).lpNorm<Eigen::Infinity>(), 1e-12);
}

// P(z) = 1 + μ (z − 1) on z <= 1 + 1e-2 (beyond it the period fails: the wall).
class WalledLineMap final : public lub::steady::CycleMap {
 public:
  static constexpr double kMu = 0.5;
  int dim() const override { return 1; }
  int apply(const double* z, double* Pz) override {
    ++maps;
    if (z[0] > 1.0 + 1e-2) {
      ++failures;
      return 1;
    }
    Pz[0] = 1.0 + kMu * (z[0] - 1.0);
    return 0;
  }
  long long maps = 0;
  int failures = 0;
};

TEST(NewtonPicard, ANewtonPointBeyondTheWallIsPulledBackAndAFailingStartReported) {
  // A chord Jacobian of half the slope doubles Newton's step: from 1 − 2e-2 its point
  // 1 + 2e-2 lies beyond the wall; halved, it is the fixed point.
  Eigen::MatrixXd J(1, 1);
  J(0, 0) = 0.5 * (WalledLineMap::kMu - 1.0);
  lub::steady::NewtonPicardOptions no;
  no.residual_scales = {1.0};
  no.tolerance = 1e-12;
  WalledLineMap P;
  const auto np = lub::steady::newton_picard(P, Eigen::VectorXd::Constant(1, 1.0 - 2e-2), J, no);
  ASSERT_EQ(np.outcome, lub::steady::ShootingOutcome::converged) << np.message;
  EXPECT_EQ(P.failures, 1);
  EXPECT_EQ(np.maps, 4);  // the start, the refused point, the halved one, the new iterate
  EXPECT_NEAR(np.z(0), 1.0, 1e-15);

  WalledLineMap Q;
  const auto bad = lub::steady::newton_picard(Q, Eigen::VectorXd::Constant(1, 1.1), J, no);
  EXPECT_EQ(bad.outcome, lub::steady::ShootingOutcome::left_domain);
  EXPECT_EQ(bad.maps, 1);
}

TEST(NewtonPicard, ARelativeToleranceStopsAtAFractionOfTheStartsResidual) {
  // A chord Jacobian 1.25 times too steep: each iteration (Newton point, then a period)
  // leaves a tenth of the distance to the fixed point, and of the residual. Asked for 2 %
  // of the start's residual it stops after two iterations (1 %), the orbit located to 1 %
  // of its distance from the start; the absolute tolerance alone would take twelve.
  Eigen::MatrixXd J(1, 1);
  J(0, 0) = 1.25 * (WalledLineMap::kMu - 1.0);
  lub::steady::NewtonPicardOptions no;
  no.residual_scales = {1.0};
  no.tolerance = 1e-14;
  no.max_iterations = 20;
  no.relative_tolerance = 2e-2;
  const double z0 = 1.0 - 5e-3;
  WalledLineMap P;
  const auto np = lub::steady::newton_picard(P, Eigen::VectorXd::Constant(1, z0), J, no);
  ASSERT_EQ(np.outcome, lub::steady::ShootingOutcome::converged) << np.message;
  EXPECT_FALSE(np.at_noise_floor);
  EXPECT_EQ(np.iterations, 2);
  EXPECT_EQ(np.maps, 5);
  EXPECT_NEAR(np.z(0), 1.0, 1.01e-2 * std::abs(z0 - 1.0));

  no.relative_tolerance = 0.0;
  WalledLineMap Q;
  const auto full = lub::steady::newton_picard(Q, Eigen::VectorXd::Constant(1, z0), J, no);
  ASSERT_EQ(full.outcome, lub::steady::ShootingOutcome::converged) << full.message;
  EXPECT_GE(full.iterations, 11);
  EXPECT_NEAR(full.z(0), 1.0, 1e-14);
}

}  // namespace
