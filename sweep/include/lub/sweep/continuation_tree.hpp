// The lattice of a study's cells, and the order in which they continue from each other's
// periodic orbits (simulation.steady = continuation; docs/theory/continuation.md).
//
// The cells of one value of every non-numeric axis (a force law) form a lattice over the
// numeric axes: two cells are neighbours when they differ on exactly one numeric axis, by
// one step of its sorted values. The study file writes its edges (/lattice), which is what
// lubjoint.bifurcations reads as the grid's neighbours. Each lattice is spanned by a breadth-first tree from its
// seed, the cell with the thickest film by the Sommerfeld number's trend (largest
// μ ω / c²: viscosity and speed up, clearance down); a cell continues from its parent's
// orbit. The tree is fixed before any case runs, from the grid alone, so the results do
// not depend on how many ranks run them or on a resume.
#pragma once

#include <vector>

#include "lub/sweep/grid.hpp"

namespace lub::sweep {

/// Two lattice neighbours: `lower` and `upper` differ on the numeric axis `axis` (an index
/// into Grid::axes) only, by one step of its sorted values, `lower` at the lower value.
struct LatticeEdge {
  int lower = -1;
  int upper = -1;
  int axis = -1;
  bool operator==(const LatticeEdge& o) const { return lower == o.lower && upper == o.upper && axis == o.axis; }
};

/// Every edge of the lattice of all the grid's cases (each axis's levels: its sorted
/// distinct values over every case), ordered by `lower`'s case id, then by axis.
std::vector<LatticeEdge> lattice_edges(const Grid& grid);

/// Each case's parent (-1: a seed, or a case whose scene does not ask for continuation):
/// a tree over the lattice of the cases that continue (levels over those cases only).
std::vector<int> continuation_parents(const Grid& grid);

}  // namespace lub::sweep
