// The paper's slider-crank through the whole engine (scene → model → CVODE → observers):
// the ideal mechanism against closed-form kinematics and inverse dynamics, constraint
// drift, the energy balance of the lubricated mechanism including the film's dissipation,
// and the reference case from ε = 0.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>

#include "lub/mechanism/model.hpp"
#include "lub/run/run.hpp"

namespace {

using lub::RunResult;
using lub::RunStatus;
using nlohmann::json;

constexpr double kPi = 3.14159265358979323846;

json load(const std::string& name) {
  return lub::read_json_file(std::string(LUB_SOURCE_DIR) + "/configs/scenes/" + name);
}

const std::vector<double>& channel(const RunResult& r, const std::string& name) {
  for (size_t i = 0; i < r.series.names.size(); ++i)
    if (r.series.names[i] == name) return r.series.data[i];
  throw std::runtime_error("no channel " + name);
}

// Closed-form slider-crank (crank a, rod l, slider on the x axis through the crank
// pivot), crank at constant ω from θ = 0 (crank and rod aligned), centres of mass at
// mid-length. Derivatives with respect to θ are written out by hand.
struct ClosedForm {
  double a = 0.05, l = 0.12, ms = 0.14, mr = 0.21, Jr = 2.5e-4, g = 9.81, omega;
  explicit ClosedForm(double rpm) : omega(rpm * 2 * kPi / 60) {}
  struct State {
    double x, xd, xdd;  // slider
    double R;           // |force| at the rod–slider pin
  };
  State at(double t) const {
    const double th = omega * t, s = std::sin(th), c = std::cos(th);
    const double D = std::sqrt(l * l - a * a * s * s);
    const double Dp = -a * a * s * c / D;
    const double Dpp = -a * a * (c * c - s * s) / D - std::pow(a, 4) * s * s * c * c / std::pow(D, 3);
    State st;
    st.x = a * c + D;
    st.xd = (-a * s + Dp) * omega;
    st.xdd = (-a * c + Dpp) * omega * omega;
    // Rod angle β: sin β = −a s / l; β'' with respect to θ.
    const double bpp = a * s / D - std::pow(a, 3) * s * c * c / std::pow(D, 3);
    const double bdd = bpp * omega * omega;
    // Rod centre of mass G = (A + B)/2 = (a c + D/2, a s/2).
    const double aGx = (-a * c + Dpp / 2) * omega * omega, aGy = -(a * s / 2) * omega * omega;
    // Slider: m_s ẍ = R_x (R: force of the rod on the slider; guide frictionless).
    const double Rx = ms * st.xdd;
    // Rod, moments about its centre: J β̈ = −(l/2) u × m(a_G − g) − l u × R.
    const double ux = D / l, uy = -a * s / l;
    const double mx = mr * aGx, my = mr * (aGy + g);
    const double cr = ux * my - uy * mx;
    const double Ry = (-Jr * bdd - 0.5 * l * cr) / (l * ux) + uy * Rx / ux;
    st.R = std::hypot(Rx, Ry);
    return st;
  }
};

RunResult run_ideal(double rtol, const std::string& method = "cvode_bdf") {
  json doc = load("slider_crank_ideal.json");
  doc["solver"]["rtol"] = rtol;
  doc["solver"]["method"] = method;
  return lub::run_scene(lub::parse_scene(doc));
}

// Largest deviations of the recorded series from the closed form, relative to their
// scales: x ~ 0.17 m (absolute, m), v ~ aω = 26 m/s, a ~ aω² = 1.9e4 m/s², R ~ 2.7e3 N.
struct Deviation {
  double x = 0, v = 0, a = 0, R = 0;
};
Deviation deviation_from_closed_form(const RunResult& r) {
  const ClosedForm cf(5000);
  const auto& t = channel(r, "t");
  const auto& x = channel(r, "slider_x");
  const auto& v = channel(r, "slider_v");
  const auto& a = channel(r, "slider_a");
  const auto& R = channel(r, "reaction_force");
  EXPECT_GT(t.size(), 2000u);
  Deviation d;
  for (size_t i = 0; i < t.size(); ++i) {
    const auto s = cf.at(t[i]);
    d.x = std::max(d.x, std::fabs(x[i] - s.x));
    d.v = std::max(d.v, std::fabs(v[i] - s.xd) / 26.0);
    d.a = std::max(d.a, std::fabs(a[i] - s.xdd) / 1.9e4);
    d.R = std::max(d.R, std::fabs(R[i] - s.R) / 2.7e3);
  }
  return d;
}

// At rtol 1e-10 the integrated answer should agree with the closed form to ~1e-8
// relative (plus a similar Baumgarte drift): bounds 10x that.
void expect_matches_closed_form(const RunResult& r) {
  const Deviation d = deviation_from_closed_form(r);
  EXPECT_LT(d.x, 1e-8);
  EXPECT_LT(d.v, 1e-6);
  EXPECT_LT(d.a, 1e-6);
  EXPECT_LT(d.R, 1e-6);
}

TEST(SliderCrankIdeal, KinematicsAndReactionMatchClosedForm) {
  const RunResult r = run_ideal(1e-10);
  ASSERT_EQ(r.status, RunStatus::ok) << r.message;
  expect_matches_closed_form(r);
}

TEST(SliderCrankIdeal, IdaOnTheGglFormulationMatchesClosedForm) {
  // The same check for IDA on the index-2 GGL DAE (no Baumgarte terms): its error test
  // sees (q, v) only, the multipliers are recomputed by the observers from (q, v).
  const RunResult r = run_ideal(1e-10, "ida");
  ASSERT_EQ(r.status, RunStatus::ok) << r.message;
  EXPECT_EQ(r.stats.method, lub::Method::ida);
  expect_matches_closed_form(r);
}

TEST(SliderCrankIdeal, PeaksAt5000RpmWithinTenthOfAPercentAtDefaultTolerance) {
  // The acceptance check, at the scene's own (default) tolerance.
  json doc = load("slider_crank_ideal.json");
  const RunResult r = lub::run_scene(lub::parse_scene(doc));
  ASSERT_EQ(r.status, RunStatus::ok) << r.message;
  const ClosedForm cf(5000);
  double peakR = 0, peakA = 0;
  const double T = 2 * kPi / cf.omega;
  for (int i = 0; i < 200000; ++i) {
    const auto s = cf.at(T * i / 200000.0);
    peakR = std::max(peakR, s.R);
    peakA = std::max(peakA, std::fabs(s.xdd));
  }
  EXPECT_NEAR(r.metrics.peak_reaction_N / peakR, 1.0, 1e-3);
  EXPECT_NEAR(r.metrics.peak_acceleration_m_s2 / peakA, 1.0, 1e-3);
  // The same peaks from the recorded series.
  double sR = 0, sA = 0;
  for (double v : channel(r, "reaction_force")) sR = std::max(sR, v);
  for (double v : channel(r, "slider_a")) sA = std::max(sA, std::fabs(v));
  EXPECT_NEAR(sR / peakR, 1.0, 1e-3);
  EXPECT_NEAR(sA / peakA, 1.0, 1e-3);
}

TEST(SliderCrankIdeal, ConstraintDriftBoundedAndShrinksWithTolerance) {
  // Baumgarte (α = β = 5) only damps the drift the integrator's error feeds it, so the
  // drift must fall with the tolerance, and stay far below the smallest length (the
  // 0.5 mm clearance of the lubricated variant).
  const RunResult loose = run_ideal(1e-6), tight = run_ideal(1e-9);
  ASSERT_EQ(loose.status, RunStatus::ok);
  ASSERT_EQ(tight.status, RunStatus::ok);
  EXPECT_LT(loose.stats.max_position_drift, 2e-5);
  EXPECT_LT(tight.stats.max_position_drift, loose.stats.max_position_drift / 100);
  EXPECT_LT(tight.stats.max_velocity_drift, loose.stats.max_velocity_drift / 100);
}

json lubricated(const std::string& law, double rtol, int cycles) {
  json doc = load("slider_crank.json");
  doc["joints"][3]["force_law"] = law;
  doc["solver"]["rtol"] = rtol;
  doc["simulation"]["max_cycles"] = cycles;
  doc["simulation"]["metric_cycles"] = 1;
  doc["outputs"]["channels"] = json::array();
  return doc;
}

// A scene that gives no solver.rtol runs at the default, chosen in docs/validation/work-precision.md
// (1e-8 since issue 12; 1e-6 before). The paper's scene without its rtol, four cycles
// from the centred start, against the study's reference (CVODE BDF partitioned, rtol
// 1e-12: h_min 1.20181e-5 m, peak reaction 9718.32 N). What rtol 1e-8 delivers on this
// orbit is ~3.4e-6 c at the cycle ends (bench_floor_accuracy, printed law, either
// Jacobian), i.e. up to 1.4e-4 of h_min (c = 0.5 mm): measured 5.4e-5 with the structured
// Jacobian (the default since issue 16), 3.3e-7 with difference quotients (a favourable
// cancellation: the bound of 1e-5 first set on it was tighter than the tolerance gives),
// 2.6e-3 at rtol 1e-6. Bound 2e-4: the 1e-8 orbit error with room, 1/13 of the 1e-6 one.
// Peak reaction: 2.1e-6 relative at 1e-8, 5.2e-5 at 1e-6; bound 1e-4.
TEST(SliderCrankLubricated, SceneWithoutRtolMeetsTheStudyAccuracy) {
  json doc = load("slider_crank.json");
  doc["solver"].erase("rtol");
  doc["simulation"]["max_cycles"] = 4;
  doc["simulation"]["metric_cycles"] = 1;
  doc["outputs"]["channels"] = json::array();
  const lub::Scene scene = lub::parse_scene(doc);
  EXPECT_EQ(scene.solver.rtol, 1e-8);
  const RunResult r = lub::run_scene(scene);
  ASSERT_EQ(r.status, RunStatus::ok) << r.message;
  EXPECT_NEAR(r.metrics.min_film_thickness_m / 1.20181e-5, 1.0, 2e-4);
  EXPECT_NEAR(r.metrics.peak_reaction_N / 9718.32, 1.0, 1e-4);
}

// The largest ε of a cycle lies between two observations (step ends, 120 phase points);
// where ε̇ changes sign there it is taken from the cubic through both ends' ε and ε̇, not
// from the larger end. Frêne short law, 3 cycles (its peak falls between phase points,
// 1.301–1.306 rad of crank), at rtol 1e-10 against 1e-11 per cycle: the peaks agree to
// 1.6e-8–1.2e-7 in ε and to 1e-5 rad in crank angle; the step ends alone (no
// interpolation) gave 1.0e-6–2.9e-6 and up to 5.4e-3 rad (a phase point won: 1.309).
// Bounds 5e-7 and 1e-3 rad: 4× above the interpolation's error, 2× below the ends'.
TEST(SliderCrankLubricated, PeakEccentricityBetweenObservationsIsInterpolated) {
  const RunResult a = lub::run_scene(lub::parse_scene(lubricated("frene_short", 1e-10, 3)));
  const RunResult b = lub::run_scene(lub::parse_scene(lubricated("frene_short", 1e-11, 3)));
  ASSERT_EQ(a.status, RunStatus::ok) << a.message;
  ASSERT_EQ(b.status, RunStatus::ok) << b.message;
  ASSERT_EQ(a.cycles.size(), 3u);
  ASSERT_EQ(b.cycles.size(), 3u);
  for (size_t k = 0; k < 3; ++k) {
    EXPECT_NEAR(a.cycles[k].max_eps, b.cycles[k].max_eps, 5e-7) << "cycle " << k + 1;
    EXPECT_NEAR(a.cycles[k].crank_angle_at_min_film_rad, b.cycles[k].crank_angle_at_min_film_rad, 1e-3) << "cycle " << k + 1;
    // min film and max ε describe the same point (c = 10.0 mm − 9.5 mm, to round-off)
    EXPECT_NEAR(a.cycles[k].min_film_thickness_m, 5e-4 * (1.0 - a.cycles[k].max_eps), 1e-15) << "cycle " << k + 1;
  }
}

TEST(SliderCrankLubricated, EnergyBalanceIncludingFilmDissipation) {
  // W_driver = ΔE + D_film + W_drift, where W_drift is the work of the ideal joints'
  // reactions on the constraint drift (zero on the exact manifold). At rtol 1e-9 the
  // drift is ~1e-9 m and its work negligible, so the residual measures the quadratures
  // and the integration: require 1e-5 of the driver work (10x what we observe).
  // IDA (GGL) integrates the same quadratures with IDAS: its balance has no drift term.
  for (const std::string method : {"cvode_bdf", "ida"})
  for (const std::string law : {"frene_long", "frene_short"}) {
    SCOPED_TRACE(method);
    json doc = lubricated(law, 1e-9, 3);
    doc["solver"]["method"] = method;
    doc["outputs"]["energy_balance"] = true;
    doc["effects"]["gravity_m_s2"] = json::array({0.0, -9.81});
    const RunResult r = lub::run_scene(lub::parse_scene(doc));
    EXPECT_EQ(r.status, RunStatus::ok) << law << ": " << r.message;
    if (r.status != RunStatus::ok) continue;
    const auto& m = r.metrics;
    EXPECT_GT(m.film_dissipation_J, 0.0) << law;  // the film dissipates
    const double scale = std::fabs(m.driver_work_J) + std::fabs(m.film_dissipation_J);
    EXPECT_LT(std::fabs(m.energy_residual_J), 1e-5 * scale)
        << law << ": W=" << m.driver_work_J << " dE=" << m.energy_change_J << " D=" << m.film_dissipation_J;
  }
}

TEST(SliderCrankLubricated, EnergyBalanceClosesWithTheFilmsFrictionLoss) {
  // effects.film_friction applies the film's shear torques T_J, T_B to crank and rod: the
  // driver then supplies the friction loss as well, and W_driver = ΔE + D_film closes with
  // D_film = ∫(T_J ω_J − T_B ω_B − F·ė) dt. Same bound as above (1e-5 of the driver work).
  // The quadrature D_film / t is the recorder's mean film power loss, which integrates the
  // same power by the trapezoidal rule between observations (every 1e-5 s, 1/1200 of a
  // cycle): it agrees to its O(Δt²) error, measured 1e-4; bound 1e-3.
  for (const std::string method : {"cvode_bdf", "ida"})
  for (const std::string law : {"frene_long", "frene_short", "pinkus_sternlicht"}) {
    SCOPED_TRACE(method + " " + law);
    json doc = lubricated(law, 1e-9, 3);
    doc["simulation"]["metric_cycles"] = 3;
    doc["solver"]["method"] = method;
    doc["outputs"]["energy_balance"] = true;
    json without = doc;
    doc["effects"]["film_friction"] = json::object();
    const RunResult r = lub::run_scene(lub::parse_scene(doc));
    const RunResult r0 = lub::run_scene(lub::parse_scene(without));
    ASSERT_EQ(r.status, RunStatus::ok) << r.message;
    ASSERT_EQ(r0.status, RunStatus::ok) << r0.message;
    const auto& m = r.metrics;
    const double scale = std::fabs(m.driver_work_J) + std::fabs(m.film_dissipation_J);
    EXPECT_LT(std::fabs(m.energy_residual_J), 1e-5 * scale)
        << "W=" << m.driver_work_J << " dE=" << m.energy_change_J << " D=" << m.film_dissipation_J;
    const double t = r.stats.final_time_s;
    EXPECT_NEAR(m.film_dissipation_J / t, m.film_power_loss_W, 1e-3 * m.film_power_loss_W);
    // Without the effect the shear is measured, not applied: the driver does not supply it.
    // Not for the printed law: its F_t exceeds its own pressure field's by 1/(1 − ε²)
    // (paper NOTES), so the pressure part (c ε/2) F_t of its torques can return work.
    if (law == "pinkus_sternlicht") continue;
    EXPECT_GT(m.driver_work_J - r0.metrics.driver_work_J, 0.01 * m.driver_work_J);
    EXPECT_GT(r0.metrics.film_power_loss_W * t, 1.01 * r0.metrics.film_dissipation_J);
  }
}

TEST(SliderCrankLubricated, ReferenceCaseFromCentredJournalRunsWithoutNaN) {
  // The paper's initial state: ε = 0 exactly, ė = 0. Five cycles of every law.
  for (const std::string law : {"pinkus_sternlicht", "frene_long", "frene_short"}) {
    SCOPED_TRACE(law);
    json doc = load("slider_crank.json");
    doc["joints"][3]["force_law"] = law;
    doc["simulation"]["max_cycles"] = 5;
    const RunResult r = lub::run_scene(lub::parse_scene(doc));
    EXPECT_EQ(r.status, RunStatus::ok) << law << ": " << r.message;
    if (r.status != RunStatus::ok) continue;
    EXPECT_EQ(r.metrics.cycles_run, 5);
    const auto& eps = channel(r, "eps");
    EXPECT_EQ(eps.front(), 0.0);
    for (size_t c = 0; c < r.series.data.size(); ++c) {
      const auto& x = r.series.data[c];
      const auto bad = std::find_if(x.begin(), x.end(), [](double v) { return !std::isfinite(v); });
      EXPECT_TRUE(bad == x.end()) << law << " " << r.series.names[c] << "[" << (bad - x.begin()) << "]";
    }
    const auto wall = std::find_if(eps.begin(), eps.end(), [](double e) { return !(e < 1.0); });
    EXPECT_TRUE(wall == eps.end()) << law << ": eps[" << (wall - eps.begin()) << "] = " << *wall;
    EXPECT_GT(r.metrics.max_eps, 0.5) << law;  // the journal does move off-centre
    EXPECT_NEAR(r.metrics.min_film_thickness_m, 0.5e-3 * (1 - r.metrics.max_eps), 1e-12);
  }
}

}  // namespace

namespace {

TEST(Series, LastCyclesKeepsOnlyTheLastCompleteCycles) {
  json doc = load("slider_crank_ideal.json");
  doc["simulation"]["max_cycles"] = 3;
  doc["outputs"]["last_cycles"] = 1;
  const RunResult r = lub::run_scene(lub::parse_scene(doc));
  ASSERT_EQ(r.status, RunStatus::ok);
  const double T = 60.0 / 5000.0;
  const auto& t = channel(r, "t");
  EXPECT_NEAR(t.front(), 2 * T, 1e-12);
  EXPECT_NEAR(t.back(), 3 * T, 1e-12);
  for (const auto& ch : r.series.data) EXPECT_EQ(ch.size(), t.size());
}

TEST(Effects, AbsentEffectsAreNeverEvaluated) {
  // No gravity in the scene: the gravity term is never evaluated. All joints ideal: no
  // force law is ever called.
  json doc = load("slider_crank_ideal.json");
  doc.erase("effects");
  RunResult r = lub::run_scene(lub::parse_scene(doc));
  ASSERT_EQ(r.status, RunStatus::ok);
  EXPECT_GT(r.stats.model_evals, 100);
  EXPECT_EQ(r.stats.gravity_evals, 0);
  EXPECT_EQ(r.stats.film_law_evals, 0);
  // With gravity and a film: every evaluation adds both (a continuous law: one call per
  // evaluation; the printed law's switching film calls its law twice more where its
  // branch is continued across ε̇ = 0, mechanism/film_element.cpp film_element_force).
  json lub_doc = load("slider_crank.json");
  lub_doc["joints"][3]["force_law"] = "frene_long";
  lub_doc["simulation"]["max_cycles"] = 1;
  lub_doc["simulation"]["metric_cycles"] = 1;
  r = lub::run_scene(lub::parse_scene(lub_doc));
  ASSERT_EQ(r.status, RunStatus::ok);
  EXPECT_EQ(r.stats.gravity_evals, r.stats.model_evals);
  EXPECT_EQ(r.stats.film_law_evals, r.stats.model_evals);
}

}  // namespace
