// The slow flow followed by projective steps (steady/slow_manifold.hpp) on cycle maps whose
// flow is known in closed form: a node, an algebraic approach to a wall, a wall reached at a
// known cycle, a flow below the map's noise, a budget.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "lub/steady/periodic_orbit.hpp"
#include "lub/steady/slow_manifold.hpp"

namespace {

using lub::steady::SlowManifoldOptions;
using lub::steady::SlowManifoldOutcome;

// z = (s, f): the slow coordinate s moves by `slow(s)` a period, the fast one is slaved to
// it on a curved manifold in one period, f' = 1e-3 f + 0.5 s² (multiplier 1e-3: the squeeze
// film's are ~1e-10; one of 0.1 leaves 1 % of a jump's error in the slope measured two
// periods after it, and the error control keeps the jumps short). The map
// fails for s below `wall` (a journal put through it).
class SlowMap final : public lub::steady::CycleMap {
 public:
  explicit SlowMap(std::function<double(double)> slow) : slow_(std::move(slow)) {}
  int dim() const override { return 2; }
  int apply(const double* z, double* Pz) override {
    ++maps;
    if (maps > refuse_after) return -1;
    if (z[0] < wall) return 1;
    Pz[0] = z[0] + slow_(z[0]);
    Pz[1] = 1e-3 * z[1] + 0.5 * z[0] * z[0];
    return 0;
  }
  long long maps = 0;
  long long refuse_after = 1LL << 60;
  double wall = -1e300;

 private:
  std::function<double(double)> slow_;
};

Eigen::Vector2d on_manifold(double s) { return {s, 0.5 * s * s / (1.0 - 1e-3)}; }

SlowManifoldOptions options() {
  SlowManifoldOptions o;
  o.scales = {1.0, 1.0};
  return o;
}

/// |value − exact| relative to the change `span` the flow has made.
double path_error(double value, double exact, double span) { return std::abs(value - exact) / span; }

// The node s' = s* + (1 − κ)(s − s*), κ = 1e-3, s* = 1: s(k) = s* − (s* − s0)(1 − κ)^k.
constexpr double kappa = 1e-3, target = 1.0;
SlowMap node() { return SlowMap([](double s) { return -kappa * (s - target); }); }

/// The node's flow from s = 0, handed over within 1e-3 of s*.
lub::steady::SlowManifoldResult follow_node(SlowMap& P) {
  SlowManifoldOptions o = options();
  o.hand_over = 1e-3;
  return lub::steady::follow_slow_manifold(P, Eigen::Vector2d(0.0, 0.0), o);
}

TEST(SlowManifold, FollowsANodeToItsOrbitInAHundredthOfThePeriods) {
  // The plain iteration needs ln(1e3)/κ ≈ 6900 periods to come within 1e-3 of s*.
  SlowMap P = node();
  const auto r = follow_node(P);
  ASSERT_EQ(r.outcome, SlowManifoldOutcome::near) << name_of(r.outcome);
  EXPECT_EQ(r.maps, P.maps);
  EXPECT_LE(r.maps, 120);
  // The estimated distance is the node's own: |g| / κ, and s is that close to s*.
  EXPECT_LE(r.distance, 1e-3);
  EXPECT_NEAR(r.z(0), target, 1.2e-3);
  // Every point of the trail on the exact flow at its cycle count, within the jumps'
  // tolerance: 1e-4 plus 5 % of each jump, summed over the way (a few % of the change).
  for (size_t i = 0; i < r.trail.size(); ++i) {
    const double exact = target - target * std::pow(1.0 - kappa, r.trail_cycles[i]);
    EXPECT_LT(path_error(r.trail[i](0), exact, target), 0.03) << "at cycle " << r.trail_cycles[i];
    // On the manifold: the fast coordinate slaved to the slow one.
    EXPECT_NEAR(r.trail[i](1), 0.5 * r.trail[i](0) * r.trail[i](0), 0.02);
  }
}

TEST(SlowManifold, FollowsAnAlgebraicSinkToItsHorizonAndSaysItStillMoves) {
  // s' = s − a s³: ds/dk ≈ −a s³, s(k) = s0 / sqrt(1 + 2 a s0² k), thinning for ever as a
  // squeeze film under a steady load (h ∝ k^(−1/2)); never within hand_over of a zero.
  constexpr double a = 1e-3, s0 = 0.5;
  SlowMap P([](double s) { return -a * s * s * s; });
  SlowManifoldOptions o = options();
  o.hand_over = 0.0;
  o.horizon_cycles = 1e5;
  o.max_maps = 400;
  const auto r = lub::steady::follow_slow_manifold(P, Eigen::Vector2d(s0, 0.0), o);
  ASSERT_EQ(r.outcome, SlowManifoldOutcome::horizon) << name_of(r.outcome);
  EXPECT_DOUBLE_EQ(r.cycles, 1e5);
  EXPECT_LE(r.maps, 200);  // the plain flow: 1e5 periods
  const double exact = s0 / std::sqrt(1.0 + 2.0 * a * s0 * s0 * r.cycles);
  EXPECT_LT(path_error(r.z(0), exact, s0 - exact), 0.03) << r.z(0) << " against " << exact;
  // Still moving: g is the flow's own slope there.
  EXPECT_NEAR(r.g(0), -a * std::pow(r.z(0), 3), 0.05 * a * std::pow(r.z(0), 3));
}

TEST(SlowManifold, HeldToItsJumpsShareAloneItsCycleCountIsTheFlowsOwn) {
  // The algebraic sink again, with no absolute jump tolerance (the map's noise only, as
  // the auto stage sets it): each jump's error at most 5 % of the jump, so the state
  // reached is where the flow is at the cycle counted, to a few %: k(s) = (s0²/s² − 1) /
  // (2 a s0²). With an absolute 1e-4 the jumps grow where g is small and the count falls
  // behind the state: here 3.8 % against 1.7 %; on the full factorial at rtol/10, where a
  // jump also excites modes that decay over tens of cycles, about 2 × (Frêne short, 40 cP).
  constexpr double a = 1e-3, s0 = 0.05;  // g ~ 1e-7 a cycle: an absolute 1e-4 is 1000 of it
  auto count_error = [&](double tolerance) {
    SlowMap P([](double s) { return -a * s * s * s; });
    SlowManifoldOptions o = options();
    o.hand_over = 0.0;
    o.jump_tolerance = tolerance;
    o.max_maps = 200;
    const auto r = lub::steady::follow_slow_manifold(P, Eigen::Vector2d(s0, 0.0), o);
    const double s = r.z(0);
    const double k = (s0 * s0 / (s * s) - 1.0) / (2.0 * a * s0 * s0);
    return std::abs(r.cycles - k) / k;
  };
  const double relative = count_error(1e-12), absolute = count_error(1e-4);
  std::printf("cycle count error: relative control %.4f, absolute 1e-4 %.4f\n", relative, absolute);
  EXPECT_LT(relative, 0.05);
  EXPECT_GT(absolute, relative);
}

TEST(SlowManifold, WhereTheFlowStopsNearANodeNewtonPicardFindsItInAFewPeriods) {
  // The node of the first test: the flow stops near s* = 1 (estimated within 1e-3); there
  // the monodromy once by central differences (2 n + 1 periods) and Newton–Picard's chord
  // steps, each followed by a period, reach the orbit on its curved manifold,
  // f* = 0.5 / (1 − 1e-3), to 1e-10: what the auto stage does where its flow stops.
  SlowMap P = node();
  const auto flow = follow_node(P);
  ASSERT_EQ(flow.outcome, SlowManifoldOutcome::near) << name_of(flow.outcome);
  const long long before = P.maps;
  Eigen::VectorXd Pz(2);
  ASSERT_EQ(P.apply(flow.z.data(), Pz.data()), 0);
  const lub::steady::Monodromy m =
      lub::steady::monodromy_by_differences(P, flow.z, Pz, lub::steady::MonodromyOptions{{1.0, 1.0}, 1e-3, true});
  ASSERT_FALSE(m.failed);
  lub::steady::NewtonPicardOptions np;
  np.residual_scales = {1.0, 1.0};
  np.tolerance = 1e-10;
  np.max_iterations = 10;
  const auto found = lub::steady::newton_picard(P, flow.z, m.M - Eigen::Matrix2d::Identity(), np);
  ASSERT_EQ(found.outcome, lub::steady::ShootingOutcome::converged) << found.message;
  EXPECT_NEAR(found.z(0), target, 1e-9);
  EXPECT_NEAR(found.z(1), 0.5 / (1.0 - 1e-3), 1e-9);
  EXPECT_LE(P.maps - before, 5 + 2 * 3);  // the period, the monodromy's 4, three iterations
}

TEST(SlowManifold, AWallOnTheWayEndsTheFlowWhereThePlainFlowWouldFail) {
  // s' = s − v until s < 0, where a period fails: the plain flow from s0 fails at its
  // period from below v, after about s0 / v = 1000 cycles. Jumps across the wall are cut.
  constexpr double v = 1e-4, s0 = 0.1;
  SlowMap P([](double) { return -v; });
  P.wall = 0.0;
  const auto r = lub::steady::follow_slow_manifold(P, Eigen::Vector2d(s0, 0.0), options());
  ASSERT_EQ(r.outcome, SlowManifoldOutcome::failed) << name_of(r.outcome);
  EXPECT_GE(r.rejected, 1);
  // The last state the flow reached: a period from it fails (s < 0 there, or one period on).
  EXPECT_GT(r.z(0), -v);
  EXPECT_LT(r.z(0), v);
  EXPECT_NEAR(r.cycles, s0 / v, 3.0);
  EXPECT_LE(r.maps, 80);
}

TEST(SlowManifold, StopsWhereTheFlowIsBelowItsStillThreshold) {
  // A flow of 1e-9 a period (below a map's noise) is still: no jump is taken.
  SlowMap P([](double) { return 1e-9; });
  SlowManifoldOptions o = options();
  o.still = 1e-8;
  // From the manifold (f = 0.5 s² / (1 − 1e-3) to the flow's 1e-9).
  const auto r = lub::steady::follow_slow_manifold(P, on_manifold(0.5), o);
  ASSERT_EQ(r.outcome, SlowManifoldOutcome::still) << name_of(r.outcome);
  EXPECT_LE(r.maps, 5);
  EXPECT_LE(r.cycles, 10.0);
}

TEST(SlowManifold, AMapThatRefusesEndsItAndTheBudgetOfPeriodsHolds) {
  SlowMap P([](double s) { return -1e-4 * s; });
  P.refuse_after = 7;
  const auto refused = lub::steady::follow_slow_manifold(P, on_manifold(0.5), options());
  EXPECT_EQ(refused.outcome, SlowManifoldOutcome::refused);
  EXPECT_EQ(refused.maps, 8);  // the eighth was asked for and refused

  SlowMap Q([](double s) { return -1e-4 * s; });
  SlowManifoldOptions o = options();
  o.max_maps = 9;
  o.hand_over = 0.0;
  const auto spent = lub::steady::follow_slow_manifold(Q, on_manifold(0.5), o);
  EXPECT_EQ(spent.outcome, SlowManifoldOutcome::budget);
  EXPECT_LE(spent.maps, 9);
  EXPECT_EQ(spent.maps, Q.maps);
  EXPECT_GT(spent.cycles, 9.0);  // the jumps went further than the periods spent
}

}  // namespace
