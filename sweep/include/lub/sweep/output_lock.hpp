// The study file's lock: one sweep per output file at a time. A sidecar file STUDY.h5.lock
// is flock()ed (exclusive, non-blocking) for the sweep's lifetime and holds "pid host
// start-time" of the sweep that holds it, so a second sweep on the same -o is refused up
// front, naming the first, instead of failing later inside HDF5 ("not an HDF5 file",
// from HDF5's own file locking). flock is released by the kernel when the process dies,
// so a killed sweep leaves a stale lock file that the next sweep simply takes over.
#pragma once

#include <string>

namespace lub::sweep {

class OutputLock {
 public:
  OutputLock() = default;
  /// Takes the lock of `study_path` (STUDY.h5.lock), trying again for `patience_s` while
  /// another process holds it (a killed sweep's rank 0 saving its last rows). Throws
  /// lub::InputError if it is still held then ("-o STUDY.h5: the file is in use by another
  /// sweep (pid 123 on host h, since ...)"), std::runtime_error if the lock file cannot be
  /// created.
  explicit OutputLock(const std::string& study_path, double patience_s = kPatienceS);
  /// How long a held lock is tried again by default.
  static constexpr double kPatienceS = 3.0;
  OutputLock(const OutputLock&) = delete;
  OutputLock& operator=(const OutputLock&) = delete;
  OutputLock(OutputLock&& other) noexcept;
  OutputLock& operator=(OutputLock&& other) noexcept;
  /// Removes the lock file and releases the lock.
  ~OutputLock();

  bool held() const { return fd_ >= 0; }
  const std::string& path() const { return path_; }

  /// The lock file of a study file.
  static std::string lock_path(const std::string& study_path) { return study_path + ".lock"; }

 private:
  void release() noexcept;
  int fd_ = -1;
  std::string path_;
};

}  // namespace lub::sweep
