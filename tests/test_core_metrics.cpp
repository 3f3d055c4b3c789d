// Unit tests of the steady-cycle metrics (core/src/run/metrics.cpp, internal to the run
// stage): the peak of the cubic Hermite through two observations (hermite_interior_max)
// against closed forms, and the reduction of per-cycle extremes to a run's metrics
// (steady_cycle_metrics) on hand-built cycles.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <complex>
#include <tuple>
#include <vector>

#include "lub/run/orbit.hpp"
#include "lub/run/run_io.hpp"
#include "run/metrics.hpp"

namespace {

using lub::CycleMetrics;
using lub::Metrics;
using lub::detail::hermite_interior_max;
using lub::detail::InteriorMax;
using lub::detail::steady_cycle_metrics;

// --- hermite_interior_max ----------------------------------------------------------
// A cubic's Hermite interpolant from its own end values and slopes is the cubic itself,
// so the interior maximum of a cubic is returned exactly but for rounding: 1e-14 relative
// (a few operations on numbers of the size of the result).
constexpr double kRoundoff = 1e-14;

TEST(HermiteInteriorMax, FindsTheMaximumOfACubic) {
  // f(t) = 5 + 3u − u³, u = t − 10, on [10, 12]: f' = 3(1 − u²) > 0 at u = 0, −9 at u = 2;
  // maximum at u = 1 (t = 11), f = 7.
  const auto f = [](double t) { return 5.0 + 3.0 * (t - 10.0) - std::pow(t - 10.0, 3); };
  const auto df = [](double t) { return 3.0 - 3.0 * std::pow(t - 10.0, 2); };
  const InteriorMax m = hermite_interior_max(10.0, f(10.0), df(10.0), 12.0, f(12.0), df(12.0));
  EXPECT_NEAR(m.t, 11.0, kRoundoff * 11.0);
  EXPECT_NEAR(m.value, 7.0, kRoundoff * 7.0);
}

TEST(HermiteInteriorMax, FindsTheMaximumOfAParabola) {
  // f(t) = 1 − (t − 0.7)² on [0, 1]: the cubic coefficient of p' vanishes (the linear
  // branch); maximum 1 at t = 0.7.
  const InteriorMax m = hermite_interior_max(0.0, 0.51, 1.4, 1.0, 0.91, -0.6);
  EXPECT_NEAR(m.t, 0.7, kRoundoff * 0.7);
  EXPECT_NEAR(m.value, 1.0, kRoundoff);
}

TEST(HermiteInteriorMax, EccentricityPeakBetweenTwoObservations) {
  // ε(t) = 15/16 − 256 u² + 8192 u³, u = t − t_p: ε̇ goes from + to − across t_p (its other
  // zero, u = 2·256/(3·8192) ≈ 0.02, is far outside the step); peak 15/16 at t_p. A step of
  // 107 µs observed off-centre around the peak, as the observer sees it. Every number is
  // dyadic, so the ends' ε and ε̇ are exact: a rounded ε moves the fitted peak by
  // δε/(|ε''| h) (~3e-15 s here), far more than the function's own rounding.
  const double tp = 0x1p-6;  // 15.625 ms
  const auto eps = [&](double t) { return 0.9375 - 256.0 * std::pow(t - tp, 2) + 8192.0 * std::pow(t - tp, 3); };
  const auto eps_dot = [&](double t) { return -512.0 * (t - tp) + 3.0 * 8192.0 * std::pow(t - tp, 2); };
  const double t0 = tp - 0x1p-15, t1 = tp + 0x5p-16;
  ASSERT_GT(eps_dot(t0), 0.0);
  ASSERT_LT(eps_dot(t1), 0.0);
  const InteriorMax m = hermite_interior_max(t0, eps(t0), eps_dot(t0), t1, eps(t1), eps_dot(t1));
  EXPECT_NEAR(m.t, tp, kRoundoff * tp);
  EXPECT_NEAR(m.value, 0.9375, kRoundoff * 0.9375);
  // The step ends alone would miss the peak by 256 u²: 2.4e-7 and 1.5e-6.
  EXPECT_GT(m.value - std::max(eps(t0), eps(t1)), 2e-7);
}

// --- steady_cycle_metrics ----------------------------------------------------------

/// A scene whose metric joint is `metric_joint` of two: a revolute (0) and a lubricated
/// revolute (1) with R_B = 10 mm; metrics over the last `metric_cycles` cycles.
lub::Scene metric_scene(int metric_joint, int metric_cycles) {
  lub::Scene scene;
  scene.joints.resize(2);
  scene.joints[0].type = lub::JointType::revolute;
  scene.joints[1].type = lub::JointType::lubricated_revolute;
  scene.joints[1].bearing.bearing_radius_m = 0.010;
  scene.metrics.joint = metric_joint;
  scene.simulation.metric_cycles = metric_cycles;
  return scene;
}

CycleMetrics cycle(double min_film_thickness_m, double angle_min_film, double max_eps, double peak_reaction_N,
                   double angle_peak_reaction, double peak_acceleration, double periodicity) {
  CycleMetrics c;
  std::tie(c.min_film_thickness_m, c.crank_angle_at_min_film_rad, c.max_eps, c.peak_reaction_N, c.crank_angle_at_peak_reaction_rad,
           c.peak_acceleration_m_s2, c.periodicity) =
      std::tie(min_film_thickness_m, angle_min_film, max_eps, peak_reaction_N, angle_peak_reaction, peak_acceleration,
               periodicity);
  return c;
}

/// Four cycles; the first holds the most extreme values of all, so a reduction over the
/// last two or three must not see it. Among the last two, each extreme sits in a different
/// cycle (film and acceleration in the third, ε, reaction and periodicity in the fourth).
std::vector<CycleMetrics> four_cycles() {
  return {cycle(1e-6, 0.1, 0.998, 9e4, 0.2, 9e5, -1.0),
          cycle(4e-5, 0.3, 0.90, 2e3, 0.4, 2e3, 0.5),
          cycle(2e-5, 1.5, 0.93, 3e3, 2.5, 5e3, 1e-3),
          cycle(3e-5, 4.5, 0.95, 4e3, 5.5, 4e3, 2e-3)};
}

TEST(SteadyCycleMetrics, ExtremesOverTheLastMetricCyclesWithTheirAngles) {
  const Metrics m = steady_cycle_metrics(metric_scene(1, 2), four_cycles(), 7);
  EXPECT_EQ(m.cycles_run, 7);
  EXPECT_EQ(m.min_film_thickness_m, 2e-5);  // the third cycle's
  EXPECT_EQ(m.crank_angle_at_min_film_rad, 1.5);  // ... and its angle
  EXPECT_EQ(m.max_eps, 0.95);               // the fourth's
  EXPECT_EQ(m.peak_reaction_N, 4e3);
  EXPECT_EQ(m.crank_angle_at_peak_reaction_rad, 5.5);
  EXPECT_EQ(m.peak_acceleration_m_s2, 5e3);  // the third's
  EXPECT_EQ(m.periodicity, 2e-3);
}

TEST(SteadyCycleMetrics, MoreMetricCyclesReachFurtherBack) {
  const Metrics three = steady_cycle_metrics(metric_scene(1, 3), four_cycles(), 4);
  EXPECT_EQ(three.min_film_thickness_m, 2e-5);
  EXPECT_EQ(three.peak_acceleration_m_s2, 5e3);
  EXPECT_EQ(three.periodicity, 0.5);  // the second cycle's
  // More metric cycles than cycles: all of them, the first included.
  const Metrics all = steady_cycle_metrics(metric_scene(1, 10), four_cycles(), 4);
  EXPECT_EQ(all.min_film_thickness_m, 1e-6);
  EXPECT_EQ(all.crank_angle_at_min_film_rad, 0.1);
  EXPECT_EQ(all.max_eps, 0.998);
  EXPECT_EQ(all.peak_reaction_N, 9e4);
  EXPECT_EQ(all.crank_angle_at_peak_reaction_rad, 0.2);
  EXPECT_EQ(all.peak_acceleration_m_s2, 9e5);
  EXPECT_EQ(all.periodicity, 0.5);
}

TEST(SteadyCycleMetrics, ATieKeepsTheLatestCyclesAngle) {
  // Equal minima (and equal peaks): the angle is the last cycle's, the first one met.
  std::vector<CycleMetrics> cycles = {cycle(2e-5, 1.0, 0.9, 3e3, 2.0, 1.0, 0.0),
                                      cycle(2e-5, 3.0, 0.9, 3e3, 4.0, 1.0, 0.0)};
  const Metrics m = steady_cycle_metrics(metric_scene(1, 2), cycles, 2);
  EXPECT_EQ(m.crank_angle_at_min_film_rad, 3.0);
  EXPECT_EQ(m.crank_angle_at_peak_reaction_rad, 4.0);
}

TEST(SteadyCycleMetrics, SafeFilmIsPerBearingDiameter) {
  // 0.00015 mm per mm of a 20 mm bearing: 3 µm. A 2 µm film is below it, a 4 µm one is not.
  const double safe = 0.00015 * 2.0 * 0.010;
  const Metrics thin = steady_cycle_metrics(metric_scene(1, 2), {cycle(2e-6, 0, 0.99, 0, 0, 0, 0)}, 1);
  EXPECT_TRUE(thin.has_film);
  EXPECT_NEAR(thin.safe_film_thickness_m, safe, 1e-15 * safe);
  EXPECT_TRUE(thin.below_safe_film);
  const Metrics thick = steady_cycle_metrics(metric_scene(1, 2), {cycle(4e-6, 0, 0.99, 0, 0, 0, 0)}, 1);
  EXPECT_FALSE(thick.below_safe_film);
}

TEST(SteadyCycleMetrics, NoFilmWithoutALubricatedMetricJoint) {
  // An ideal metric joint, or none: no film metrics (0), no safe film, never below it.
  for (const int joint : {0, -1}) {
    SCOPED_TRACE(joint);
    const Metrics m = steady_cycle_metrics(metric_scene(joint, 2), four_cycles(), 4);
    EXPECT_FALSE(m.has_film);
    EXPECT_EQ(m.min_film_thickness_m, 0.0);
    EXPECT_EQ(m.safe_film_thickness_m, 0.0);
    EXPECT_FALSE(m.below_safe_film);
    EXPECT_EQ(m.peak_reaction_N, 4e3);  // the other extremes are still reduced
  }
  // No cycle at all: no minimum either (0, not +inf).
  const Metrics none = steady_cycle_metrics(metric_scene(1, 2), {}, 0);
  EXPECT_EQ(none.min_film_thickness_m, 0.0);
  EXPECT_EQ(none.periodicity, -1.0);
}

// below_safe_film as a result (run_io.cpp): a stable orbit's film decides (the journal
// leaves an unstable one: unknown); a collapsed film is
// below; a drifting film is below once its drift law crosses the safe film or when it is
// already below and falling; anything else (a transient's last film) is unknown, NaN.
TEST(SteadyCycleMetrics, BelowSafeFilmIsAResultOrUnknown) {
  const auto& fields = lub::metric_fields();
  const auto field = std::find_if(fields.begin(), fields.end(), [](const auto& f) { return f.name == "below_safe_film"; });
  ASSERT_NE(field, fields.end());
  const auto below = [&](lub::SteadyClass kind, bool under, double drift, double crossing,
                         lub::RunStatus status = lub::RunStatus::ok) {
    lub::RunResult r;
    r.status = status;
    r.steady.kind = kind;
    r.metrics.below_safe_film = under;
    r.steady.min_film_drift_m_per_cycle = drift;
    r.steady.safe_film_cycle = crossing;
    return field->get(r);
  };
  const double nan = std::nan("");
  using K = lub::SteadyClass;
  EXPECT_EQ(below(K::periodic, true, nan, nan), 1.0);
  EXPECT_TRUE(std::isnan(below(K::periodic_unstable, false, -1e-9, nan)));  // the journal leaves it
  EXPECT_TRUE(std::isnan(below(K::periodic_unstable, true, -1e-9, nan)));
  EXPECT_EQ(below(K::drifting, false, -1e-9, 471.0), 1.0);   // its law crosses the safe film
  EXPECT_EQ(below(K::drifting, true, -1e-9, nan), 1.0);      // already below, and falling
  EXPECT_TRUE(std::isnan(below(K::drifting, false, -1e-9, nan)));  // above, law beyond reach
  EXPECT_TRUE(std::isnan(below(K::drifting, true, 3e-9, nan)));    // below, but rising
  EXPECT_TRUE(std::isnan(below(K::not_converged, true, -1e-9, nan)));
  EXPECT_EQ(below(K::not_converged, false, nan, nan, lub::RunStatus::film_collapse), 1.0);
  EXPECT_TRUE(std::isnan(below(K::periodic, false, nan, nan, lub::RunStatus::solver_failure)));
}

// How well posed an orbit is, from its multipliers (lub/run/orbit.hpp), against values
// worked by hand. A real slow multiplier 0.9999 with the squeeze film's near 0: κ = 1e4 and
// an e-folding time of 1/(−ln 0.9999) = 9999.5 cycles. A complex pair just outside the unit
// circle at 0.94 rad grows as slowly (1/ln 1.0001 = 10000.5 cycles) but its place is well
// posed: |1 − μ| = sqrt(1 − 2 r cos θ + r²) = 0.906, κ = 1.10 (1 − |μ| would say 1e4).
TEST(OrbitConditioning, IsSetByTheMultiplierNearestOneNotTheLargest) {
  const std::vector<std::complex<double>> real{{0.9999, 0.0}, {0.5, 0.0}, {1e-9, 0.0}};
  EXPECT_NEAR(lub::orbit_conditioning(real), 1e4, 1e4 * 1e-9);
  EXPECT_NEAR(lub::slowest_mode_cycles(real), 1.0 / -std::log(0.9999), 1e-6);
  const double r = 1.0001, a = 0.94;
  const std::vector<std::complex<double>> pair{std::polar(r, a), std::polar(r, -a), {1e-9, 0.0}};
  EXPECT_NEAR(lub::orbit_conditioning(pair), 1.0 / std::sqrt(1.0 - 2.0 * r * std::cos(a) + r * r), 1e-12);
  EXPECT_LT(lub::orbit_conditioning(pair), 1.2);
  EXPECT_NEAR(lub::slowest_mode_cycles(pair), 1.0 / std::log(r), 1e-6);
  EXPECT_TRUE(std::isnan(lub::orbit_conditioning({})));
  EXPECT_TRUE(std::isnan(lub::slowest_mode_cycles({})));
}

}  // namespace
