// Private to the study file's sources: what the writer (study_file.cpp) takes from the
// resume reader (study_resume.cpp), the series of an earlier run. Not installed.
#pragma once

#include <map>
#include <string>
#include <vector>

#include "lub/io/h5.hpp"
#include "lub/sweep/case_result.hpp"
#include "lub/sweep/grid.hpp"

namespace lub::sweep::detail {

/// Copies series/<from_name> of `from` to the series of case `to_case` in `to` (nothing if
/// `from` has no such group). The names differ when the file being resumed came from
/// another grid: a case keeps its hash but its id and name follow its place in the new grid.
void copy_series(const h5::File& from, const std::string& from_name, h5::File& to, const Case& to_case);

/// The empty table `cases` in `parent` (the root's /cases, or /refinement/cases): the
/// columns of case_columns(g), then `extra`, with the attributes that group them (axes,
/// metrics, solver, each axis's pointer, the missing values, the classifications, the
/// orbit seed's packing).
h5::Table create_cases_table(h5::Group& parent, const Grid& g, const std::vector<h5::Column>& extra = {});

/// Copies to `to` the series the earlier study file `from` holds for the `reused` cases of
/// `grid`, each found by its scene's hash (the earlier file's case names are those of the
/// grid it was made from).
void copy_reused_series(const h5::File& from, const Grid& grid, const std::map<int, CaseResult>& reused,
                        h5::File& to);

/// The groups other tools add to a study file: lubsweep refine's /refinement and
/// lubjoint.boundaries' /boundaries. A rewrite of the file keeps them while every case of
/// the grid is one they were made from (study_added_groups_kept).
std::vector<std::string> study_added_groups(const h5::File& from);
/// Copies the added groups `from` holds to `to`.
void copy_added_groups(const h5::File& from, h5::File& to);

}  // namespace lub::sweep::detail
