// append_series (core/src/run/series_recorder.hpp): a transient continued after shooting
// keeps the samples of its last outputs.last_cycles cycles across both segments, with the
// boundary both segments sampled stored once.
#include <gtest/gtest.h>

#include <vector>

#include "run/series_recorder.hpp"

namespace {

using lub::CycleMetrics;
using lub::Series;

// A series sampled every 0.25 s over [t0, t1] with one channel x = 10 t.
Series sampled(double t0, double t1) {
  Series s;
  s.names = {"t", "x"};
  s.units = {"s", "m"};
  s.data.resize(2);
  for (double t = t0; t <= t1 + 1e-12; t += 0.25) {
    s.data[0].push_back(t);
    s.data[1].push_back(10.0 * t);
  }
  return s;
}

// Cycles of 1 s ending at 1, 2, ..., n.
std::vector<CycleMetrics> cycles(int n) {
  std::vector<CycleMetrics> cs(static_cast<size_t>(n));
  for (int k = 0; k < n; ++k) {
    cs[static_cast<size_t>(k)].t_start_s = k;
    cs[static_cast<size_t>(k)].t_end_s = k + 1;
  }
  return cs;
}

TEST(AppendSeries, KeepsTheLastCyclesAcrossSegments) {
  // First segment: its last 2 cycles (2..4 s) kept; the continuation runs cycles 5..7.
  Series all = sampled(2.0, 4.0);
  const Series more = sampled(4.0, 7.0);
  lub::detail::append_series(all, more, cycles(7), 2);
  ASSERT_EQ(all.data[0].size(), all.data[1].size());
  // The last 2 cycles are [5, 7]: samples from 5 s (the boundary sample belongs to the cycle
  // it starts) to 7 s, every 0.25 s, none repeated.
  EXPECT_DOUBLE_EQ(all.data[0].front(), 5.0);
  EXPECT_DOUBLE_EQ(all.data[0].back(), 7.0);
  EXPECT_EQ(all.data[0].size(), 9u);
  for (size_t i = 1; i < all.data[0].size(); ++i) EXPECT_GT(all.data[0][i], all.data[0][i - 1]) << i;
  for (size_t i = 0; i < all.data[0].size(); ++i) EXPECT_DOUBLE_EQ(all.data[1][i], 10.0 * all.data[0][i]);
}

TEST(AppendSeries, TheSharedBoundaryIsStoredOnce) {
  Series all = sampled(0.0, 2.0);
  lub::detail::append_series(all, sampled(2.0, 3.0), cycles(3), 0);  // keep everything
  EXPECT_EQ(all.data[0].size(), 13u);  // 0..3 s every 0.25 s
  for (size_t i = 1; i < all.data[0].size(); ++i) EXPECT_GT(all.data[0][i], all.data[0][i - 1]) << i;
}

TEST(AppendSeries, FewerCyclesThanKeptKeepsEverything) {
  Series all = sampled(0.0, 1.0);
  lub::detail::append_series(all, sampled(1.0, 2.0), cycles(2), 5);
  EXPECT_DOUBLE_EQ(all.data[0].front(), 0.0);
  EXPECT_EQ(all.data[0].size(), 9u);
}

}  // namespace
