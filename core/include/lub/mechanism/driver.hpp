// How a driver prescribes a body's angle (a constraint row of the mechanism; the scene
// names it in drivers[].type): φ(t) = φ0 + ω t (constant_speed), or
// φ(t) = φ0 + (ω/Ω) sin(Ω t) (reversing: the speed ω cos Ω t changes sign).
#pragma once

#include <array>
#include <string_view>
#include <utility>

#include "lub/common/name_table.hpp"

namespace lub {

enum class DriverType { constant_speed, reversing };

template <>
struct NameTable<DriverType> {
  static constexpr std::array<std::pair<DriverType, std::string_view>, 2> entries{{
      {DriverType::constant_speed, "constant_speed"},
      {DriverType::reversing, "reversing"},
  }};
};

}  // namespace lub
