// The order in which a study's cells continue from each other's periodic orbits
// (simulation.steady = continuation; docs/theory/continuation.md).
//
// The cells of one value of every non-numeric axis (a force law) form a lattice over the
// numeric axes: two cells are neighbours when they differ on exactly one numeric axis, by
// one step of its sorted values. Each lattice is spanned by a breadth-first tree from its
// seed, the cell with the thickest film by the Sommerfeld number's trend (largest
// μ ω / c²: viscosity and speed up, clearance down); a cell continues from its parent's
// orbit. The tree is fixed before any case runs, from the grid alone, so the results do
// not depend on how many ranks run them or on a resume.
#pragma once

#include <vector>

#include "lub/sweep/grid.hpp"

namespace lub::sweep {

/// Each case's parent (-1: a seed, or a case whose scene does not ask for continuation).
std::vector<int> continuation_parents(const Grid& grid);

}  // namespace lub::sweep
