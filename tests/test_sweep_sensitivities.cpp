// A study's sensitivities (issue 44): each located orbit's steady metrics differentiated by
// every numeric axis of the grid (Grid::parameters, CaseResult::sensitivities), against
// central differences of the neighbouring cases' orbits, located separately at the axis
// value ± 1 % on the same grid line. The routes share nothing but the scene: one
// differentiates the period map at one orbit, the other runs each case's steady stage.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "lub/sweep/case_result.hpp"
#include "lub/sweep/grid.hpp"
#include "lub/sweep/transport.hpp"

namespace {

using namespace lub::sweep;
using lub::ResultField;

const std::string kScenes = std::string(LUB_SOURCE_DIR) + "/configs/scenes";

/// The paper's reference case on one axis: its value × 0.99, × 1, × 1.01.
Grid line(const std::string& axis, double value) {
  const std::string text = R"({"scene": "slider_crank.json", "set": {"/simulation/steady": "auto"},
      "study": {"channels": []},
      "axes": [{"name": ")" + axis + R"(", "values": [)" +
                           std::to_string(0.99 * value) + ", " + std::to_string(value) + ", " +
                           std::to_string(1.01 * value) + "]}]}";
  return parse_grid(text, kScenes, "line.json");
}

CaseResult run(const Grid& g, int id) {
  Task t;
  t.case_id = id;
  t.scene = g.cases.at(static_cast<std::size_t>(id)).scene;
  t.parameters = g.parameters;
  return run_task(t, 0);
}

std::size_t column(const std::vector<ResultField>& fields, const std::string& name) {
  for (std::size_t i = 0; i < fields.size(); ++i)
    if (fields[i].name == name) return i;
  ADD_FAILURE() << "no column " << name;
  return 0;
}

class AxisSensitivity : public testing::TestWithParam<std::pair<std::string, double>> {};

// d h_min / dλ and d F_max / dλ of the middle case against (m(λ+) − m(λ−)) / (λ+ − λ−) of
// its neighbours: within the sensitivity's error bar plus the difference's own truncation
// and the two orbits' error bars over the step, or 2 % (issue 44's bound), whichever is
// larger.
TEST_P(AxisSensitivity, AgreesWithCentralDifferencesOfItsNeighbours) {
  const auto& [axis, value] = GetParam();
  const Grid g = line(axis, value);
  ASSERT_EQ(g.parameters.size(), 1u);
  EXPECT_EQ(g.parameters[0].name, axis);
  const CaseResult lo = run(g, 0), mid = run(g, 1), hi = run(g, 2);
  for (const CaseResult* r : {&lo, &mid, &hi}) ASSERT_EQ(r->classification, CaseClass::periodic) << r->message;
  const auto sf = sensitivity_fields(g.parameters);
  ASSERT_EQ(mid.sensitivities.size(), sf.size());
  EXPECT_GT(mid.sensitivity_periods, 0);
  const auto rf = result_fields();
  const double step = g.cases[2].axis_values[0].get<double>() - g.cases[0].axis_values[0].get<double>();
  for (const std::string metric : {"min_film_thickness_m", "peak_reaction_N"}) {
    const std::size_t m = column(rf, metric), e = column(rf, metric + "_error");
    const double cd = (hi.values[m] - lo.values[m]) / step;
    const double cd_error = (hi.values[e] + lo.values[e]) / step;
    const std::size_t d = column(sf, "d_" + metric + "_per_" + axis);
    const double ift = mid.sensitivities[d], ift_error = mid.sensitivities[d + 1];
    ASSERT_TRUE(std::isfinite(ift)) << metric;
    EXPECT_NEAR(ift, cd, std::max(0.02 * std::abs(cd), ift_error + cd_error))
        << metric << " per " << axis << ": implicit function " << ift << " ± " << ift_error << ", central difference "
        << cd << " ± " << cd_error;
  }
  EXPECT_EQ(sf[column(sf, "d_min_film_thickness_m_per_" + axis)].unit,
            lub::derivative_unit("m", g.parameters[0].unit));
}

INSTANTIATE_TEST_SUITE_P(Axes, AxisSensitivity,
                         testing::Values(std::make_pair(std::string("viscosity_Pa_s"), 0.4),
                                         std::make_pair(std::string("clearance_m"), 5e-4),
                                         std::make_pair(std::string("speed_rpm"), 5000.0)),
                         [](const auto& i) { return i.param.first; });

// What is not a physical number of the scene is not differentiated: settings (solver,
// simulation), the force law, dimensionless counts; and a grid may turn them off.
TEST(StudySensitivities, OnlyPhysicalNumericAxes) {
  const Grid g = parse_grid(R"({"scene": "slider_crank.json",
      "axes": [{"name": "force_law", "values": ["frene_short", "frene_long"]},
               {"pointer": "/solver/rtol", "values": [1e-8, 1e-9]},
               {"name": "viscosity_Pa_s", "values": [0.4, 0.2]}]})",
                            kScenes, "g.json");
  ASSERT_EQ(g.parameters.size(), 1u);
  EXPECT_EQ(g.parameters[0].name, "viscosity_Pa_s");
  EXPECT_EQ(g.parameters[0].unit, "Pa s");
  const Grid off = parse_grid(R"({"scene": "slider_crank.json", "study": {"sensitivities": false},
      "axes": [{"name": "viscosity_Pa_s", "values": [0.4, 0.2]}]})",
                              kScenes, "g.json");
  EXPECT_TRUE(off.parameters.empty());
  // A case without a located orbit gets NaN sensitivities, not none.
  const Grid t = parse_grid(R"({"scene": "slider_crank.json", "study": {"max_cycles": 2, "channels": []},
      "axes": [{"name": "viscosity_Pa_s", "values": [0.4]}]})",
                            kScenes, "g.json");
  const CaseResult r = run(t, 0);
  ASSERT_FALSE(has_orbit(r.classification)) << r.classification.str();
  ASSERT_EQ(r.sensitivities.size(), sensitivity_fields(t.parameters).size());
  for (double v : r.sensitivities) EXPECT_TRUE(std::isnan(v));
}

}  // namespace
