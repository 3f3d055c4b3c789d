#include "lub/io/data_path.hpp"

#include <cstdlib>
#include <filesystem>
#include <system_error>

// LUB_DATADIR_FROM_BINDIR, LUB_INSTALL_FULL_DATADIR, LUB_BINARY_DIR: set by core/CMakeLists.txt
// on this file alone (a changed prefix recompiles nothing else).

namespace lub {

namespace {

namespace fs = std::filesystem;

bool is_dir(const fs::path& p) {
  std::error_code ec;
  return fs::is_directory(p, ec);
}

bool is_under(const fs::path& p, const fs::path& dir) {
  const fs::path rel = p.lexically_relative(dir);
  return !rel.empty() && *rel.begin() != "..";
}

// The directory that holds configs/ and docs/ for this program, "" for the repository (paths
// relative to its root, as the docs write them).
std::string find_root() {
  if (const char* env = std::getenv("LUBJOINT_DATADIR"); env && *env) return env;
  std::error_code ec;
  const fs::path exe = fs::read_symlink("/proc/self/exe", ec);
  if (!ec) {
    const fs::path beside = (exe.parent_path() / LUB_DATADIR_FROM_BINDIR).lexically_normal();
    if (is_dir(beside)) return beside.string();
    if (is_under(exe, LUB_BINARY_DIR)) return "";  // the build tree: the repository's paths
  }
  if (is_dir(LUB_INSTALL_FULL_DATADIR)) return LUB_INSTALL_FULL_DATADIR;
  return "";
}

}  // namespace

std::string data_path(std::string_view rel) {
  static const std::string root = find_root();
  if (root.empty()) return std::string(rel);
  std::string path = root;
  if (path.back() != '/') path += '/';
  return path.append(rel);
}

}  // namespace lub
