// Sensitivities of a located orbit's steady metrics (lub/run/run.hpp, steady_sensitivities):
// the implicit-function route, dz*/dλ = (I − M)⁻¹ ∂P/∂λ and each metric measured on the
// predicted orbits, against central differences of orbits located separately at λ(1 ± 1 %)
// (issue 44's check). The two routes share nothing but the scene: one differentiates the
// period map at one orbit, the other runs each case's steady stage from its own transient.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>

#include "lub/run/orbit.hpp"
#include "lub/run/run.hpp"

namespace {

using nlohmann::json;

json paper_case() {
  json doc = lub::read_json_file(std::string(LUB_SOURCE_DIR) + "/configs/scenes/slider_crank.json");
  doc["simulation"]["steady"] = "auto";
  doc["outputs"]["channels"] = json::array();
  return doc;
}

lub::SensitivityParameter parameter(const json& doc, const std::string& pointer, const std::string& unit) {
  lub::SensitivityParameter p;
  p.name = pointer;
  p.unit = unit;
  p.value = doc.at(json::json_pointer(pointer)).get<double>();
  p.scene_at = [doc, pointer](double v) {
    json d = doc;
    d[json::json_pointer(pointer)] = v;
    return lub::parse_scene(d);
  };
  return p;
}

lub::RunResult run_at(const json& doc, const std::string& pointer, double v) {
  json d = doc;
  d[json::json_pointer(pointer)] = v;
  return lub::run_scene(lub::parse_scene(d));
}

// The paper's reference case (printed law, 0.5 mm, 400 cP, 5000 rpm): a well-conditioned
// orbit. Bound: the two routes' error bars added (the differences' bars are the separate
// orbits' metric bars over the step) plus 2 % of the difference, the rule.
TEST(Sensitivity, AgreesWithCentralDifferencesOfSeparatelyLocatedOrbits) {
  const json doc = paper_case();
  const lub::Scene scene = lub::parse_scene(doc);
  const lub::RunResult r = lub::run_scene(scene);
  ASSERT_EQ(r.status, lub::RunStatus::ok) << r.message;
  ASSERT_TRUE(lub::has_orbit(r.steady.kind)) << r.message;
  // The central differences' step: 1 % of the value; of the clearance for the bearing radius
  // (1 % of the radius would change the clearance by 20 %, far outside the linear range).
  const struct {
    const char* pointer;
    const char* unit;
    double step;
  } cases[] = {{"/joints/3/viscosity_Pa_s", "Pa s", 0.01},
               {"/drivers/0/speed_rpm", "rpm", 0.01},
               {"/joints/3/bearing_radius_m", "m", 0.0005}};
  for (const auto& [pointer, unit, step] : cases) {
    SCOPED_TRACE(pointer);
    const lub::SensitivityParameter p = parameter(doc, pointer, unit);
    const std::vector<lub::Sensitivity> s = lub::steady_sensitivities(r, {p});
    ASSERT_EQ(s.size(), 1u);
    ASSERT_TRUE(s[0].ok) << s[0].message;
    EXPECT_LT(s[0].periods, 20);  // 2 maps and 2 measurements of 2 cycles, twice
    const double h = step * p.value;
    const lub::RunResult plus = run_at(doc, pointer, p.value + h), minus = run_at(doc, pointer, p.value - h);
    ASSERT_TRUE(lub::has_orbit(plus.steady.kind) && lub::has_orbit(minus.steady.kind));
    const auto& metrics = lub::steady_metrics();
    for (std::size_t i = 0; i < metrics.size(); ++i) {
      const lub::SteadyMetric& m = metrics[i];
      const double a = plus.metrics.*m.value, b = minus.metrics.*m.value;
      if (!std::isfinite(a) || !std::isfinite(b)) continue;  // not measured (peak pressure)
      const double cd = (m.angle ? std::remainder(a - b, 2.0 * M_PI) : a - b) / (2.0 * h);
      const double cd_error = (plus.metrics.*m.error + minus.metrics.*m.error) / (2.0 * h);
      const double bound = s[0].d_metric_error[i] + cd_error + 0.02 * std::abs(cd);
      std::printf("[ measured ] %s: d %s = %.6g ± %.2g (IFT), %.6g ± %.2g (central differences)\n", pointer,
                  m.name, s[0].d_metric[i], s[0].d_metric_error[i], cd, cd_error);
      EXPECT_NEAR(s[0].d_metric[i], cd, bound) << m.name;
    }
  }
}

// A second, exact route: the printed (long-bearing) law's force is μ L times a function of the
// film's state, and nothing else in the mechanism depends on μ or L, so the orbit and every
// metric depend on the product μ L alone: L ∂m/∂L = μ ∂m/∂μ. Bound: the two error bars, and
// 1e-4 of the value for what the bars do not see (the maps' noise at rtol/100 over the step).
TEST(Sensitivity, ThePrintedLawsMetricsDependOnViscosityTimesLength) {
  const json doc = paper_case();
  const lub::Scene scene = lub::parse_scene(doc);
  const lub::RunResult r = lub::run_scene(scene);
  ASSERT_TRUE(lub::has_orbit(r.steady.kind)) << r.message;
  const auto s = lub::steady_sensitivities(
      r, {parameter(doc, "/joints/3/viscosity_Pa_s", "Pa s"), parameter(doc, "/joints/3/length_m", "m")});
  ASSERT_TRUE(s[0].ok && s[1].ok) << s[0].message << s[1].message;
  const auto& metrics = lub::steady_metrics();
  for (std::size_t i = 0; i < metrics.size(); ++i) {
    const double mu = s[0].value * s[0].d_metric[i], len = s[1].value * s[1].d_metric[i];
    if (!std::isfinite(mu)) continue;
    const double bound =
        s[0].value * s[0].d_metric_error[i] + s[1].value * s[1].d_metric_error[i] + 1e-4 * std::abs(mu);
    EXPECT_NEAR(mu, len, bound) << metrics[i].name;
  }
}

// The error bar, half the difference of the two one-sided differences (theory page): for a
// smooth metric it is the step's truncation, h |m''|/2, of order δ = 1e-3 of the slope (bound
// 1e-2: m'' on the scale of m'/λ); for the crank angle of the minimum film, a flat minimum
// whose place jumps within the step, it is as large as the value (bound: half of it). The
// orbit's own measurement (the metric cycles) is shared: the second parameter does not pay it.
TEST(Sensitivity, ItsErrorBarIsTheTruncationForASmoothMetricAndTheJumpAtAKink) {
  const json doc = paper_case();
  const lub::RunResult r = lub::run_scene(lub::parse_scene(doc));
  ASSERT_TRUE(lub::has_orbit(r.steady.kind)) << r.message;
  const auto s = lub::steady_sensitivities(
      r, {parameter(doc, "/joints/3/viscosity_Pa_s", "Pa s"), parameter(doc, "/drivers/0/speed_rpm", "rpm")});
  ASSERT_TRUE(s[0].ok && s[1].ok) << s[0].message << s[1].message;
  const auto& metrics = lub::steady_metrics();
  for (std::size_t i = 0; i < metrics.size(); ++i) {
    const std::string name = metrics[i].name;
    if (name == "min_film_thickness_m" || name == "max_eps" || name == "peak_reaction_N") {
      EXPECT_GT(s[0].d_metric_error[i], 0.0) << name;
      EXPECT_LT(s[0].d_metric_error[i], 1e-2 * std::abs(s[0].d_metric[i])) << name;
    }
    if (name == "crank_angle_at_min_film_rad") {
      EXPECT_GT(s[0].d_metric_error[i], 0.5 * std::abs(s[0].d_metric[i])) << name;
    }
  }
  EXPECT_EQ(s[0].periods - s[1].periods, static_cast<long long>(lub::parse_scene(doc).simulation.metric_cycles));
}

TEST(Sensitivity, ARunWithoutAnOrbitSaysSo) {
  json doc = paper_case();
  doc["simulation"]["steady"] = "transient";
  doc["simulation"]["max_cycles"] = 3;
  doc["simulation"]["metric_cycles"] = 1;
  const lub::Scene scene = lub::parse_scene(doc);
  const lub::RunResult r = lub::run_scene(scene);
  const auto s = lub::steady_sensitivities(r, {parameter(doc, "/joints/3/viscosity_Pa_s", "Pa s")});
  ASSERT_EQ(s.size(), 1u);
  EXPECT_FALSE(s[0].ok);
  EXPECT_NE(s[0].message.find("no located orbit"), std::string::npos) << s[0].message;
  EXPECT_TRUE(std::isnan(s[0].d_metric[0]));
}

}  // namespace
