#include "lub/sweep/continuation_tree.hpp"

#include <algorithm>
#include <cmath>
#include <deque>
#include <limits>
#include <map>
#include <string>

#include <nlohmann/json.hpp>

namespace lub::sweep {

namespace {

using nlohmann::json;

bool continues(const Case& c) { return c.steady == SteadyMethod::continuation; }

/// How an axis moves the Sommerfeld number μ ω (R/c)²: its exponent (0: unknown).
double sommerfeld_exponent(const Axis& a) {
  switch (a.kind) {
    case AxisKind::viscosity_Pa_s: return 1.0;
    case AxisKind::speed_rpm: return 1.0;
    case AxisKind::clearance_m: return -2.0;
    default: return 0.0;
  }
}

struct Lattice {
  std::vector<std::vector<double>> levels;  // per axis: its sorted numeric values (empty: not numeric)
  std::vector<std::string> component;       // per case: its non-numeric values
  std::vector<std::vector<int>> index;      // per case: its level on each numeric axis (-1: none)
  std::map<std::pair<std::string, std::vector<int>>, int> at;  // (component, index) -> case
};

Lattice lattice_of(const Grid& g, const std::vector<bool>& in) {
  Lattice l;
  const std::size_t na = g.axes.size();
  l.levels.resize(na);
  for (std::size_t k = 0; k < na; ++k) {
    if (!g.axes[k].numeric) continue;
    for (const Case& c : g.cases)
      if (in[static_cast<std::size_t>(c.id)] && c.axis_values[k].is_number())
        l.levels[k].push_back(c.axis_values[k].get<double>());
    std::sort(l.levels[k].begin(), l.levels[k].end());
    l.levels[k].erase(std::unique(l.levels[k].begin(), l.levels[k].end()), l.levels[k].end());
  }
  for (const Case& c : g.cases) {
    std::string comp;
    std::vector<int> idx(na, -1);
    for (std::size_t k = 0; k < na; ++k) {
      const json& v = c.axis_values[k];
      if (g.axes[k].numeric && v.is_number()) {
        const auto& lv = l.levels[k];
        idx[k] = static_cast<int>(std::lower_bound(lv.begin(), lv.end(), v.get<double>()) - lv.begin());
      } else {
        comp += v.dump() + "\x1f";
      }
    }
    l.component.push_back(comp);
    l.index.push_back(idx);
    if (in[static_cast<std::size_t>(c.id)]) l.at.emplace(std::make_pair(comp, idx), c.id);
  }
  return l;
}

/// The case one level `dir` (±1) from case `c` along axis `k` in the same component, or -1.
int neighbour(const Lattice& l, int c, std::size_t k, int dir) {
  std::vector<int> idx = l.index[static_cast<std::size_t>(c)];
  if (idx[k] < 0) return -1;
  idx[k] += dir;
  const auto it = l.at.find({l.component[static_cast<std::size_t>(c)], idx});
  return it == l.at.end() ? -1 : it->second;
}

double sommerfeld_score(const Grid& g, const Case& c) {
  double s = 0.0;
  for (std::size_t k = 0; k < g.axes.size(); ++k) {
    const json& v = c.axis_values[k];
    if (v.is_number() && v.get<double>() > 0.0) s += sommerfeld_exponent(g.axes[k]) * std::log(v.get<double>());
  }
  return s;
}

}  // namespace

std::vector<LatticeEdge> lattice_edges(const Grid& g) {
  const Lattice l = lattice_of(g, std::vector<bool>(g.cases.size(), true));
  std::vector<LatticeEdge> edges;
  for (const Case& c : g.cases)
    for (std::size_t k = 0; k < g.axes.size(); ++k)
      if (const int up = neighbour(l, c.id, k, +1); up >= 0) edges.push_back({c.id, up, static_cast<int>(k)});
  return edges;
}

std::vector<int> continuation_parents(const Grid& g) {
  const std::size_t n = g.cases.size();
  std::vector<int> parent(n, -1);
  std::vector<bool> in(n, false);
  for (const Case& c : g.cases) in[static_cast<std::size_t>(c.id)] = continues(c);
  const Lattice l = lattice_of(g, in);
  // Seeds in order of their film's thickness, thickest first (ties: the lower case id).
  std::vector<int> order;
  for (const Case& c : g.cases)
    if (in[static_cast<std::size_t>(c.id)]) order.push_back(c.id);
  std::stable_sort(order.begin(), order.end(), [&](int a, int b) {
    return sommerfeld_score(g, g.cases[static_cast<std::size_t>(a)]) >
           sommerfeld_score(g, g.cases[static_cast<std::size_t>(b)]);
  });
  std::vector<bool> reached(n, false);
  for (int seed : order) {
    if (reached[static_cast<std::size_t>(seed)]) continue;
    reached[static_cast<std::size_t>(seed)] = true;
    std::deque<int> front{seed};
    while (!front.empty()) {
      const int c = front.front();
      front.pop_front();
      for (std::size_t k = 0; k < g.axes.size(); ++k) {
        for (int dir : {-1, +1}) {
          const int next = neighbour(l, c, k, dir);
          if (next < 0 || reached[static_cast<std::size_t>(next)]) continue;
          reached[static_cast<std::size_t>(next)] = true;
          parent[static_cast<std::size_t>(next)] = c;
          front.push_back(next);
        }
      }
    }
  }
  return parent;
}

}  // namespace lub::sweep
