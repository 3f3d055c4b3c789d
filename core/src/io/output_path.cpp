#include "lub/io/output_path.hpp"

#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>

namespace lub {

std::optional<std::string> output_path_problem(const std::string& path, const std::string& option) {
  const std::string head = option + " " + path + ": ";
  if (path.empty()) return option + " \"\": must name a file (the path is empty)";
  if (path.back() == '/') return head + "must name a file, not a directory (the path ends in '/')";
  struct stat st{};
  if (::stat(path.c_str(), &st) == 0) {
    if (S_ISDIR(st.st_mode)) return head + "must name a file, not a directory (it is an existing directory)";
    if (!S_ISREG(st.st_mode)) return head + "must name a regular file (it exists and is a device, pipe or socket)";
    if (::access(path.c_str(), W_OK) != 0) return head + "the file exists and is not writable (" + std::strerror(errno) + ")";
  }
  const auto slash = path.find_last_of('/');
  const std::string dir = slash == std::string::npos ? "." : (slash == 0 ? "/" : path.substr(0, slash));
  struct stat ds{};
  if (::stat(dir.c_str(), &ds) != 0)
    return head + "its directory " + dir + " does not exist (" + std::strerror(errno) + ")";
  if (!S_ISDIR(ds.st_mode)) return head + "its directory " + dir + " is not a directory";
  if (::access(dir.c_str(), W_OK | X_OK) != 0)
    return head + "its directory " + dir + " is not writable (" + std::strerror(errno) + ")";
  return std::nullopt;
}

}  // namespace lub
