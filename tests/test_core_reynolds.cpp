// Tests of the finite-length bearing (core/src/bearing/reynolds.cpp, law `finite_reynolds`):
//  - its limits L/D → ∞ and L/D → 0 against the long and short closed forms (full film,
//    Gümbel and Reynolds cavitation), with the expected rate of approach;
//  - second-order convergence under grid refinement, for each cavitation condition;
//  - Raimondi & Boyd's design table for the full journal bearing (L/D = 1, 1/2, 1/4);
//  - determinism: the result does not depend on the warm start.
// Each tolerance carries its reason.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

#include "fixtures/film_quadrature.hpp"
#include "lub/bearing/film_force.hpp"
#include "lub/bearing/reynolds.hpp"
#include "fixtures/bearing_fixture.hpp"

namespace {

using bearing_fixture::kMu;
using bearing_fixture::state;

using filmquad::kPi;
using lub::BearingGeometry;
using lub::BearingState;
using lub::Cavitation;
using lub::FilmForce;
using lub::FiniteBearingOptions;
using lub::FiniteBearingSolver;
using lub::ForceLaw;

// A bearing of journal radius 10 mm, clearance 0.5 mm and L/D = ld.
BearingGeometry geometry(double ld) {
  BearingGeometry g;
  g.journal_radius_m = 0.010;
  g.bearing_radius_m = 0.0105;
  g.length_m = ld * 2.0 * g.journal_radius_m;
  return g;
}

FilmForce finite(const BearingGeometry& g, const BearingState& s, Cavitation cav, int n_theta, int n_z,
                 bool groove = false) {
  FiniteBearingOptions o;
  o.cavitation = cav;
  o.n_theta = n_theta;
  o.n_z = n_z;
  o.groove_at_max_film = groove;
  FiniteBearingSolver solver(o);
  return solver.solve(g, kMu, s);
}

double rel_dev(const FilmForce& a, const FilmForce& b) {
  return std::hypot(a.radial_N - b.radial_N, a.tangential_N - b.tangential_N) /
         std::hypot(b.radial_N, b.tangential_N);
}

const BearingState kStates[] = {state(0.3, 0.0, 300.0), state(0.7, 2.0, 300.0), state(0.7, -2.0, 300.0),
                                state(0.5, 10.0, 0.0), state(0.9, -5.0, -200.0)};

// --- Short limit: L/D → 0 ---------------------------------------------------------------

TEST(FiniteBearing, ShortLimitIsOcvirkForEveryCavitationCondition) {
  // As λ = L/D → 0 the circumferential flow term is O(λ²) against the axial one, so the
  // finite solution approaches Eq. (3) (full film: frene_short) and, with either cavitation
  // condition, its positive part (gumbel_short: the LCP decouples column by column). The
  // deviation must fall like λ² (ratio 4 per halving; accepted 3.0–4.8: at ε = 0.9 the thin
  // film needs λ/(1 − ε) small before the asymptotic rate shows) and be below 1 % at
  // λ = 0.025. Grid 512 × 8: its own error (second order; the axial parabola is exact) is far
  // below the deviations measured.
  for (const BearingState& s : kStates) {
    for (Cavitation cav : {Cavitation::sommerfeld, Cavitation::gumbel, Cavitation::reynolds}) {
      const ForceLaw ref = cav == Cavitation::sommerfeld ? ForceLaw::frene_short : ForceLaw::gumbel_short;
      double dev_prev = 0.0;
      for (double ld : {0.1, 0.05, 0.025}) {
        const auto g = geometry(ld);
        const double dev = rel_dev(finite(g, s, cav, 512, 8), lub::film_force(ref, g, kMu, s));
        if (dev_prev > 0.0) {
          EXPECT_GT(dev_prev / dev, 3.0) << name_of(cav) << " eps=" << s.eps << " ld=" << ld;
          EXPECT_LT(dev_prev / dev, 4.8) << name_of(cav) << " eps=" << s.eps << " ld=" << ld;
        }
        dev_prev = dev;
      }
      EXPECT_LT(dev_prev, 0.01) << name_of(cav) << " eps=" << s.eps;
    }
  }
}

// --- Long limit: L/D → ∞ ---------------------------------------------------------------

// Eq. (5) (ε > 0) plus a constant K (its gauge).
double p_long(const BearingState& s, double th, double K) {
  const double e = s.eps;
  const double ec = 1.0 + e * std::cos(th);
  return s.wedge * (2.0 + e * std::cos(th)) * e * std::sin(th) / ((2.0 + e * e) * ec * ec) +
         s.eps_dot / e * (1.0 / (ec * ec) - 1.0 / ((1.0 + e) * (1.0 + e))) + K;
}

TEST(FiniteBearing, LongLimitIsSommerfeldAndTheHalfFilmGaugeIsTheCubedFilmMean) {
  // As λ → ∞ the axial flow is confined to end layers of width O(R): deviations fall like 1/λ.
  //  - full film → frene_long (the gauge does not matter over the full circle);
  //  - Gümbel: the mid-length pressure tends to the Sommerfeld field shifted so that its
  //    H³-weighted circumferential mean is zero (the only constant the end layers pass), whose
  //    positive part is computed here by quadrature. For pure wedge that is Eq. (5) itself
  //    (odd in θ), i.e. gumbel_long; with squeeze it is not: the constant moves the rupture.
  // Checked at λ = 10, 20, 40 with Δz̄ = 1/4: deviation ratio per doubling in 1.6–2.6 and
  // below 4 % at λ = 40.
  for (const BearingState& s : kStates) {
    // Gauge constant K0 = −∫H³P dθ/∫H³ dθ of the Sommerfeld field, by the trapezoidal rule
    // (periodic analytic integrand: converged to rounding at 4096 nodes).
    double num = 0.0, den = 0.0;
    for (int i = 0; i < 4096; ++i) {
      const double th = 2.0 * kPi * i / 4096.0;
      const double h3 = std::pow(1.0 + s.eps * std::cos(th), 3);
      num += h3 * p_long(s, th, 0.0);
      den += h3;
    }
    const double K0 = -num / den;
    for (Cavitation cav : {Cavitation::sommerfeld, Cavitation::gumbel}) {
      double dev_prev = 0.0;
      for (double ld : {10.0, 20.0, 40.0}) {
        const auto g = geometry(ld);
        const int n_z = static_cast<int>(4.0 * ld);
        const FilmForce f = finite(g, s, cav, 64, n_z);
        FilmForce ref;
        if (cav == Cavitation::sommerfeld) {
          ref = lub::film_force(ForceLaw::frene_long, g, kMu, s);
        } else {
          const double c = g.clearance_m(), R = g.journal_radius_m;
          const auto q = filmquad::positive_part_force(
              [&](double th) { return 6.0 * kMu * (R / c) * (R / c) * p_long(s, th, K0) * g.length_m; }, R);
          ref = FilmForce{q.r, q.t};
        }
        const double dev = rel_dev(f, ref);
        if (dev_prev > 0.0) {
          EXPECT_GT(dev_prev / dev, 1.6) << name_of(cav) << " eps=" << s.eps << " ed=" << s.eps_dot;
          EXPECT_LT(dev_prev / dev, 2.6) << name_of(cav) << " eps=" << s.eps << " ed=" << s.eps_dot;
        }
        dev_prev = dev;
      }
      EXPECT_LT(dev_prev, 0.04) << name_of(cav) << " eps=" << s.eps << " ed=" << s.eps_dot;
    }
    if (s.eps_dot == 0.0) {
      // Pure wedge: the re-gauging is zero and the long limit is gumbel_long itself.
      EXPECT_NEAR(K0, 0.0, 1e-14);
      const auto g = geometry(40.0);
      EXPECT_LT(rel_dev(finite(g, s, Cavitation::gumbel, 64, 160), lub::film_force(ForceLaw::gumbel_long, g, kMu, s)),
                0.04);
    } else {
      EXPECT_GT(std::fabs(K0), 1e-3);  // with squeeze the Eq. (5) gauge is not the long limit's
    }
  }
}

// --- Grid convergence -------------------------------------------------------------------

TEST(FiniteBearing, ConvergesAtSecondOrderUnderRefinement) {
  // The paper's bearing (L/D = 40/19), n_theta = 32, 64, 128, 256 with n_z = n_theta/8. Observed
  // order log2(|F_N − F_2N| / |F_2N − F_4N|) from the last three grids: second order expected
  // (exact cell integrals, vertex-centred axial nodes). Accepted 1.6–2.6 (the cavitation
  // boundary cutting cells adds a small non-smooth part).
  BearingGeometry g;
  g.journal_radius_m = 0.0095;
  g.bearing_radius_m = 0.0100;
  g.length_m = 0.040;
  for (const BearingState& s : {state(0.7, 3.0, 500.0), state(0.9, -20.0, 300.0)}) {
    for (Cavitation cav : {Cavitation::sommerfeld, Cavitation::gumbel, Cavitation::reynolds}) {
      std::vector<FilmForce> f;
      for (int n : {32, 64, 128, 256}) f.push_back(finite(g, s, cav, n, n / 8));
      const auto d = [&](int a, int b) {
        return std::hypot(f[a].radial_N - f[b].radial_N, f[a].tangential_N - f[b].tangential_N);
      };
      const double order = std::log2(d(1, 2) / d(2, 3));
      const double err64 = d(1, 3) / std::hypot(f[3].radial_N, f[3].tangential_N);
      std::printf("[ measured ] finite_reynolds %-10s eps=%.1f: order %.2f, |F(64x8) - F(256x32)|/|F| = %.2e\n",
                  std::string(name_of(cav)).c_str(), s.eps, order, err64);
      EXPECT_GT(order, 1.6) << name_of(cav) << " eps=" << s.eps;
      EXPECT_LT(order, 2.6) << name_of(cav) << " eps=" << s.eps;
    }
  }
}

// --- Raimondi & Boyd ------------------------------------------------------------------------

// A. A. Raimondi and J. Boyd, "A solution for the finite journal bearing and its application
// to analysis and design: III", ASLE Transactions 1(1), 194–209 (1958), Table 1 (full 360°
// journal bearing, Swift–Stieber film rupture, lubricant supplied at ambient pressure at the
// position of maximum film thickness), as reproduced in Shigley's Mechanical Engineering
// Design, Table 12-4 "Dimensionless performance parameters for full journal bearings with side
// flow". Columns: ε, Sommerfeld number S = (R/c)² μN/P, attitude angle φ [deg].
struct RBRow {
  double eps, S, phi_deg;
};
const RBRow kRB1[] = {{0.1, 1.33, 79.5},   {0.2, 0.631, 74.02},  {0.4, 0.264, 63.10},  {0.6, 0.121, 50.58},
                      {0.8, 0.0446, 36.24}, {0.9, 0.0188, 26.45}, {0.97, 0.00474, 15.47}};
const RBRow kRB12[] = {{0.1, 4.31, 81.62},   {0.2, 2.03, 74.94},   {0.4, 0.779, 61.45}, {0.6, 0.319, 48.14},
                       {0.8, 0.0923, 33.31}, {0.9, 0.0313, 23.66}, {0.97, 0.00609, 13.75}};
const RBRow kRB14[] = {{0.1, 16.2, 82.31},  {0.2, 7.57, 75.18},   {0.4, 2.83, 60.86}, {0.6, 1.07, 46.72},
                       {0.8, 0.261, 31.04}, {0.9, 0.0736, 21.85}, {0.97, 0.0101, 12.22}};

TEST(FiniteBearing, MatchesRaimondiBoydFullBearingTable) {
  // Steady load, journal at speed N (w = ω = 2πN), Reynolds cavitation and R&B's supply
  // condition (groove_at_max_film). S from the film force at the tabulated ε, φ = atan2(F_t, −F_r).
  // The table gives 3 significant figures and comes from a 1958 relaxation solution: S within
  // 3.5 %, φ within 0.6° (our grid, 96 × 12, is converged to ~0.3 % in S).
  const struct {
    double ld;
    const RBRow* rows;
  } tables[] = {{1.0, kRB1}, {0.5, kRB12}, {0.25, kRB14}};
  double worst_s = 0.0, worst_phi = 0.0;
  std::printf("[ measured ] Raimondi-Boyd Table 1 (L/D, eps: S ours/table, phi ours/table deg):\n");
  for (const auto& t : tables) {
    const auto g = geometry(t.ld);
    const double n_rev = 25.0;
    const double w = 2.0 * kPi * n_rev;
    for (int k = 0; k < 7; ++k) {
      const RBRow& row = t.rows[k];
      const FilmForce f = finite(g, state(row.eps, 0.0, w), Cavitation::reynolds, 96, 12, true);
      const double W = std::hypot(f.radial_N, f.tangential_N);
      const double P = W / (2.0 * g.journal_radius_m * g.length_m);
      const double rc = g.journal_radius_m / g.clearance_m();
      const double S = rc * rc * kMu * n_rev / P;
      const double phi = std::atan2(f.tangential_N, -f.radial_N) * 180.0 / kPi;
      std::printf("    L/D=%-4g eps=%-4g S %.4g / %.4g  phi %.2f / %.2f\n", t.ld, row.eps, S, row.S, phi,
                  row.phi_deg);
      worst_s = std::max(worst_s, std::fabs(S / row.S - 1.0));
      worst_phi = std::max(worst_phi, std::fabs(phi - row.phi_deg));
      EXPECT_NEAR(S / row.S, 1.0, 0.035) << "L/D=" << t.ld << " eps=" << row.eps;
      EXPECT_NEAR(phi, row.phi_deg, 0.6) << "L/D=" << t.ld << " eps=" << row.eps;
    }
  }
  std::printf("[ measured ] Raimondi-Boyd: max |S/S_table - 1| = %.3f, max |phi - phi_table| = %.2f deg\n",
              worst_s, worst_phi);
}

// The same table's friction and flow columns: friction variable (R/c) f, f = T_J/(R W); flow
// variable Q/(R c N L); side-flow ratio Q_s/Q; load over peak pressure P/p_max, P = W/(L D).
struct RBOutputRow {
  double eps, friction, flow, side_ratio, p_ratio;
};
const RBOutputRow kRBOut1[] = {{0.1, 26.4, 3.37, 0.150, 0.540}, {0.2, 12.8, 3.59, 0.280, 0.529},
                               {0.4, 5.79, 3.99, 0.497, 0.484},  {0.6, 3.22, 4.33, 0.680, 0.415},
                               {0.8, 1.70, 4.62, 0.842, 0.313},  {0.9, 1.05, 4.74, 0.919, 0.247},
                               {0.97, 0.514, 4.82, 0.973, 0.152}};
const RBOutputRow kRBOut12[] = {{0.1, 85.6, 3.43, 0.173, 0.523}, {0.2, 40.9, 3.72, 0.318, 0.506},
                                {0.4, 17.0, 4.29, 0.552, 0.441},  {0.6, 8.10, 4.85, 0.730, 0.365},
                                {0.8, 3.26, 5.41, 0.874, 0.267},  {0.9, 1.60, 5.69, 0.939, 0.206},
                                {0.97, 0.610, 5.88, 0.980, 0.126}};
const RBOutputRow kRBOut14[] = {{0.1, 322.0, 3.45, 0.180, 0.515}, {0.2, 153.0, 3.76, 0.330, 0.489},
                                {0.4, 61.1, 4.37, 0.567, 0.415},   {0.6, 26.7, 4.99, 0.746, 0.334},
                                {0.8, 8.80, 5.60, 0.884, 0.240},   {0.9, 3.50, 5.91, 0.945, 0.180},
                                {0.97, 0.922, 6.12, 0.984, 0.108}};

TEST(FiniteBearing, FrictionFlowAndPeakPressureAgainstRaimondiBoyd) {
  // The library's outputs at the tabulated ε (load from the film force, friction from
  // film_friction_torques, flows and peak from the pressure field), grid 192 × 24, against the
  // table's 3 significant figures, within the 3.5 % the S column is held to. Two exceptions,
  // each with its measurement: the inflow converges at first order beside the groove (1.3–1.7 %
  // low here; 3.326 / 3.350 on 192 / 384 cells at L/D = 1, ε = 0.1, Richardson 3.37); at ε = 0.97
  // the table's peak pressure is the under-resolved one (ours is 0.1335 on 96 to 768 cells at
  // L/D = 1/2, table 0.126), so P/p_max there within 7 %.
  const struct {
    double ld;
    const RBOutputRow* rows;
  } tables[] = {{1.0, kRBOut1}, {0.5, kRBOut12}, {0.25, kRBOut14}};
  double worst[4] = {0, 0, 0, 0};
  std::printf("[ measured ] Raimondi-Boyd (L/D, eps: (R/c)f, Q/(RcNL), Qs/Q, P/pmax ours / table):\n");
  for (const auto& t : tables) {
    const auto g = geometry(t.ld);
    const double n_rev = 25.0, w = 2.0 * kPi * n_rev;
    const double R = g.journal_radius_m, c = g.clearance_m(), L = g.length_m;
    for (int k = 0; k < 7; ++k) {
      const RBOutputRow& row = t.rows[k];
      FiniteBearingOptions o;
      o.cavitation = Cavitation::reynolds;
      o.n_theta = 192;
      o.n_z = 24;
      o.groove_at_max_film = true;
      FiniteBearingSolver solver(o);
      const FilmForce f = solver.solve(g, kMu, state(row.eps, 0.0, w));
      const lub::FilmOutputs out = solver.outputs(w);
      const double W = std::hypot(f.radial_N, f.tangential_N);
      const double ours[4] = {(R / c) * out.journal_friction_torque_Nm / (R * W),
                              out.inflow_m3_s / (R * c * n_rev * L), out.side_flow_m3_s / out.inflow_m3_s,
                              W / (L * 2.0 * R) / out.peak_pressure_Pa};
      const double table[4] = {row.friction, row.flow, row.side_ratio, row.p_ratio};
      std::printf("    L/D=%-4g eps=%-4g f %.4g / %.4g  Q %.4g / %.4g  Qs/Q %.4g / %.4g  P/pmax %.4g / %.4g\n", t.ld,
                  row.eps, ours[0], table[0], ours[1], table[1], ours[2], table[2], ours[3], table[3]);
      for (int q = 0; q < 4; ++q) {
        const double tol = q == 3 && row.eps > 0.95 ? 0.07 : 0.035;
        EXPECT_NEAR(ours[q] / table[q], 1.0, tol) << "L/D=" << t.ld << " eps=" << row.eps << " column " << q;
        if (!(q == 3 && row.eps > 0.95)) worst[q] = std::max(worst[q], std::fabs(ours[q] / table[q] - 1.0));
      }
      // The peak sits in the converging film, before the minimum film at θ = π.
      EXPECT_GT(out.peak_pressure_angle_rad, 0.5 * kPi);
      EXPECT_LT(out.peak_pressure_angle_rad, kPi);
    }
  }
  std::printf("[ measured ] worst relative deviation: friction %.3f, flow %.3f, side/flow %.3f, P/pmax %.3f\n",
              worst[0], worst[1], worst[2], worst[3]);
}

TEST(FiniteBearing, PetroffTorqueOfANearlyCentredJournal) {
  // Petroff: T = 2π μ ω R³ L/c at ε = 0. At ε = 1e-3 the film adds O(ε²) to the Couette part
  // and (c ε/2) F_t = O(ε²) to the journal's torque: within 1e-5 of Petroff, for every
  // cavitation condition (the done-when asks 0.1 %). A sliding speed other than the wedge
  // speed (a rotating bearing): the torque follows ω_J − ω_B.
  const auto g = geometry(1.0);
  for (const Cavitation cav : {Cavitation::sommerfeld, Cavitation::gumbel, Cavitation::reynolds}) {
    FiniteBearingOptions o;
    o.cavitation = cav;
    FiniteBearingSolver solver(o);
    for (const double sliding : {100.0, -40.0}) {
      solver.solve(g, kMu, state(1e-3, 0.0, 100.0));
      const lub::FilmOutputs out = solver.outputs(sliding);
      const double petroff = lub::petroff_torque_Nm(kMu, sliding, g.journal_radius_m, g.length_m, g.clearance_m());
      EXPECT_NEAR(out.journal_friction_torque_Nm, petroff, 1e-5 * std::fabs(petroff));
      EXPECT_NEAR(out.bearing_friction_torque_Nm, petroff, 1e-5 * std::fabs(petroff));
    }
  }
  // By hand for this bearing: 2π · 0.4 Pa s · 100 rad/s · (0.01 m)³ · 0.02 m / 0.0005 m = 3.2e-3 π N m.
  EXPECT_NEAR(lub::petroff_torque_Nm(kMu, 100.0, 0.010, 0.020, 0.0005), 3.2e-3 * kPi, 1e-16);
}

TEST(FiniteBearing, PeriodicFilmDiffersFromTheGroovedOneOnlyAtLowEccentricity) {
  // Without the supply groove the film may reform before θ = 0 and carry pressure there:
  // at ε = 0.1 (L/D = 1) the attitude angle rises by ~4°; at ε >= 0.8 the two agree to 1°.
  const auto g = geometry(1.0);
  const auto phi = [&](double eps, bool groove) {
    const FilmForce f = finite(g, state(eps, 0.0, 100.0), Cavitation::reynolds, 96, 12, groove);
    return std::atan2(f.tangential_N, -f.radial_N) * 180.0 / kPi;
  };
  EXPECT_GT(phi(0.1, false) - phi(0.1, true), 2.0);
  EXPECT_LT(std::fabs(phi(0.8, false) - phi(0.8, true)), 1.0);
}

// --- Solver properties ------------------------------------------------------------------------

TEST(FiniteBearing, ResultDoesNotDependOnTheWarmStart) {
  // The active-set iteration ends at the exact discrete solution: a solver reused along a
  // sequence of states (warm starts) gives what a fresh solver gives, to rounding (1e-12).
  BearingGeometry g = geometry(40.0 / 19.0);
  FiniteBearingOptions o;
  FiniteBearingSolver reused(o);
  for (int k = 0; k < 40; ++k) {
    const BearingState s = state(0.5 + 0.45 * std::sin(0.3 * k), 20.0 * std::cos(0.7 * k), 500.0 * std::cos(0.2 * k));
    const FilmForce a = reused.solve(g, kMu, s);
    EXPECT_TRUE(reused.stats().converged);
    FiniteBearingSolver fresh(o);
    const FilmForce b = fresh.solve(g, kMu, s);
    const double sc = std::hypot(b.radial_N, b.tangential_N) + 1e-300;
    EXPECT_NEAR(a.radial_N, b.radial_N, 1e-12 * sc) << k;
    EXPECT_NEAR(a.tangential_N, b.tangential_N, 1e-12 * sc) << k;
  }
}

TEST(FiniteBearing, ReynoldsPressureIsNonNegativeAndCarriesMoreThanGumbel) {
  // Swift–Stieber: p >= 0 everywhere (exactly: the solver clips rounding-level negatives); the
  // film extends past the Gümbel rupture, so the load it carries is larger.
  const auto g = geometry(1.0);
  FiniteBearingOptions o;
  o.n_theta = 64;
  o.n_z = 8;
  FiniteBearingSolver solver(o);
  for (double eps : {0.2, 0.6, 0.9}) {
    const FilmForce f = solver.solve(g, kMu, state(eps, 0.0, 300.0));
    int below_zero = 0;  // cells with p < 0 (or NaN)
    for (int i = 0; i < o.n_theta; ++i)
      for (int j = 0; j < o.n_z; ++j) below_zero += !(solver.pressure_Pa(i, j) >= 0.0);
    EXPECT_EQ(below_zero, 0) << "eps " << eps;
    EXPECT_GT(solver.stats().cavitated_cells, 0);
    const FilmForce fg = finite(g, state(eps, 0.0, 300.0), Cavitation::gumbel, 64, 8);
    EXPECT_GT(std::hypot(f.radial_N, f.tangential_N), std::hypot(fg.radial_N, fg.tangential_N));
  }
}

TEST(FiniteBearing, SymmetriesAndZeroState) {
  // Homogeneous of degree 1 in (ε̇, w) for λ > 0; w → −w mirrors the field (F_t flips);
  // no motion, no force. Same discrete problem scaled: 1e-12.
  const auto g = geometry(40.0 / 19.0);
  for (Cavitation cav : {Cavitation::sommerfeld, Cavitation::gumbel, Cavitation::reynolds}) {
    const FilmForce f = finite(g, state(0.6, 4.0, 300.0), cav, 48, 6);
    const FilmForce f3 = finite(g, state(0.6, 12.0, 900.0), cav, 48, 6);
    const FilmForce fm = finite(g, state(0.6, 4.0, -300.0), cav, 48, 6);
    const double sc = std::hypot(f.radial_N, f.tangential_N);
    EXPECT_NEAR(f3.radial_N, 3.0 * f.radial_N, 3e-12 * sc) << name_of(cav);
    EXPECT_NEAR(f3.tangential_N, 3.0 * f.tangential_N, 3e-12 * sc) << name_of(cav);
    // The ψ grid is symmetric about θ = 0: the mirror is exact up to rounding.
    EXPECT_NEAR(fm.radial_N, f.radial_N, 1e-12 * sc) << name_of(cav);
    EXPECT_NEAR(fm.tangential_N, -f.tangential_N, 1e-12 * sc) << name_of(cav);
    const FilmForce z = finite(g, state(0.6, 0.0, 0.0), cav, 48, 6);
    EXPECT_EQ(z.radial_N, 0.0);
    EXPECT_EQ(z.tangential_N, 0.0);
  }
}

TEST(FiniteBearing, DispatchAndOptionValidation) {
  const auto g = geometry(1.0);
  const auto s = state(0.5, 1.0, 200.0);
  FiniteBearingSolver solver{FiniteBearingOptions{}};
  const FilmForce a = lub::film_force(ForceLaw::finite_reynolds, g, kMu, s, &solver);
  const FilmForce b = lub::film_force(ForceLaw::finite_reynolds, g, kMu, s);  // default options
  EXPECT_EQ(a.radial_N, b.radial_N);
  EXPECT_EQ(a.tangential_N, b.tangential_N);
  FiniteBearingOptions bad;
  bad.n_theta = 4;
  EXPECT_THROW(FiniteBearingSolver{bad}, std::invalid_argument);
  bad.n_theta = 16;
  bad.n_z = 0;
  EXPECT_THROW(FiniteBearingSolver{bad}, std::invalid_argument);
  // Copies get their own scratch and the same options.
  FiniteBearingSolver copy = solver;
  EXPECT_EQ(copy.options().n_theta, solver.options().n_theta);
  const FilmForce c = copy.solve(g, kMu, s);
  EXPECT_EQ(c.radial_N, a.radial_N);
}

}  // namespace
