#include "lub/sweep/output_lock.hpp"

#include <fcntl.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <cstring>
#include <ctime>
#include <stdexcept>
#include <thread>
#include <utility>

#include <fmt/format.h>

#include "lub/io/json_reader.hpp"

namespace lub::sweep {

namespace {

std::string read_all(int fd) {
  std::string out;
  char buf[256];
  if (::lseek(fd, 0, SEEK_SET) < 0) return out;
  for (;;) {
    const ssize_t n = ::read(fd, buf, sizeof buf);
    if (n <= 0) break;
    out.append(buf, static_cast<std::size_t>(n));
  }
  while (!out.empty() && (out.back() == '\n' || out.back() == ' ')) out.pop_back();
  return out;
}

std::string holder_text(const std::string& content) {
  // "pid 123 host h since 2026-11-24T16:00:00Z"
  if (content.empty()) return "a process that has not written its pid yet";
  return content;
}

}  // namespace

OutputLock::OutputLock(const std::string& study_path, double patience_s) : path_(lock_path(study_path)) {
  // Open, lock, then check that the path still names the file locked: a sweep that ends
  // unlinks its lock file while holding it, and one that opened the old file meanwhile
  // must not run on a lock nobody else can see.
  // A held lock is tried again for `patience_s`: a sweep whose mpirun was just killed is
  // still saving its last rows for a few milliseconds, and its resume must not be refused.
  const auto give_up = std::chrono::steady_clock::now() + std::chrono::duration<double>(patience_s);
  for (int attempt = 0; attempt < 100;) {
    const int fd = ::open(path_.c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0644);
    if (fd < 0)
      throw std::runtime_error("-o " + study_path + ": cannot create the lock file " + path_ + ": " +
                               std::strerror(errno));
    if (::flock(fd, LOCK_EX | LOCK_NB) != 0) {
      const int err = errno;
      const std::string holder = read_all(fd);
      ::close(fd);
      if (err == EWOULDBLOCK && std::chrono::steady_clock::now() < give_up) {
        std::this_thread::sleep_for(std::chrono::milliseconds(20));
        continue;
      }
      if (err == EWOULDBLOCK)
        throw InputError("-o " + study_path + ": the file is in use by another sweep (" + holder_text(holder) +
                         "; lock file " + path_ + "): wait for it to end, or choose another -o");
      throw std::runtime_error("-o " + study_path + ": cannot lock " + path_ + ": " + std::strerror(err));
    }
    struct stat by_fd{}, by_path{};
    if (::fstat(fd, &by_fd) == 0 && ::stat(path_.c_str(), &by_path) == 0 && by_fd.st_ino == by_path.st_ino &&
        by_fd.st_dev == by_path.st_dev) {
      fd_ = fd;
      break;
    }
    ::close(fd);  // unlinked by its previous holder: take the new one
    ++attempt;
  }
  if (fd_ < 0) throw std::runtime_error("-o " + study_path + ": cannot take the lock " + path_);

  char host[256] = "?";
  ::gethostname(host, sizeof host - 1);
  char when[64] = "";
  const std::time_t now = std::time(nullptr);
  std::tm tm{};
  ::gmtime_r(&now, &tm);
  std::strftime(when, sizeof when, "%Y-%m-%dT%H:%M:%SZ", &tm);
  const std::string content = fmt::format("pid {} on host {}, since {}\n", ::getpid(), host, when);
  if (::ftruncate(fd_, 0) != 0 || ::pwrite(fd_, content.data(), content.size(), 0) < 0) {
    // The lock holds without its text; the refusal message then says less.
  }
}

OutputLock::OutputLock(OutputLock&& other) noexcept
    : fd_(std::exchange(other.fd_, -1)), path_(std::move(other.path_)) {}

OutputLock& OutputLock::operator=(OutputLock&& other) noexcept {
  if (this != &other) {
    release();
    fd_ = std::exchange(other.fd_, -1);
    path_ = std::move(other.path_);
  }
  return *this;
}

OutputLock::~OutputLock() { release(); }

void OutputLock::release() noexcept {
  if (fd_ < 0) return;
  ::unlink(path_.c_str());  // while still holding it (see the constructor)
  ::close(fd_);
  fd_ = -1;
}

}  // namespace lub::sweep
