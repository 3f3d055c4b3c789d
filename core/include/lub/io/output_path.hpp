// Checking an output path before any work: lubsim's run file and lubsweep's study file
// are refused up front (exit 2, no file created) when they could not be written at the
// end, instead of after a whole simulation.
#pragma once

#include <optional>
#include <string>

namespace lub {

/// Why `path` cannot be an output file, or nullopt if it can. The message names the path
/// and the rule, e.g. "-o out/: must name a file, not a directory". Rules: not empty; not
/// ending in '/'; not an existing directory or other non-regular file; an existing file
/// must be writable; its directory must exist, be a directory, and be writable (the file
/// is written as PATH.partial there, then renamed). Creates nothing.
std::optional<std::string> output_path_problem(const std::string& path, const std::string& option = "-o");

}  // namespace lub
