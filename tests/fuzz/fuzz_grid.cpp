// Fuzz target: the grid reader (lub/sweep/grid.hpp) must refuse any input with an
// InputError, never crash, hang, leak an exception of another type or accept a grid that
// breaks its invariants. Each input is parsed as a grid whose relative scene paths resolve
// against configs/grids (so the seed corpus, configs/grids/*.json, finds its scenes); an
// accepted grid is checked: every case has a scene, a hash, a value per axis, and every
// sub-grid's case ids are cases of the grid, as many as its shape says.
// Built like fuzz_scene (tests/fuzz/CMakeLists.txt): a plain replay program in every build
// (ctest fuzz_grid_replay), libFuzzer with ASan and UBSan in tools/check/fuzz.sh's clang build.
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string>

#include "fuzz_check.hpp"

#include "lub/io/json_reader.hpp"
#include "lub/sweep/grid.hpp"

#ifndef LUB_SOURCE_DIR
#define LUB_SOURCE_DIR "."
#endif

namespace {

#define FUZZ_CHECK(cond) LUB_FUZZ_CHECK("fuzz_grid", cond)

void check_invariants(const lub::sweep::Grid& g) {
  FUZZ_CHECK(!g.cases.empty());
  for (std::size_t i = 0; i < g.cases.size(); ++i) {
    const lub::sweep::Case& c = g.cases[i];
    FUZZ_CHECK(c.id == static_cast<int>(i));
    FUZZ_CHECK(!c.scene.empty() && c.hash.size() == 64);
    FUZZ_CHECK(c.axis_values.size() == g.axes.size());
  }
  for (const lub::sweep::Block& b : g.blocks) {
    std::size_t n = 1;
    for (std::size_t e : b.shape) n *= e;
    FUZZ_CHECK(b.shape.empty() || n == b.case_ids.size());
    for (int id : b.case_ids) FUZZ_CHECK(id >= 0 && id < static_cast<int>(g.cases.size()));
    if (b.factorial) FUZZ_CHECK(b.axes.size() == b.values.size());
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  if (text.size() > 16384) return 0;  // a grid is a few hundred bytes; keep each input fast
  try {
    check_invariants(lub::sweep::parse_grid(text, std::string(LUB_SOURCE_DIR) + "/configs/grids", "fuzz.json"));
  } catch (const lub::InputError&) {
  }
  return 0;
}
