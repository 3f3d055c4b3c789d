// The film's drift law near the wall (steady/drift_law.hpp): fitted to films that follow
// dh/dN = −a h^p exactly, with noise, and refused where the film does not fall.
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

#include "lub/steady/drift_law.hpp"

namespace {

using lub::steady::cycles_to_film;
using lub::steady::fit_drift_law;

/// h(N) under dh/dN = −a h^p from h0 at N = 0: h^(1−p) = h0^(1−p) + a (p − 1) N.
double film(double h0, double a, double p, double N) {
  if (std::abs(p - 1.0) < 1e-9) return h0 * std::exp(-a * N);  // p = 1: exponential
  return std::pow(std::pow(h0, 1.0 - p) + a * (p - 1.0) * N, 1.0 / (1.0 - p));
}

struct Samples {
  std::vector<double> cycles, films;
};

/// Films at 12 cycles spread like the slow flow's trail (growing steps), from h0 = 30 µm.
Samples power_law(double p, double noise, unsigned seed) {
  const double h0 = 30e-6, a = 1.1e-8 / std::pow(13e-6, p);  // 11 nm a cycle at 13 µm
  std::mt19937 rng(seed);
  std::normal_distribution<double> e(0.0, noise);
  Samples s;
  for (int k = 0; k < 12; ++k) {
    const double N = 20.0 * (std::pow(1.3, k) - 1.0);
    s.cycles.push_back(N);
    s.films.push_back(film(h0, a, p, N) * (1.0 + e(rng)));
  }
  return s;
}

TEST(DriftLaw, RecoversAnExactPowerLawAndItsCrossing) {
  for (const double p : {1.0 + 1e-12, 1.8, 2.6, 3.5}) {
    const Samples s = power_law(p, 0.0, 1);
    const auto law = fit_drift_law(s.cycles, s.films);
    ASSERT_TRUE(law.known) << law.why;
    // Each secant's slope is the law's drift at a film between its ends, the one the
    // fitted law puts there: exact data give p and the crossing to rounding.
    EXPECT_NEAR(law.exponent, p, 1e-8);
    // From the last film to 0.55 of it (within the law's reach): the exact ΔN.
    const double h_end = s.films.back(), target = 0.55 * h_end;
    const double a = 1.1e-8 / std::pow(13e-6, p);
    double exact = 0.0;
    if (std::abs(p - 1.0) < 1e-9) exact = std::log(h_end / target) / a;
    else exact = (std::pow(target, 1.0 - p) - std::pow(h_end, 1.0 - p)) / (a * (p - 1.0));
    const auto x = cycles_to_film(law, h_end, target, 0.0);
    EXPECT_NEAR(x.cycles, exact, 1e-8 * exact) << "p " << p;
    EXPECT_LT(x.error, 1e-6 * exact) << "p " << p;
  }
}

TEST(DriftLaw, ItsErrorBarCoversTheTruthUnderNoise) {
  // 0.3 % noise on each film (the jumps' wobble): the 2σ bar holds the exact crossing in
  // most draws (a 2σ bar: ~95 %; at least 85 % of 40 allows the estimate's own scatter).
  const double p = 2.6, a = 1.1e-8 / std::pow(13e-6, p);
  int covered = 0;
  for (unsigned seed = 1; seed <= 40; ++seed) {
    const Samples s = power_law(p, 3e-3, seed);
    const auto law = fit_drift_law(s.cycles, s.films);
    ASSERT_TRUE(law.known) << law.why;
    const double h_end = film(30e-6, a, p, s.cycles.back());  // the noiseless start
    const double target = 0.55 * h_end;
    const double exact = (std::pow(target, 1.0 - p) - std::pow(h_end, 1.0 - p)) / (a * (p - 1.0));
    const auto x = cycles_to_film(law, h_end, target, 0.0);
    if (std::abs(x.cycles - exact) <= x.error) ++covered;
  }
  EXPECT_GE(covered, 34);
}

TEST(DriftLaw, TheDriftsOwnErrorWidensTheBar) {
  const Samples s = power_law(2.6, 0.0, 1);
  const auto law = fit_drift_law(s.cycles, s.films);
  ASSERT_TRUE(law.known);
  const auto plain = cycles_to_film(law, s.films.back(), 0.55 * s.films.back(), 0.0);
  const auto wide = cycles_to_film(law, s.films.back(), 0.55 * s.films.back(), 0.1);
  // A 10 % error in the drift is a 10 % error in ΔN, twice over (the bar is 2σ).
  EXPECT_GT(wide.error, 0.19 * wide.cycles);
  EXPECT_GT(wide.error, plain.error);
}

TEST(DriftLaw, NoLawWhereTheFilmDoesNotFallOrHardlyChanges) {
  Samples s = power_law(2.6, 0.0, 1);
  std::swap(s.films[4], s.films[5]);  // rises once
  EXPECT_FALSE(fit_drift_law(s.cycles, s.films).known);
  const std::vector<double> N = {0, 10, 20, 30, 40, 50}, flat = {10e-6, 9.9e-6, 9.8e-6, 9.7e-6, 9.6e-6, 9.5e-6};
  const auto f = fit_drift_law(N, flat);
  EXPECT_FALSE(f.known);
  EXPECT_NE(f.why.find("15 %"), std::string::npos) << f.why;
  EXPECT_FALSE(fit_drift_law({0, 1, 2, 3}, {4e-6, 3e-6, 2e-6, 1e-6}).known);  // too few
  // Nothing to cross: a target at or above the film.
  const auto law = fit_drift_law(power_law(2.6, 0.0, 1).cycles, power_law(2.6, 0.0, 1).films);
  EXPECT_TRUE(std::isnan(cycles_to_film(law, 5e-6, 6e-6, 0.0).cycles));
  // Nor one beyond the law's reach: more than kDriftLawReach below its films.
  const auto far = cycles_to_film(law, law.film_low_m, 0.45 * law.film_low_m, 0.0);
  EXPECT_TRUE(far.beyond_reach);
  EXPECT_TRUE(std::isnan(far.cycles));
}

}  // namespace
