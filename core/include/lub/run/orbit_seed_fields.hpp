// The packed orbit seed's layout (pack_seed, lub/run/run.hpp), field by field: the one
// definition behind pack_seed and unpack_seed (core/src/run/orbit_seed.cpp) and behind the
// study file's description of its /cases/orbit_seed column (attributes `layout`, `fields`,
// `field_shapes`, `field_types`, `field_units`, `field_long_names`), which a reader
// decodes by name (lubjoint.study.orbit_seed).
//
// A packed row is: the layout number (orbit_seed_layout()), then the count of each field
// that is not a scalar, in field order, then those fields' values, in field order, then
// each scalar field. A square matrix is stored column-major, its count the square of its
// side.
#pragma once

#include <array>
#include <string_view>
#include <utility>
#include <vector>

#include "lub/common/name_table.hpp"

namespace lub {

/// How one field of a seed is laid out in the packed row.
enum class SeedShape {
  scalar,         ///< one number, after every other field
  vector,         ///< a count in the header, then that many numbers
  square_matrix,  ///< as a vector of n² numbers: an n × n matrix, column-major
};
template <>
struct NameTable<SeedShape> {
  static constexpr std::array<std::pair<SeedShape, std::string_view>, 3> entries{{
      {SeedShape::scalar, "scalar"},
      {SeedShape::vector, "vector"},
      {SeedShape::square_matrix, "square_matrix_column_major"},
  }};
};

/// One field of OrbitSeed as packed.
struct OrbitSeedField {
  std::string_view name;       ///< the OrbitSeed member's name
  SeedShape shape;
  bool integer;                ///< integers (an int member), stored as doubles
  std::string_view unit;       ///< CF-style ("1": dimensionless, each coordinate in its own unit)
  std::string_view long_name;  ///< a description
};

/// The packed layout's number: the first of every row; bumped when the layout changes.
int orbit_seed_layout();

/// OrbitSeed's fields in packing order (every field that is not a scalar first).
const std::vector<OrbitSeedField>& orbit_seed_fields();

}  // namespace lub
