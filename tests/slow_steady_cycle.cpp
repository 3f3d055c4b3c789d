// The steady cycle found by shooting against a transient of thousands of cycles (label
// slow: `LUB_SLOW=1 bash tools/test.sh`; about a minute): Frêne long at the reference case,
// the "not periodic" case of the paper, converges to the orbit shooting finds.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <string>

#include "lub/run/run.hpp"

namespace {

using nlohmann::json;

json frene_long(const std::string& steady, int cycles) {
  json doc = lub::read_json_file(std::string(LUB_SOURCE_DIR) + "/configs/scenes/slider_crank.json");
  doc["joints"][3]["force_law"] = "frene_long";
  doc["simulation"]["steady"] = steady;
  doc["simulation"]["max_cycles"] = cycles;
  doc["outputs"]["channels"] = json::array();
  return doc;
}

TEST(SlowSteadyCycle, FreneLongLongTransientEndsOnTheShootingOrbit) {
  const lub::RunResult s = lub::run_scene(lub::parse_scene(frene_long("shooting", 40)));
  ASSERT_EQ(lub::classification(s), "periodic") << s.message;
  json t = frene_long("transient", 3000);
  t["solver"]["rtol"] = 1e-10;
  const lub::RunResult tr = lub::run_scene(lub::parse_scene(t));
  ASSERT_EQ(tr.status, lub::RunStatus::ok) << tr.message;
  // The transient still turns about the cycle after 3000 cycles (|μ| ≈ 0.998 a cycle):
  // its per-cycle h_min oscillates; the band of its last 50 cycles is how far it is.
  double lo = 1.0, hi = 0.0;
  for (size_t k = tr.cycles.size() - 50; k < tr.cycles.size(); ++k)
    lo = std::min(lo, tr.cycles[k].min_film_thickness_m), hi = std::max(hi, tr.cycles[k].min_film_thickness_m);
  const double h = s.metrics.min_film_thickness_m;
  const double err = s.metrics.min_film_thickness_m_error;
  std::printf("shooting h_min %.6e ± %.2e m (%lld periods); transient 3000 cycles, last 50: [%.6e, %.6e] m\n", h, err,
              s.steady.periods_integrated, lo, hi);
  EXPECT_GE(h + err, lo - (hi - lo)) << "band [" << lo << ", " << hi << "] m, shooting " << h << " ± " << err;
  EXPECT_LE(h - err, hi + (hi - lo)) << "band [" << lo << ", " << hi << "] m, shooting " << h << " ± " << err;
  EXPECT_LT(hi - lo, 0.05 * h);  // the transient is close: a band of a few % of the film
}

}  // namespace
