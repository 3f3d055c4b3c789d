// Plausibility warnings of a scene (the ranges of lub/bearing/plausibility.hpp applied to its
// joints and drivers) and its validity notes (lub/bearing/law_validity.hpp), each named by its
// JSON Pointer (the form --set takes).
#include "lub/bearing/plausibility.hpp"

#include <cmath>

#include "lub/bearing/law_validity.hpp"
#include "lub/common/constants.hpp"
#include "lub/scene/scene.hpp"

namespace lub {

std::vector<std::string> plausibility_warnings(const Scene& scene) {
  std::vector<std::string> out;
  const auto add = [&out](std::optional<std::string> w) {
    if (w) out.push_back(std::move(*w));
  };
  for (std::size_t i = 0; i < scene.joints.size(); ++i) {
    const JointSpec& s = scene.joints[i];
    if (s.type != JointType::lubricated_revolute || s.ideal) continue;  // an ideal joint has no film
    const std::string at = "/joints/" + std::to_string(i);
    add(implausible_viscosity(at + "/viscosity_Pa_s", s.viscosity_Pa_s));
    add(implausible_clearance_ratio(at + ": (bearing_radius_m − journal_radius_m) / journal_radius_m",
                                    s.bearing.clearance_m(), s.bearing.journal_radius_m));
  }
  for (std::size_t i = 0; i < scene.drivers.size(); ++i)
    add(implausible_speed_rpm("/drivers/" + std::to_string(i) + "/speed_rpm",
                              scene.drivers[i].speed_rad_s * 60.0 / (2.0 * kPi)));
  return out;
}

std::vector<std::string> validity_notes(const Scene& scene) {
  std::vector<std::string> out;
  for (std::size_t i = 0; i < scene.joints.size(); ++i) {
    const JointSpec& s = scene.joints[i];
    if (s.type != JointType::lubricated_revolute || s.ideal) continue;
    if (auto n = geometry_validity_note("/joints/" + std::to_string(i) + "/force_law", s.law, s.bearing))
      out.push_back(std::move(*n));
  }
  return out;
}

}  // namespace lub
