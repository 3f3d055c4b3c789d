// Tests of the steadily loaded bearing (core/src/bearing/steady_bearing.cpp): for each law, the
// equilibrium eccentricity and attitude angle under a static load against the classical
// results, and the finite bearing against Raimondi & Boyd's table through the same solver.
//
// Route: pick ε₀, compute the load W(ε₀) from the classical closed form (written here, not
// taken from the library), hand W to the solver and expect ε₀ back; compare φ with its
// classical formula. Tolerances: the solver stops at |Δε| <= 1e-14 ε, so ε agrees to ~1e-12
// (the closed forms' rounding in log|F| mapped through dε/dlog W ~ 1); φ to 1e-10 rad.

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "lub/bearing/film_outputs.hpp"
#include "lub/bearing/force_laws.hpp"
#include "lub/bearing/steady_bearing.hpp"

namespace {

using lub::BearingGeometry;
using lub::ForceLaw;
using lub::SteadyBearingInput;
using lub::SteadyBearingResult;

constexpr double kPi = 3.14159265358979323846;
constexpr double kMu = 0.05;
constexpr double kOmega = 2.0 * kPi * 3000.0 / 60.0;  // 3000 rpm

BearingGeometry geometry(double length_m) {
  BearingGeometry g;
  g.journal_radius_m = 0.025;
  g.bearing_radius_m = 0.025 + 50e-6;
  g.length_m = length_m;
  return g;
}

SteadyBearingResult solve(ForceLaw law, const BearingGeometry& g, double load) {
  SteadyBearingInput in;
  in.law = law;
  in.geometry = g;
  in.viscosity_Pa_s = kMu;
  in.load_N = load;
  in.speed_rad_s = kOmega;
  return lub::solve_steady_bearing(in);
}

struct Classical {
  double load_N;
  double attitude_rad;
};

// Classical steady bearings, U = R ω, C = μLR³/c², C_s = μL³R/c².
Classical ocvirk(const BearingGeometry& g, double e) {  // short, π film
  const double c = g.clearance_m();
  const double Cs = kMu * std::pow(g.length_m, 3) * g.journal_radius_m / (c * c);
  const double om = 1.0 - e * e;
  return {Cs * kOmega * e / (4.0 * om * om) * std::sqrt(16.0 * e * e + kPi * kPi * om),
          std::atan(kPi * std::sqrt(om) / (4.0 * e))};
}
double ocvirk_full(const BearingGeometry& g, double e) {  // short, full film: F_t alone
  const double c = g.clearance_m();
  const double Cs = kMu * std::pow(g.length_m, 3) * g.journal_radius_m / (c * c);
  return kPi * Cs * kOmega * e / (2.0 * std::pow(1.0 - e * e, 1.5));
}
Classical sommerfeld_full(const BearingGeometry& g, double e) {  // long, full film: φ = 90°
  const double c = g.clearance_m();
  const double C = kMu * g.length_m * std::pow(g.journal_radius_m, 3) / (c * c);
  return {12.0 * kPi * C * kOmega * e / ((2.0 + e * e) * std::sqrt(1.0 - e * e)), 0.5 * kPi};
}
Classical half_sommerfeld(const BearingGeometry& g, double e) {  // long, π film
  const double c = g.clearance_m();
  const double C = kMu * g.length_m * std::pow(g.journal_radius_m, 3) / (c * c);
  const double om = 1.0 - e * e;
  return {6.0 * C * kOmega * e * std::sqrt(kPi * kPi * om + 4.0 * e * e) / ((2.0 + e * e) * om),
          std::atan(kPi * std::sqrt(om) / (2.0 * e))};
}
Classical short_full(const BearingGeometry& g, double e) {  // short, full film: φ = 90°
  const double c = g.clearance_m();
  const double Cs = kMu * std::pow(g.length_m, 3) * g.journal_radius_m / (c * c);
  return {kPi * Cs * kOmega * e / (2.0 * std::pow(1.0 - e * e, 1.5)), 0.5 * kPi};
}

void expect_equilibrium(ForceLaw law, const BearingGeometry& g, double e0, const Classical& cl) {
  const SteadyBearingResult r = solve(law, g, cl.load_N);
  ASSERT_TRUE(r.converged) << lub::name_of(law) << ": " << r.message;
  EXPECT_NEAR(r.eps, e0, 1e-11 * e0) << lub::name_of(law) << " eps0=" << e0;
  EXPECT_NEAR(r.attitude_rad, cl.attitude_rad, 1e-10) << lub::name_of(law) << " eps0=" << e0;
  EXPECT_NEAR(r.min_film_thickness_m, g.clearance_m() * (1.0 - e0), 1e-11 * g.clearance_m());
  EXPECT_NEAR(std::hypot(r.force.radial_N, r.force.tangential_N), cl.load_N, 1e-12 * cl.load_N);
}

const double kEps[] = {0.05, 0.2, 0.5, 0.8, 0.95};

TEST(SteadyBearing, OcvirkShortBearing) {
  const auto g = geometry(0.010);  // L/D = 0.2
  for (double e : kEps) expect_equilibrium(ForceLaw::gumbel_short, g, e, ocvirk(g, e));
}

TEST(SteadyBearing, SommerfeldLongBearingFullFilm) {
  const auto g = geometry(0.150);  // L/D = 3
  for (double e : kEps) expect_equilibrium(ForceLaw::frene_long, g, e, sommerfeld_full(g, e));
}

TEST(SteadyBearing, HalfSommerfeldLongBearing) {
  // gumbel_long and the exact π film (identical at ε̇ = 0) both reproduce it.
  const auto g = geometry(0.150);
  for (double e : kEps) {
    expect_equilibrium(ForceLaw::gumbel_long, g, e, half_sommerfeld(g, e));
    expect_equilibrium(ForceLaw::pinkus_sternlicht_continuous, g, e, half_sommerfeld(g, e));
  }
}

TEST(SteadyBearing, ShortBearingFullFilm) {
  const auto g = geometry(0.010);
  for (double e : kEps) expect_equilibrium(ForceLaw::frene_short, g, e, short_full(g, e));
}

TEST(SteadyBearing, PrintedPinkusSternlichtCarriesTheLoadAtASmallerEccentricity) {
  // Its F_t is 1/(1−ε²) too large, so under the half-Sommerfeld load W(ε₀) it settles at a
  // smaller ε with a larger attitude angle: tan φ = π/(2ε(1−ε²)^(1/2)) at its own ε.
  const auto g = geometry(0.150);
  for (double e : {0.5, 0.8}) {
    SCOPED_TRACE(e);
    const SteadyBearingResult r = solve(ForceLaw::pinkus_sternlicht, g, half_sommerfeld(g, e).load_N);
    EXPECT_TRUE(r.converged);
    if (!r.converged) continue;
    EXPECT_LT(r.eps, e);
    EXPECT_NEAR(std::tan(r.attitude_rad), kPi / (2.0 * r.eps * std::sqrt(1.0 - r.eps * r.eps)), 1e-9);
  }
}

TEST(SteadyBearing, FiniteBearingAgainstRaimondiBoydThroughTheSolver) {
  // Raimondi & Boyd (1958) Table 1, L/D = 1 (see test_core_reynolds.cpp for the citation):
  // load from the tabulated S, equilibrium ε within 0.01 of the tabulated ε, φ within 0.6°.
  // Grid 96 × 12 with R&B's supply condition.
  const struct {
    double eps, S, phi_deg;
  } rows[] = {{0.2, 0.631, 74.02}, {0.6, 0.121, 50.58}, {0.9, 0.0188, 26.45}};
  const auto g = geometry(0.050);  // L/D = 1
  for (const auto& row : rows) {
    const double rc = g.journal_radius_m / g.clearance_m();
    const double n_rev = kOmega / (2.0 * kPi);
    const double P = rc * rc * kMu * n_rev / row.S;
    SteadyBearingInput in;
    in.law = ForceLaw::finite_reynolds;
    in.finite.n_theta = 96;
    in.finite.n_z = 12;
    in.finite.groove_at_max_film = true;
    in.geometry = g;
    in.viscosity_Pa_s = kMu;
    in.load_N = P * 2.0 * g.journal_radius_m * g.length_m;
    in.speed_rad_s = kOmega;
    const SteadyBearingResult r = lub::solve_steady_bearing(in);
    EXPECT_TRUE(r.converged) << row.eps << ": " << r.message;
    if (!r.converged) continue;
    EXPECT_NEAR(r.eps, row.eps, 0.01) << row.eps;
    EXPECT_NEAR(r.attitude_rad * 180.0 / kPi, row.phi_deg, 0.6) << row.eps;
    EXPECT_NEAR(r.sommerfeld, row.S, 1e-12 * row.S);
    std::printf("[ measured ] steady finite_reynolds L/D=1 S=%g: eps %.4f (table %.2f), phi %.2f deg (table %.2f)\n",
                row.S, r.eps, row.eps, r.attitude_rad * 180.0 / kPi, row.phi_deg);
  }
}

TEST(SteadyBearing, SommerfeldBearingsFrictionIsTheClassicalOne) {
  // The full (Sommerfeld) long bearing's friction variable, from its pressure field alone:
  // (R/c) f = (1 + 2ε²)/(3ε) (e.g. Hamrock, Fundamentals of Fluid Film Lubrication, ch. 10).
  // Through the solver: load from the closed form at ε₀, friction from the film's torque.
  // Petroff at small ε: T → 2π μ ω R³ L/c. Tolerance: the solver's ε to ~1e-12.
  const auto g = geometry(0.100);
  for (const double e : {0.05, 0.3, 0.6, 0.9}) {
    const SteadyBearingResult r = solve(ForceLaw::frene_long, g, sommerfeld_full(g, e).load_N);
    ASSERT_TRUE(r.converged) << r.message;
    const double W = sommerfeld_full(g, e).load_N, c = g.clearance_m();
    const double friction_variable = r.outputs.journal_friction_torque_Nm / (c * W);
    EXPECT_NEAR(friction_variable, (1.0 + 2.0 * e * e) / (3.0 * e), 1e-9 * friction_variable) << e;
    // The bearing's torque is the journal's less e F_t (the film's moment balance).
    EXPECT_NEAR(r.outputs.journal_friction_torque_Nm - r.outputs.bearing_friction_torque_Nm,
                c * r.eps * r.force.tangential_N, 1e-9 * r.outputs.journal_friction_torque_Nm);
  }
}

TEST(SteadyBearing, PeakPressureOfTheClassicalBearings) {
  // Closed forms of the steadily loaded bearings' peak pressure and its angle θ_m (from the
  // line of maximum film), written here from the classical fields:
  //   Sommerfeld (and half-Sommerfeld, its positive part): cos θ_m = −3ε/(2 + ε²),
  //     p_max = 6 μ ω (R/c)² ε sin θ_m (2 + ε cos θ_m)/((2 + ε²)(1 + ε cos θ_m)²);
  //   Ocvirk (full and π film), mid-plane: cos θ_m = (1 − (1 + 24ε²)^½)/(4ε),
  //     p_max = 3 μ ω (L²/4) ε sin θ_m/(c² (1 + ε cos θ_m)³).
  // The library maximises the law's own field numerically: to 1e-8 (the golden section's
  // 1e-9 rad on a flat maximum moves the value by ~1e-18; the angle by its tolerance).
  const auto g = geometry(0.050);
  const double R = g.journal_radius_m, c = g.clearance_m(), L = g.length_m;
  for (const double e : {0.2, 0.6, 0.9}) {
    const double cs = -3.0 * e / (2.0 + e * e), ss = std::sqrt(1.0 - cs * cs);
    const double p_somm = 6.0 * kMu * kOmega * (R / c) * (R / c) * e * ss * (2.0 + e * cs) /
                          ((2.0 + e * e) * (1.0 + e * cs) * (1.0 + e * cs));
    const double co = (1.0 - std::sqrt(1.0 + 24.0 * e * e)) / (4.0 * e), so = std::sqrt(1.0 - co * co);
    const double p_ocv = 3.0 * kMu * kOmega * (L * L / 4.0) * e * so / (c * c * std::pow(1.0 + e * co, 3));
    const struct {
      ForceLaw law;
      double load, p, theta;
    } cases[] = {{ForceLaw::frene_long, sommerfeld_full(g, e).load_N, p_somm, std::acos(cs)},
                 {ForceLaw::gumbel_long, half_sommerfeld(g, e).load_N, p_somm, std::acos(cs)},
                 {ForceLaw::frene_short, ocvirk_full(g, e), p_ocv, std::acos(co)},
                 {ForceLaw::gumbel_short, ocvirk(g, e).load_N, p_ocv, std::acos(co)}};
    for (const auto& k : cases) {
      const SteadyBearingResult r = solve(k.law, g, k.load);
      ASSERT_TRUE(r.converged) << r.message;
      ASSERT_NEAR(r.eps, e, 1e-9);
      EXPECT_NEAR(r.outputs.peak_pressure_Pa, k.p, 1e-8 * k.p) << lub::name_of(k.law) << " eps " << e;
      EXPECT_NEAR(r.outputs.peak_pressure_angle_rad, k.theta, 1e-7) << lub::name_of(k.law) << " eps " << e;
    }
  }
}

TEST(SteadyBearing, ReportsLoadsOutsideTheFilmsRange) {
  const auto g = geometry(0.050);
  const SteadyBearingResult tiny = solve(ForceLaw::gumbel_short, g, 1e-12);
  EXPECT_FALSE(tiny.converged);
  EXPECT_NE(tiny.message.find("centred"), std::string::npos) << tiny.message;
  const SteadyBearingResult huge = solve(ForceLaw::gumbel_short, g, 1e30);
  EXPECT_FALSE(huge.converged);
  EXPECT_NE(huge.message.find("cannot carry"), std::string::npos) << huge.message;
}

// The short-bearing laws' oil flows (lub/bearing/film_outputs.hpp): the Couette flow alone
// carries the film round, so Q/(R c N L) = π (1 + ε) and Q_s/Q = 2ε/(1 + ε). Against Raimondi &
// Boyd's L/D = 1/4 table (their relaxation solution of the finite bearing, the short-bearing
// limit's nearest column; Shigley Table 12-4), within the 2 % their three digits and the
// finite length allow (measured: within 1.0 %).
TEST(SteadyBearing, ShortBearingFlowsAgainstRaimondiBoydAtAQuarterOfTheDiameter) {
  const struct {
    double eps, flow_variable, side_ratio;
  } table[] = {{0.1, 3.45, 0.180}, {0.2, 3.76, 0.330}, {0.4, 4.37, 0.567}, {0.6, 4.99, 0.746}, {0.8, 5.60, 0.884},
               {0.9, 5.91, 0.945}};
  const BearingGeometry g = geometry(0.25 * 0.05);
  for (const auto& row : table) {
    // The flows depend on ε alone: the exact relations, then the table's columns, at its ε.
    lub::FilmOutputs o;
    lub::short_bearing_flows(g, row.eps, kOmega, o);
    const double n_rev = kOmega / (2.0 * kPi), R = 0.025, c = 50e-6, L = g.length_m;
    const double q = o.inflow_m3_s / (R * c * n_rev * L), ratio = o.side_flow_m3_s / o.inflow_m3_s;
    EXPECT_NEAR(q, kPi * (1.0 + row.eps), 1e-12 * q);
    EXPECT_NEAR(ratio, 2.0 * row.eps / (1.0 + row.eps), 1e-12);
    EXPECT_NEAR(q, row.flow_variable, 0.02 * row.flow_variable) << "eps " << row.eps;
    EXPECT_NEAR(ratio, row.side_ratio, 0.02 * row.side_ratio) << "eps " << row.eps;
  }
  // The steady bearing reports them at its equilibrium.
  const SteadyBearingResult r = solve(ForceLaw::gumbel_short, g, 200.0);
  ASSERT_TRUE(r.converged) << r.message;
  EXPECT_TRUE(r.has_flows);
  EXPECT_NEAR(r.outputs.side_flow_m3_s / r.outputs.inflow_m3_s, 2.0 * r.eps / (1.0 + r.eps), 1e-12);
}

TEST(SteadyBearing, SommerfeldNumberDefinition) {
  // S = (R/c)² μ N/P with N in rev/s and P = W/(L D).
  const auto g = geometry(0.050);
  const double S = lub::sommerfeld_number(g, kMu, 1000.0, kOmega);
  const double expect = std::pow(0.025 / g.clearance_m(), 2) * kMu * 50.0 / (1000.0 / (0.050 * 0.050));
  EXPECT_NEAR(S, expect, 1e-14 * expect);
}

}  // namespace
