// Mathematical constants and the "unknown" value, written once for the whole library.
#pragma once

#include <limits>

namespace lub {

constexpr double kPi = 3.14159265358979323846;     ///< π
constexpr double kTwoPi = 6.28318530717958647692;  ///< 2π: one crank revolution [rad]
/// A value not known (a metric without a film, an estimate without enough cycles).
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

}  // namespace lub
