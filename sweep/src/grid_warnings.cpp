// The plausibility warnings of a grid: each case's scene's (Scene::warnings, collected as the
// grid is expanded), each distinct warning once, with how many cases give it (lubsweep prints
// them once per grid and stores them in the study file).
#include <map>
#include <utility>

#include <fmt/format.h>

#include "grid_parts.hpp"

namespace lub::sweep::detail {

std::vector<std::string> distinct_warnings(const Grid& g, const std::vector<std::vector<std::string>>& per_case) {
  std::vector<std::string> order;                               // distinct warnings, first met first
  std::map<std::string, std::pair<std::size_t, std::size_t>> seen;  // warning -> (cases, first case id)
  for (std::size_t id = 0; id < per_case.size(); ++id)
    for (const std::string& w : per_case[id]) {
      auto [it, fresh] = seen.try_emplace(w, 0, id);
      if (fresh) order.push_back(w);
      ++it->second.first;
    }
  std::vector<std::string> out;
  for (const std::string& w : order) {
    const auto& [count, first] = seen.at(w);
    out.push_back(
        fmt::format("{}; in {} of {} cases (the first {})", w, count, g.cases.size(), g.cases.at(first).name));
  }
  return out;
}

}  // namespace lub::sweep::detail
