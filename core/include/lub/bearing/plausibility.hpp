// Plausible ranges of a bearing's and a mechanism's inputs, written once for their readers:
// the scene (core/src/scene/plausibility.cpp), lubbearing (core/apps/lubbearing.cpp) and,
// through the scene, lubsweep and the Python module.
//
// A value outside its range is valid input (the rules of bearing_inputs.hpp accept it) but
// most likely a unit slip: a viscosity in cP given as Pa s (400 for 0.4), a length in mm given
// as m, a speed in deg/s given as rpm. It is a warning, not an error: the programs print it
// once and store it (the root attribute `warnings` of the run or study file), and refuse the
// input under --strict. Each warning is one line naming the field, the value, the range and
// the likely slip:
//   /joints/3/viscosity_Pa_s = 400 Pa s is outside the plausible 1e-4 – 5 Pa s (400 cP is 0.4 Pa s)
// docs/reference/plausible-ranges.md; configs/scene.schema.json.
#pragma once

#include <cmath>
#include <cstdio>
#include <optional>
#include <string>

#include "lub/common/constants.hpp"

namespace lub {

/// A closed range [min, max] of plausible values.
struct PlausibleRange {
  double min;
  double max;
  bool contains(double v) const { return v >= min && v <= max; }
};

/// Dynamic viscosity [Pa s]: from a thin oil or water (1 cP = 1e-3 Pa s) down to 0.1 cP, up
/// to a heavy gear oil at room temperature (5 Pa s). Above: cP or mPa s given as Pa s;
/// below: a kinematic viscosity in m^2/s given as Pa s.
inline constexpr PlausibleRange kPlausibleViscosityPaS{1e-4, 5.0};
inline constexpr const char* kPlausibleViscosityText = "1e-4 – 5 Pa s";
/// Radial clearance over journal radius c/R: 1e-4 to 0.3. Running bearings have ~1e-3; the
/// paper's worn joint 0.053 (0.5 mm on 9.5 mm), the shipped extreme configs/scenes/hard/
/// clearance_2mm.json 0.25. Above: a length in mm given as m, or a diameter as a radius;
/// below: a radius in mm given as m, or a clearance converted to m twice.
inline constexpr PlausibleRange kPlausibleClearanceRatio{1e-4, 0.3};
inline constexpr const char* kPlausibleClearanceRatioText = "1e-4 – 0.3";
/// Driver (crank) or journal speed |n| [rpm]: up to 50 000 rpm (a fast engine turns at 20 000).
/// Above: a speed in deg/s or rad/min given as rpm, or a digit too many.
inline constexpr double kPlausibleMaxSpeedRpm = 5e4;
inline constexpr const char* kPlausibleMaxSpeedText = "50000 rpm";

/// A number as the warnings print it (%.6g: 400, 0.0005, 5e+06).
inline std::string plausibility_number(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.6g", v);
  return buf;
}

/// "FIELD = MU Pa s is outside the plausible 1e-4 – 5 Pa s (likely slip)", or nothing.
inline std::optional<std::string> implausible_viscosity(const std::string& field, double mu_Pa_s) {
  if (!std::isfinite(mu_Pa_s) || kPlausibleViscosityPaS.contains(mu_Pa_s)) return std::nullopt;
  const std::string mu = plausibility_number(mu_Pa_s);
  const std::string slip =
      mu_Pa_s > kPlausibleViscosityPaS.max
          ? mu + " cP is " + plausibility_number(mu_Pa_s * 1e-3) + " Pa s"
          : "a kinematic viscosity in m^2/s? " + mu + " m^2/s of an oil of 870 kg/m^3 is " +
                plausibility_number(mu_Pa_s * 870.0) + " Pa s";
  return field + " = " + mu + " Pa s is outside the plausible " + kPlausibleViscosityText + " (" + slip + ")";
}

/// "QUANTITY = C m / R m = C/R is outside the plausible clearance/radius 1e-4 – 0.3 (likely
/// slip)", or nothing. `quantity` names the fields the ratio comes from.
inline std::optional<std::string> implausible_clearance_ratio(const std::string& quantity, double clearance_m,
                                                              double radius_m) {
  const double ratio = clearance_m / radius_m;
  if (!std::isfinite(ratio) || kPlausibleClearanceRatio.contains(ratio)) return std::nullopt;
  const std::string c = plausibility_number(clearance_m);
  // A clearance of 10 mm or more is itself implausible: then say what it is in mm.
  const std::string slip =
      ratio > kPlausibleClearanceRatio.max
          ? "a length in mm given as m, or a diameter as a radius?" +
                (clearance_m >= 0.01 ? " " + c + " mm is " + plausibility_number(clearance_m * 1e-3) + " m" : "")
          : "a radius in mm given as m, or a clearance converted to m twice? " + c + " m × 1000 is " +
                plausibility_number(clearance_m * 1e3) + " m";
  return quantity + " = " + c + " m / " + plausibility_number(radius_m) + " m = " + plausibility_number(ratio) +
         " is outside the plausible clearance/radius " + kPlausibleClearanceRatioText + " (" + slip + ")";
}

/// "FIELD = N rpm is above the plausible 50000 rpm (likely slip)", or nothing.
inline std::optional<std::string> implausible_speed_rpm(const std::string& field, double rpm) {
  if (!std::isfinite(rpm) || std::fabs(rpm) <= kPlausibleMaxSpeedRpm) return std::nullopt;
  const std::string n = plausibility_number(rpm);
  return field + " = " + n + " rpm is above the plausible " + kPlausibleMaxSpeedText +
         " (a speed in deg/s or rad/min given as rpm, " +
         "or a digit too many? " + n + " deg/s is " + plausibility_number(rpm / 6.0) + " rpm)";
}

/// The same for a speed given in rad/s (lubbearing force --omega): the likely slip is rpm
/// given as rad/s.
inline std::optional<std::string> implausible_speed_rad_s(const std::string& field, double rad_s) {
  const double rpm = rad_s * 60.0 / (2.0 * kPi);
  if (!std::isfinite(rpm) || std::fabs(rpm) <= kPlausibleMaxSpeedRpm) return std::nullopt;
  const std::string w = plausibility_number(rad_s);
  return field + " = " + w + " rad/s (" + plausibility_number(rpm) +
         " rpm) is above the plausible " + kPlausibleMaxSpeedText + " (rpm given as rad/s? " + w + " rpm is " +
         plausibility_number(rad_s * 2.0 * kPi / 60.0) + " rad/s)";
}

}  // namespace lub
