// Where the files that messages and --help texts point to are: the example scenes and grids
// with the scene schema (configs/) and the docs (docs/). In the repository they are its
// configs/ and docs/; `cmake --install` copies both, in the same layout, to share/lubjoint of
// the prefix (docs/guide/install.md). Messages name them through data_path, so that a path
// printed by an installed program exists for its user.
#pragma once

#include <string>
#include <string_view>

namespace lub {

/// `rel`, a path of the repository ("configs/scene.schema.json", "docs/theory/"), as this
/// program's user finds it: under $LUBJOINT_DATADIR when set; for an installed program,
/// under the share/lubjoint of its prefix (the one beside its executable's bin/, else the
/// configured prefix's); else `rel` itself (a program of the build tree: the repository's path).
std::string data_path(std::string_view rel);

}  // namespace lub
