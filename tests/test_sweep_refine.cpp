// The refinement's selection rule (lub/sweep/refine.hpp) on hand-made points: where the new
// case goes on an edge, which edges score and why, and the order of those that do. The runs
// themselves (lubsweep refine on a study, MPI, resume) are tests/python/test_refine.py's.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "lub/run/run.hpp"
#include "lub/sweep/refine.hpp"

namespace {

using namespace lub::sweep;

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

/// The index of a steady metric by name.
std::size_t metric(const std::string& name) {
  const auto& m = lub::steady_metrics();
  for (std::size_t i = 0; i < m.size(); ++i)
    if (name == m[i].name) return i;
  ADD_FAILURE() << "no steady metric " << name;
  return 0;
}

/// A periodic case, above the safe film, with one parameter: every metric and slope NaN but
/// h_min = `h` with slope `slope` and error bars `error` (metric) and `slope_error`.
RefinePoint point(int id, double h, double slope, double error = 0.0, double slope_error = 0.0) {
  const std::size_t n = lub::steady_metrics().size();
  RefinePoint p;
  p.id = id;
  p.ok = true;
  p.classification = "periodic";
  p.below_safe_film = 0.0;
  p.metric.assign(n, kNaN);
  p.metric_error.assign(n, kNaN);
  p.slope.assign(n, kNaN);
  p.slope_error.assign(n, kNaN);
  const std::size_t k = metric("min_film_thickness_m");
  p.metric[k] = h, p.metric_error[k] = error, p.slope[k] = slope, p.slope_error[k] = slope_error;
  return p;
}

TEST(RefineMidpoint, GeometricOnAFactorSpacedAxisArithmeticOtherwise) {
  EXPECT_TRUE(geometric_axis({0.04, 0.1, 0.2, 0.4}));     // the paper's viscosities: ratios 2.5, 2, 2
  EXPECT_TRUE(geometric_axis({5e-5, 1e-4, 2e-4, 5e-4}));  // and clearances
  EXPECT_TRUE(geometric_axis({0.1, 0.4}));                // two positive values: a factor
  EXPECT_FALSE(geometric_axis({1.0, 2.0, 3.0, 4.0}));     // equal steps
  EXPECT_FALSE(geometric_axis({-1.0, 1.0}));              // not all positive
  EXPECT_DOUBLE_EQ(refine_midpoint(0.1, 0.4, true), 0.2);
  EXPECT_DOUBLE_EQ(refine_midpoint(0.1, 0.4, false), 0.25);
  EXPECT_DOUBLE_EQ(refine_midpoint(-1.0, 3.0, true), 1.0);  // a non-positive end: arithmetic
}

TEST(RefineScore, DifferentLabelsScoreBeforeAnyMetric) {
  RefinePoint a = point(0, 2e-6, 1e-5), b = point(1, 4e-6, 1e-5);
  a.below_safe_film = 1.0;
  const RefineEdge e{0, 1, 0, 0};
  const auto c = score_edge(e, a, b, 0.1, 0.2, 0, 0.05);
  ASSERT_TRUE(c);
  EXPECT_EQ(c->reason, RefineReason::below_safe_film);
  EXPECT_EQ(c->score, 1.0);
  b.classification = "drifting";
  const auto both = score_edge(e, a, b, 0.1, 0.2, -1, 0.05);  // labels need no sensitivities
  ASSERT_TRUE(both);
  EXPECT_EQ(both->reason, RefineReason::classification);
  EXPECT_EQ(both->score, 2.0);
  b.ok = false;  // a case that is not ok teaches nothing
  EXPECT_FALSE(score_edge(e, a, b, 0.1, 0.2, 0, 0.05));
}

TEST(RefineScore, AMetricScoresWhenItMissesTheTrapezoidByMoreThanItsAllowance) {
  const RefineEdge e{0, 1, 0, 0};
  // h = 10 + 20 λ over [0, 1] with slope 20 at both ends: the trapezoid is exact.
  EXPECT_FALSE(score_edge(e, point(0, 10.0, 20.0), point(1, 30.0, 20.0), 0.0, 1.0, 0, 0.05));
  // Slopes 10 and 10 predict +10; the change is +20: a miss of 10 against 5 % of 30 = 1.5.
  const auto c = score_edge(e, point(0, 10.0, 10.0), point(1, 30.0, 10.0), 0.0, 1.0, 0, 0.05);
  ASSERT_TRUE(c);
  EXPECT_EQ(c->reason, RefineReason::metric);
  EXPECT_EQ(c->metric, "min_film_thickness_m");
  EXPECT_NEAR(c->score, 10.0 / 1.5 - 1.0, 1e-12);  // allowance 0.05 · 30
  // Error bars widen the allowance: 4 + 4 on the metric, 2 + 2 on the slope over half of 1.
  EXPECT_FALSE(score_edge(e, point(0, 10.0, 10.0, 4.0, 2.0), point(1, 30.0, 10.0, 4.0, 2.0), 0.0, 1.0, 0, 0.05));
  // No sensitivities (parameter -1): the metric criterion is off.
  EXPECT_FALSE(score_edge(e, point(0, 10.0, 10.0), point(1, 30.0, 10.0), 0.0, 1.0, -1, 0.05));
}

TEST(RefineRank, LabelsFirstThenTheLargestScoreThenTheCaseIds) {
  std::vector<RefineCandidate> c = {{{4, 5, 0, 0}, RefineReason::metric, 3.0, "max_eps"},
                                    {{2, 3, 0, 0}, RefineReason::metric, 0.5, "max_eps"},
                                    {{6, 7, 0, 0}, RefineReason::below_safe_film, 1.0, ""},
                                    {{0, 1, 0, 0}, RefineReason::metric, 3.0, "max_eps"},
                                    {{8, 9, 0, 0}, RefineReason::classification, 2.0, ""}};
  rank_candidates(c);
  std::vector<int> order;
  for (const RefineCandidate& x : c) order.push_back(x.edge.a);
  EXPECT_EQ(order, (std::vector<int>{8, 6, 0, 4, 2}));
}

}  // namespace
