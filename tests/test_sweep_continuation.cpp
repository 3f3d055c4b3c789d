// The continuation tree of a study (lub/sweep/continuation_tree.hpp): fixed by the grid
// alone, it reaches every continued cell of a force law from that law's thickest-film
// cell, through lattice neighbours only, and never across a force law.
#include "lub/sweep/continuation_tree.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <set>
#include <string>
#include <tuple>

#include <nlohmann/json.hpp>

#include "lub/scene/scene.hpp"
#include "lub/sweep/grid.hpp"

namespace {

using lub::sweep::Grid;
using nlohmann::json;

const std::string kScenes = std::string(LUB_SOURCE_DIR) + "/configs/scenes";

Grid grid(const std::string& steady) {
  const json g = {
      {"scene", "slider_crank.json"},
      {"joint", "rod_slider"},
      {"driver", "crank_speed"},
      {"set", {{"/simulation/steady", steady}, {"/simulation/max_cycles", 40}}},
      {"axes",
       {{{"name", "clearance_m"}, {"values", {0.0005, 0.0002, 0.0001}}},
        {{"name", "viscosity_Pa_s"}, {"values", {0.4, 0.1}}},
        {{"name", "speed_rpm"}, {"values", {5000, 500, 50}}},
        {{"name", "force_law"}, {"values", {"pinkus_sternlicht", "frene_long"}}}}}};
  return lub::sweep::parse_grid(g.dump(), kScenes, "test.json");
}

/// The number of numeric axes on which two cases differ, and by how many steps in all.
int lattice_steps(const Grid& g, int a, int b) {
  int steps = 0;
  for (std::size_t k = 0; k < g.axes.size(); ++k) {
    const json& x = g.cases[static_cast<std::size_t>(a)].axis_values[k];
    const json& y = g.cases[static_cast<std::size_t>(b)].axis_values[k];
    if (x == y) continue;
    if (!x.is_number()) return 1000;  // across a force law
    std::vector<double> levels;
    for (const auto& c : g.cases) levels.push_back(c.axis_values[k].get<double>());
    std::sort(levels.begin(), levels.end());
    levels.erase(std::unique(levels.begin(), levels.end()), levels.end());
    const auto at = [&](double v) { return std::lower_bound(levels.begin(), levels.end(), v) - levels.begin(); };
    steps += static_cast<int>(std::abs(at(x.get<double>()) - at(y.get<double>())));
  }
  return steps;
}

/// Lattice neighbours by the definition, pair by pair: equal on every axis but one numeric
/// axis, both set there, their values consecutive in its sorted distinct values.
std::set<std::tuple<int, int, int>> brute_force_neighbours(const Grid& g) {
  std::set<std::tuple<int, int, int>> out;
  const auto value = [&](int c, std::size_t k) -> const json& { return g.cases[static_cast<std::size_t>(c)].axis_values[k]; };
  for (const auto& a : g.cases)
    for (const auto& b : g.cases) {
      if (a.id >= b.id) continue;
      std::vector<std::size_t> differ;
      for (std::size_t k = 0; k < g.axes.size(); ++k)
        if (value(a.id, k) != value(b.id, k)) differ.push_back(k);
      if (differ.size() != 1) continue;
      const std::size_t k = differ[0];
      if (!g.axes[k].numeric || !value(a.id, k).is_number() || !value(b.id, k).is_number()) continue;
      std::set<double> levels;
      for (const auto& c : g.cases)
        if (c.axis_values[k].is_number()) levels.insert(c.axis_values[k].get<double>());
      const double x = value(a.id, k).get<double>(), y = value(b.id, k).get<double>();
      const auto between = std::distance(levels.find(std::min(x, y)), levels.find(std::max(x, y)));
      if (between == 1) out.insert({x < y ? a.id : b.id, x < y ? b.id : a.id, static_cast<int>(k)});
    }
  return out;
}

// The lattice the study file writes (/lattice) and lubjoint.bifurcations reads: every
// pair of neighbours by the definition, once, the lower value first, in case-id order.
TEST(ContinuationTree, TheLatticeOfAFullFactorialEqualsThePairwiseDefinition) {
  const json spec = {
      {"scene", "slider_crank.json"},
      {"joint", "rod_slider"},
      {"driver", "crank_speed"},
      {"grids",
       {{{"name", "ff"},
         {"axes",
          {{{"name", "clearance_m"}, {"values", {0.0002, 0.00005, 0.0001}}},
           {{"name", "viscosity_Pa_s"}, {"values", {0.4, 0.04}}},
           {{"name", "speed_rpm"}, {"values", {5000, 50, 500}}},
           {{"name", "force_law"}, {"values", {"pinkus_sternlicht", "frene_long"}}}}}},
        {{"name", "ideal"},
         {"axes", {{{"name", "force_law"}, {"values", {"ideal"}}}, {{"name", "speed_rpm"}, {"values", {500, 5000}}}}}}}}};
  const Grid g = lub::sweep::parse_grid(spec.dump(), kScenes, "test.json");
  const std::vector<lub::sweep::LatticeEdge> edges = lub::sweep::lattice_edges(g);
  std::set<std::tuple<int, int, int>> got;
  for (const auto& e : edges) got.insert({e.lower, e.upper, e.axis});
  EXPECT_EQ(got.size(), edges.size()) << "each edge once";
  EXPECT_EQ(got, brute_force_neighbours(g));
  // 2 laws x (2*2*3 + 3*1*3 + 3*2*2) + the ideal pair along the speed.
  EXPECT_EQ(edges.size(), 2u * (12 + 9 + 12) + 1);
  for (std::size_t i = 1; i < edges.size(); ++i)
    EXPECT_TRUE(std::tie(edges[i - 1].lower, edges[i - 1].axis) < std::tie(edges[i].lower, edges[i].axis)) << i;
}

TEST(ContinuationTree, SpansEachForceLawFromItsThickestFilmThroughNeighbours) {
  const Grid g = grid("continuation");
  ASSERT_EQ(g.cases.size(), 36u);
  const std::vector<int> parent = lub::sweep::continuation_parents(g);
  int seeds = 0;
  for (const auto& c : g.cases) {
    const int p = parent[static_cast<std::size_t>(c.id)];
    if (p < 0) {
      ++seeds;
      // The seed: smallest clearance, largest viscosity and speed (μ ω / c² largest).
      EXPECT_EQ(c.axis_values[0], 0.0001);
      EXPECT_EQ(c.axis_values[1], 0.4);
      EXPECT_EQ(c.axis_values[2], 5000);
      continue;
    }
    EXPECT_EQ(lattice_steps(g, c.id, p), 1) << c.label << " from " << g.cases[static_cast<std::size_t>(p)].label;
    // Every cell reaches its seed: no cycle.
    int hops = 0;
    for (int q = p; q >= 0 && hops < 100; q = parent[static_cast<std::size_t>(q)]) ++hops;
    EXPECT_LT(hops, 100);
    EXPECT_LE(hops, 2 + 1 + 2) << "a breadth-first tree: as many hops as lattice steps from the seed";
  }
  EXPECT_EQ(seeds, 2) << "one seed per force law";
  // Fixed by the grid: the same tree every time.
  EXPECT_EQ(lub::sweep::continuation_parents(g), parent);
}

TEST(ContinuationTree, CasesThatDoNotAskForContinuationHaveNoParent) {
  const Grid g = grid("auto");
  for (int p : lub::sweep::continuation_parents(g)) EXPECT_EQ(p, -1);
}

// The tree asks each case's parsed scene whether it continues (Case::steady, read where the
// case is built), whichever way the grid says it: here an axis over simulation.steady,
// continuation for half the cases. Only those are linked, and only to each other.
TEST(ContinuationTree, AsksEachCasesParsedScene) {
  json g = {{"scene", "slider_crank.json"},
            {"set", {{"/simulation/max_cycles", 40}}},
            {"axes",
             {{{"name", "clearance_m"}, {"values", {0.0005, 0.0002, 0.0001}}},
              {{"pointer", "/simulation/steady"}, {"name", "steady_method"}, {"values", {"auto", "continuation"}}}}}};
  const Grid grid = lub::sweep::parse_grid(g.dump(), kScenes, "test.json");
  ASSERT_EQ(grid.cases.size(), 6u);
  for (const auto& c : grid.cases)
    EXPECT_EQ(c.steady, lub::parse_scene(json::parse(c.scene)).simulation.steady) << c.label;
  const std::vector<int> parent = lub::sweep::continuation_parents(grid);
  int linked = 0;
  for (const auto& c : grid.cases) {
    const int p = parent[static_cast<std::size_t>(c.id)];
    if (c.steady != lub::SteadyMethod::continuation) {
      EXPECT_EQ(p, -1) << c.label;
      continue;
    }
    if (p < 0) continue;  // the seed
    ++linked;
    EXPECT_EQ(grid.cases[static_cast<std::size_t>(p)].steady, lub::SteadyMethod::continuation) << c.label;
  }
  EXPECT_EQ(linked, 2) << "three continued cells: a seed and two children";
}

}  // namespace
