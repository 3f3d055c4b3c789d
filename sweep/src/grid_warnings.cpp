// The plausibility warnings of a grid: each case's scene's (Scene::warnings), each distinct
// warning once, with how many cases give it (lubsweep prints them once per grid).
#include <map>
#include <nlohmann/json.hpp>

#include "lub/scene/scene.hpp"
#include "lub/sweep/grid.hpp"

namespace lub::sweep {

std::vector<std::string> grid_warnings(const Grid& grid) {
  std::vector<std::string> order;                            // distinct warnings, first met first
  std::map<std::string, std::pair<std::size_t, int>> seen;   // warning -> (cases, first case id)
  for (const Case& c : grid.cases)
    for (const std::string& w : parse_scene(nlohmann::json::parse(c.scene)).warnings) {
      auto [it, fresh] = seen.try_emplace(w, 0, c.id);
      if (fresh) order.push_back(w);
      ++it->second.first;
    }
  std::vector<std::string> out;
  for (const std::string& w : order) {
    const auto& [count, first] = seen.at(w);
    out.push_back(w + "; in " + std::to_string(count) + " of " + std::to_string(grid.cases.size()) +
                  " cases (the first " + grid.cases.at(static_cast<std::size_t>(first)).name + ")");
  }
  return out;
}

}  // namespace lub::sweep
