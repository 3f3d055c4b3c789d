// The steady cycle found by shooting against a transient of thousands of cycles (label
// slow: `LUB_SLOW=1 bash tools/test.sh`; a few minutes): Frêne long at the reference case,
// the "not periodic" case of the paper, converges to the orbit shooting finds; and cells of
// the full factorial whose label the steady stage changed, each against a transient 10
// times tighter; and ten drifting cells, their drift law and safe-film cycle against
// transients at rtol 1e-10.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <ostream>
#include <string>
#include <vector>

#include "lub/run/run.hpp"
#include "lub/steady/drift_law.hpp"

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

// A full-factorial cell (configs/grids/full_factorial.json) whose label the steady stage
// changed: `not_converged` on e5ef3a1 (Newton stalled at the map's noise), now `label` on
// the default (joint) formulation with shooting in its coordinates (or, for a
// `not_converged` one, now with another reason). Three cells flip between drifting and
// not_converged with the step sequence (partitioned formulation; joint with the
// partitioned chart; joint with its own chart): Frene short 0.5 mm 400 cP 2500 rpm
// (drifting, drifting, not_converged), Frene long 0.05 mm 40 cP 5000 rpm (drifting,
// not_converged, drifting), Frene short 0.1 mm 100 cP 5000 rpm (not_converged, drifting,
// not_converged). Both labels are checked the same way: against a tight transient that
// settles on no orbit.
struct ChangedCell {
  const char* law;
  double clearance_m, viscosity_Pa_s, speed_rpm;
  const char* label;
};
// Its name in test listings (gtest prints a struct's bytes otherwise: its pointers, which
// change from run to run).
void PrintTo(const ChangedCell& c, std::ostream* os) {
  *os << c.law << ' ' << c.clearance_m << " m " << c.viscosity_Pa_s << " Pa s " << c.speed_rpm << " rpm: " << c.label;
}

json cell(const ChangedCell& c, const std::string& steady, double rtol, int max_cycles) {
  json doc = lub::read_json_file(std::string(LUB_SOURCE_DIR) + "/configs/scenes/slider_crank.json");
  doc["joints"][3]["force_law"] = c.law;
  doc["joints"][3]["journal_radius_m"] = 0.0100 - c.clearance_m;
  doc["joints"][3]["viscosity_Pa_s"] = c.viscosity_Pa_s;
  doc["drivers"][0]["speed_rpm"] = c.speed_rpm;
  doc["solver"]["rtol"] = rtol;
  doc["simulation"]["steady"] = steady;
  doc["simulation"]["max_cycles"] = max_cycles;
  doc["simulation"]["stop_when_steady"] = true;
  doc["simulation"]["error_bars"] = true;
  doc["outputs"]["channels"] = json::array();
  return doc;
}

class ChangedLabel : public testing::TestWithParam<ChangedCell> {};

TEST_P(ChangedLabel, AgreesWithATransientTenTimesTighter) {
  const ChangedCell& c = GetParam();
  const lub::RunResult a = lub::run_scene(lub::parse_scene(cell(c, "auto", 1e-8, 40)));
  ASSERT_EQ(a.status, lub::RunStatus::ok) << a.message;
  ASSERT_EQ(lub::classification(a), c.label) << a.message;
  // The transient at rtol/10, from rest, its stop confirmed by the period map.
  const lub::RunResult t = lub::run_scene(lub::parse_scene(cell(c, "transient", 1e-9, 1500)));
  std::printf("%s %g m %g Pa s %g rpm: %s (h_min %.5e ± %.1e m); transient at rtol 1e-9: %s after %zu cycles "
              "(h_min %.5e m): %s\n",
              c.law, c.clearance_m, c.viscosity_Pa_s, c.speed_rpm, c.label, a.metrics.min_film_thickness_m,
              a.metrics.min_film_thickness_m_error, lub::classification(t).c_str(), t.cycles.size(),
              t.cycles.empty() ? 0.0 : t.cycles.back().min_film_thickness_m, t.message.c_str());
  if (std::string(c.label) == "periodic") {
    // The orbit is where the tight transient settles: the same film within twice the summed
    // error bars. Each bar is a route's distance to its own solution 100 times tighter
    // (rtol 1e-10 and 1e-11), which differ too: the plain sum holds only if those coincide
    // (printed law, 0.05 mm: |Δh_min| 7.3618e-9 m against a sum of 7.3607e-9 m).
    ASSERT_EQ(lub::classification(t), "periodic") << t.message;
    EXPECT_NEAR(t.metrics.min_film_thickness_m, a.metrics.min_film_thickness_m,
                2 * (a.metrics.min_film_thickness_m_error + t.metrics.min_film_thickness_m_error));
    EXPECT_NEAR(t.metrics.max_eps, a.metrics.max_eps, 2 * (a.metrics.max_eps_error + t.metrics.max_eps_error));
  } else {
    // No orbit inside the clearance, or none located: the tight transient settles on none.
    EXPECT_NE(lub::classification(t), "periodic") << t.message;
  }
  if (a.steady.method == lub::SteadyCycleMethod::slow_flow && std::string(c.label) == "drifting") {
    // Followed along its slow manifold (at rtol/10): the transient at rtol 1e-9, cycle by
    // cycle to the cycle the flow got to, has the same film within 10 % (each jump's error
    // is held to 5 % of it: the flow's cycle count is good to ~5 %; measured 1.6-4.5 % on
    // the seven cells away from the wall), within 2e-2 c of it within 30 % (14 % measured).
    const int n = 40 + static_cast<int>(std::lround(a.steady.slow_flow_cycles)) + 1;
    json d = cell(c, "transient", 1e-9, n);
    d["simulation"]["stop_when_steady"] = false;
    d["simulation"]["error_bars"] = false;
    const lub::RunResult f = lub::run_scene(lub::parse_scene(d));
    ASSERT_EQ(f.status, lub::RunStatus::ok) << f.message;
    const double h = f.cycles.back().min_film_thickness_m;
    std::printf("  slow flow: h_min %.4e m about %d cycles from rest; the transient at rtol 1e-9 there: %.4e m\n",
                a.steady.last_cycle_min_film_m, n, h);
    if (h > 2e-2 * c.clearance_m) {
      EXPECT_NEAR(a.steady.last_cycle_min_film_m, h, 0.10 * h);
    } else {
      // Within 2e-2 c of the wall (the seven others have 0.035-0.18 c), when the journal gets somewhere depends on the tolerance
      // by any route (Frêne long at 0.5 mm, 400 cP, 50 rpm reaches eps_limit at cycle 121,
      // 179, 287 at rtol 1e-8, 1e-9, 1e-10; the flow at 169 and 293 with the scene at 1e-8
      // and 1e-9): the film within 30 % (Frêne long, 0.05 mm, 40 cP, 5000 rpm: 589 nm
      // against 687 nm at cycle 514).
      EXPECT_NEAR(a.steady.last_cycle_min_film_m, h, 0.30 * h);
    }
  }
}

INSTANTIATE_TEST_SUITE_P(
    FullFactorial, ChangedLabel,
    // Their labels since the slow flow (issue 25): the eight without an orbit are followed
    // along their slow manifolds, still moving thousands of cycles on.
    testing::Values(ChangedCell{"pinkus_sternlicht", 1e-4, 0.1, 5000, "periodic"},
                    ChangedCell{"pinkus_sternlicht", 5e-5, 0.4, 5000, "periodic"},
                    ChangedCell{"frene_short", 5e-4, 0.4, 2500, "drifting"},
                    ChangedCell{"frene_short", 2e-4, 0.2, 500, "drifting"},
                    ChangedCell{"frene_short", 1e-4, 0.2, 500, "drifting"},
                    ChangedCell{"frene_long", 5e-5, 0.04, 5000, "drifting"},
                    ChangedCell{"frene_short", 2e-4, 0.2, 5000, "drifting"},
                    ChangedCell{"frene_short", 1e-4, 0.2, 5000, "drifting"},
                    ChangedCell{"frene_short", 1e-4, 0.1, 5000, "drifting"},
                    ChangedCell{"frene_short", 1e-4, 0.1, 500, "drifting"}),
    [](const testing::TestParamInfo<ChangedCell>& i) { return std::to_string(i.index); });

}  // namespace

// Drifting cells of the full factorial (issue 43's three among them: Frêne short 0.5 mm and
// 0.2 mm at 400 cP, 5000 rpm; Frêne long 0.2 mm, 400 cP, 500 rpm): no orbit, their journal
// creeping toward the wall. What the steady stage says of each, against a transient from
// rest, cycle by cycle at rtol 1e-10 (the flow's own rtol / 10):
//  - the transient reaches the film the flow got to within 10 % of the flow's cycle count
//    (each jump's error is held to 5 % of it, one way, and the flow runs at rtol 1e-9);
//  - its own drift law over the same films (twice the last down to it, as the flow fits it)
//    has the flow's exponent, within their two error bars and 0.15 (the exponent's growth
//    toward the wall moves a fit by that much between the two routes' windows);
//  - where the flow gives a safe-film cycle, the transient crosses within its error bar.
struct DriftingCell {
  const char* law;
  double clearance_m, viscosity_Pa_s, speed_rpm;
};
void PrintTo(const DriftingCell& c, std::ostream* os) {
  *os << c.law << ' ' << c.clearance_m << " m " << c.viscosity_Pa_s << " Pa s " << c.speed_rpm << " rpm";
}

class Drifting : public testing::TestWithParam<DriftingCell> {};

/// The first cycle whose minimum film is at or below h (-1: none).
int first_at_or_below(const lub::RunResult& r, double h) {
  for (size_t k = 0; k < r.cycles.size(); ++k)
    if (r.cycles[k].min_film_thickness_m <= h) return static_cast<int>(k);
  return -1;
}

TEST_P(Drifting, ItsDriftLawAndSafeFilmCycleAgreeWithATightTransient) {
  const DriftingCell& c = GetParam();
  const ChangedCell as{c.law, c.clearance_m, c.viscosity_Pa_s, c.speed_rpm, "drifting"};
  json doc = cell(as, "auto", 1e-8, 40);
  // The full factorial's settings (configs/grids/full_factorial.json, "study"; error bars
  // on, the scene's default, which also tells a located orbit from a near-wall fixed
  // point of the map's error).
  doc["simulation"]["steady_tolerance"] = 1e-3;
  doc["simulation"]["metric_cycles"] = 2;
  const lub::RunResult a = lub::run_scene(lub::parse_scene(doc));
  ASSERT_EQ(lub::classification(a), "drifting") << a.message;
  ASSERT_TRUE(std::isfinite(a.steady.drift_exponent)) << a.message;
  const double h_end = a.steady.last_cycle_min_film_m;
  const double n_end = 40.0 + a.steady.slow_flow_cycles;
  const bool crossing = std::isfinite(a.steady.safe_film_cycle);
  const double until = std::max(1.3 * n_end, crossing ? a.steady.safe_film_cycle + a.steady.safe_film_cycle_error : 0.0);
  json t = cell(as, "transient", 1e-10, static_cast<int>(until) + 20);
  t["simulation"]["stop_when_steady"] = false;
  t["simulation"]["error_bars"] = false;
  t["solver"]["max_steps"] = 1000000000;
  const lub::RunResult tr = lub::run_scene(lub::parse_scene(t));
  ASSERT_TRUE(tr.status == lub::RunStatus::ok || tr.status == lub::RunStatus::film_collapse) << tr.message;
  const int seen = first_at_or_below(tr, h_end);
  ASSERT_GE(seen, 0) << "the transient did not reach " << h_end << " m by cycle " << tr.cycles.size();
  // The transient's law over the films from 2 h_end down to h_end: 12 cycles evenly spread.
  const int from = std::max(1, first_at_or_below(tr, 2.0 * h_end));
  std::vector<double> cycles, films;
  for (int k = 0; k < 12; ++k) {
    const int i = from + (k * (seen - from)) / 11;
    if (!cycles.empty() && i <= cycles.back()) continue;
    cycles.push_back(i);
    films.push_back(tr.cycles[static_cast<size_t>(i)].min_film_thickness_m);
  }
  const lub::steady::DriftLaw law = lub::steady::fit_drift_law(cycles, films);
  ASSERT_TRUE(law.known) << law.why;
  const double p_tr_error = 2.0 * std::sqrt(law.covariance(1, 1));
  std::printf("%s %g m %g Pa s %g rpm: flow %.3e m at cycle %.0f, p %.3f ± %.3f; transient there at cycle %d, "
              "p %.3f ± %.3f",
              c.law, c.clearance_m, c.viscosity_Pa_s, c.speed_rpm, h_end, n_end, a.steady.drift_exponent,
              a.steady.drift_exponent_error, seen, law.exponent, p_tr_error);
  EXPECT_NEAR(seen, n_end, 0.10 * n_end);
  EXPECT_NEAR(law.exponent, a.steady.drift_exponent, a.steady.drift_exponent_error + p_tr_error + 0.15);
  if (crossing) {
    const int safe = first_at_or_below(tr, a.metrics.safe_film_thickness_m);
    std::printf("; safe film at cycle %.0f ± %.0f, transient %d", a.steady.safe_film_cycle,
                a.steady.safe_film_cycle_error, safe);
    ASSERT_GE(safe, 0);
    EXPECT_NEAR(safe, a.steady.safe_film_cycle, a.steady.safe_film_cycle_error);
  }
  std::printf("\n");
}

INSTANTIATE_TEST_SUITE_P(
    FullFactorial, Drifting,
    testing::Values(DriftingCell{"frene_short", 0.0005, 0.4, 5000.0}, DriftingCell{"frene_short", 0.0002, 0.4, 5000.0},
                    DriftingCell{"frene_long", 0.0002, 0.4, 500.0}, DriftingCell{"frene_short", 0.0005, 0.4, 500.0},
                    DriftingCell{"frene_short", 0.0005, 0.2, 50.0}, DriftingCell{"frene_short", 0.0002, 0.04, 50.0},
                    DriftingCell{"frene_short", 0.0001, 0.1, 500.0}, DriftingCell{"frene_long", 0.0001, 0.2, 2500.0},
                    DriftingCell{"frene_long", 0.00005, 0.2, 5000.0}, DriftingCell{"frene_long", 0.0001, 0.4, 50.0}));
