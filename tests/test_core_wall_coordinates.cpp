// Shooting's wall coordinates (core/src/run/wall_coordinates.hpp): the map onto the plane
// and back, its rates against differences of the map, and the chart built on them.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "lub/io/json_reader.hpp"
#include "lub/mechanism/film_element.hpp"
#include "lub/run/run.hpp"
#include "lub/scene/scene.hpp"
#include "run/period_map.hpp"
#include "run/segment.hpp"
#include "run/wall_coordinates.hpp"

namespace {

using Eigen::Vector2d;
using lub::detail::from_wall_coordinates;
using lub::detail::to_wall_coordinates;

// Eccentricity ratios on both sides of the series' switch (1e-2), mid-clearance, and near
// the wall, down to a gap of 1e-6 c (a tenth of the default film-collapse limit
// simulation.eps_limit = 1 − 1e-5).
const double kEps[] = {0.0, 1e-7, 9.9e-3, 1.01e-2, 0.3, 0.9, 0.999, 1.0 - 1e-6};

Vector2d direction(double angle) { return {std::cos(angle), std::sin(angle)}; }

TEST(WallCoordinates, RoundTripIsTheIdentity) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> angle(-M_PI, M_PI), rate(-50.0, 50.0);
  for (double eps : kEps) {
    for (int k = 0; k < 20; ++k) {
      const Vector2d u = eps * direction(angle(rng));
      const Vector2d u_dot(rate(rng), rate(rng));
      Vector2d w, w_dot, u2, u2_dot;
      to_wall_coordinates(u, u_dot, w, w_dot);
      ASSERT_TRUE(from_wall_coordinates(w, w_dot, u2, u2_dot));
      // The gap 1 − ε to the round-off of u itself (1e-16 absolute: 1e-10 of a gap of
      // 1e-6 c), the rates to their round-off times the stretch 1/(1 − ε²) that the way
      // out multiplies and the way back divides (a few 1e-16 / (1 − ε)).
      const double gap = 1.0 - eps;
      EXPECT_NEAR(1.0 - u2.norm(), gap, 4e-16 + 1e-12 * gap) << "eps " << eps;
      EXPECT_LE((u2 - u).norm(), 4e-16) << "eps " << eps;
      EXPECT_LE((u2_dot - u_dot).norm(), (1e-12 + 4e-16 / gap) * u_dot.norm()) << "eps " << eps;
    }
  }
}

TEST(WallCoordinates, RatesAreTheDerivativesOfTheMap) {
  // Along u(t) = (ε + a t)(cos(b t), sin(b t)) + (0, d t), ẇ against a central difference
  // of w(u(t)) at t = 0 (step 1e-6 of the gap: O(h²) truncation, ~1e-10 round-off).
  for (double eps : {1e-7, 9.9e-3, 1.01e-2, 0.3, 0.9, 0.999}) {
    const double a = 0.7, b = 1.3, d = -0.4;
    const double h = 1e-6 * std::max(1e-3, 1.0 - eps);
    auto u_at = [&](double t) { return Vector2d((eps + a * t) * direction(b * t) + Vector2d(0.0, d * t)); };
    const Vector2d u_dot = Vector2d(a, eps * b + d);
    Vector2d w, w_dot, wp, wm, ignore;
    to_wall_coordinates(u_at(0.0), u_dot, w, w_dot);
    to_wall_coordinates(u_at(h), u_dot, wp, ignore);
    to_wall_coordinates(u_at(-h), u_dot, wm, ignore);
    const Vector2d fd = (wp - wm) / (2.0 * h);
    EXPECT_LE((fd - w_dot).norm(), 1e-6 * w_dot.norm()) << "eps " << eps;
  }
}

TEST(WallCoordinates, NearTheWallAStepIsARelativeChangeOfTheGap) {
  // |w| = atanh ε ≈ ½ ln(2/(1 − ε)): equal steps in |w| are equal ratios of the gap.
  for (double gap : {1e-3, 1e-6, 1e-9}) {
    Vector2d w, w_dot, u, u_dot;
    to_wall_coordinates(Vector2d(1.0 - gap, 0.0), Vector2d::Zero(), w, w_dot);
    EXPECT_NEAR(w.x(), 0.5 * std::log(2.0 / gap), 1e-3 * w.x());
    ASSERT_TRUE(from_wall_coordinates(Vector2d(w.x() + 0.01, 0.0), Vector2d::Zero(), u, u_dot));
    EXPECT_NEAR((1.0 - u.x()) / gap, std::exp(-0.02), 1e-3);
  }
  // Every w is inside the clearance (|w| = 15: a gap of 2e-13 c), until tanh rounds to 1.
  Vector2d u, u_dot;
  EXPECT_TRUE(from_wall_coordinates(Vector2d(0.0, -15.0), Vector2d(3.0, 1.0), u, u_dot));
  EXPECT_LT(u.norm(), 1.0);
  EXPECT_FALSE(from_wall_coordinates(Vector2d(30.0, 0.0), Vector2d::Zero(), u, u_dot));
}

lub::Scene slider_crank() {
  nlohmann::json doc = lub::read_json_file(std::string(LUB_SOURCE_DIR) + "/configs/scenes/slider_crank.json");
  doc["solver"]["formulation"] = "partitioned";
  return lub::parse_scene(doc);
}

TEST(WallChart, ExpandsToTheEccentricityItWasGiven) {
  // The slider-crank at its initial state, then with the journal moved to ε = 1 − 1e-8 in
  // wall coordinates: the chart's state has that gap, consistent constraints, and reduces
  // back to the same w.
  const lub::Scene scene = slider_crank();
  lub::detail::RunModel rm(scene);
  lub::detail::StartState x;
  {
    lub::detail::SegmentOptions o;
    o.cycles = 1;
    o.series = false;
    x = lub::detail::run_segment(rm, o).end;
  }
  lub::detail::Chart chart(rm, x, lub::ShootingCoordinates::wall);
  ASSERT_TRUE(chart.wall());
  ASSERT_EQ(chart.size(), 4);
  const Eigen::VectorXd z0 = chart.reduce(x.qv);
  for (double gap : {0.5, 1e-3, 1e-5}) {
    Eigen::VectorXd z = z0;
    const double rho = std::atanh(1.0 - gap);
    z.head<2>() = rho * z0.head<2>().normalized();
    std::vector<double> qv = x.qv;
    ASSERT_TRUE(chart.expand(x.t, z.data(), qv)) << "gap " << gap;
    const lub::FilmKinematics fk = lub::film_kinematics(rm.model, 0, qv.data(), qv.data() + rm.model.nq);
    EXPECT_NEAR(1.0 - fk.state.eps, gap, 1e-6 * gap + 1e-11) << "gap " << gap;
    const Eigen::VectorXd back = chart.reduce(qv);
    // A position resolves ~1e-16 m, 2e-13 c: w to that over the gap, ẇ times the rate unit.
    const Eigen::VectorXd err = (back - z).cwiseAbs().cwiseQuotient(Eigen::Map<const Eigen::VectorXd>(chart.units().data(), 4));
    EXPECT_LE(err.maxCoeff(), 1e-10 / gap) << "gap " << gap;
  }
}

}  // namespace

namespace {

// The same periodic orbit found in both charts: Newton's unknowns change, the orbit and its
// multipliers (invariant under a change of coordinates) must not, beyond their error bars.
lub::RunResult shoot(const std::string& law, lub::ShootingCoordinates chart) {
  nlohmann::json doc = lub::read_json_file(std::string(LUB_SOURCE_DIR) + "/configs/scenes/slider_crank.json");
  doc["solver"]["formulation"] = "partitioned";
  doc["joints"][3]["force_law"] = law;
  doc["simulation"]["steady"] = "auto";
  doc["simulation"]["max_cycles"] = 40;
  doc["simulation"]["stop_when_steady"] = true;
  doc["simulation"]["shooting_coordinates"] = std::string(lub::name_of(chart));
  doc["outputs"]["channels"] = nlohmann::json::array();
  return lub::run_scene(lub::parse_scene(doc));
}

TEST(WallChart, FindsTheOrbitTheIndependentCoordinatesFind) {
  // The printed law (|μ|max ≈ 0.05) and Frêne long (≈ 0.998, a slowly turning pair) at the
  // reference case.
  for (const char* law : {"pinkus_sternlicht", "frene_long"}) {
    const lub::RunResult a = shoot(law, lub::ShootingCoordinates::independent);
    const lub::RunResult b = shoot(law, lub::ShootingCoordinates::wall);
    ASSERT_EQ(lub::classification(a), "periodic") << law << ": " << a.message;
    ASSERT_EQ(lub::classification(b), "periodic") << law << ": " << b.message;
    const double bar = a.metrics.min_film_thickness_m_error + b.metrics.min_film_thickness_m_error;
    // Both error bars, or the map's noise floor (1e-6 c accepted at the noise) over 1 − |μ|.
    const double mu = std::abs(a.steady.multipliers.front());
    const double floor = 1e-6 * 5e-4 / (1.0 - mu);
    EXPECT_NEAR(a.metrics.min_film_thickness_m, b.metrics.min_film_thickness_m, std::max(bar, floor)) << law;
    EXPECT_NEAR(std::abs(a.steady.multipliers.front()), std::abs(b.steady.multipliers.front()), 1e-3) << law;
  }
}

}  // namespace
