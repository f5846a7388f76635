#include "run/results_directory.hpp"

#include <fcntl.h>
#include <sys/file.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <string>

#include "core/errors.hpp"
#include "run/new_file.hpp"

namespace rumble {
namespace {

namespace fs = std::filesystem;

std::string shown(const fs::path& p) {
  return p.lexically_normal().string();
}

}  // namespace

ResultsDirectory::ResultsDirectory(fs::path directory) : dir_(std::move(directory)) {
  std::error_code ec;
  fs::create_directories(dir_, ec);
  if (ec) {
    throw RunError("cannot create results directory " + dir_.string() + ": " + ec.message() +
                   "; set /outputs/directory to a writable place");
  }
  lock();
}

ResultsDirectory::~ResultsDirectory() {
  // Empty between runs; the lock itself goes with the descriptor (and with the process).
  if (::ftruncate(lock_fd_, 0) != 0) {
    // Harmless: the process id of an ended run stays, and the lock is what counts.
  }
  ::close(lock_fd_);
}

void ResultsDirectory::lock() {
  const fs::path path = dir_ / kLockFile;
  lock_fd_ = ::open(path.c_str(), O_RDWR | O_CREAT | O_NOFOLLOW | O_CLOEXEC, 0666);
  if (lock_fd_ < 0) {
    const int err = errno;
    throw RunError("cannot open the lock file " + shown(path) + ": " + std::strerror(err) +
                   (err == ELOOP
                        ? "; it is a symbolic link, which rumble does not follow: remove it"
                        : "; check that the results directory is writable"));
  }
  if (::flock(lock_fd_, LOCK_EX | LOCK_NB) == 0) {
    const std::string pid = std::to_string(::getpid()) + "\n";
    if (::ftruncate(lock_fd_, 0) != 0 ||
        ::pwrite(lock_fd_, pid.data(), pid.size(), 0) != static_cast<ssize_t>(pid.size())) {
      const int err = errno;
      ::close(lock_fd_);
      throw RunError(write_error(path, err));
    }
    return;
  }
  const int err = errno;
  char text[32] = {};
  const ssize_t n = ::pread(lock_fd_, text, sizeof text - 1, 0);
  ::close(lock_fd_);
  std::string holder = n > 0 ? std::string(text, static_cast<std::size_t>(n)) : "";
  while (!holder.empty() && (holder.back() == '\n' || holder.back() == ' ')) holder.pop_back();
  if (holder.empty() || holder.find_first_not_of("0123456789") != std::string::npos)
    holder = "not written yet";
  if (err == EWOULDBLOCK) {
    throw RunError("results directory " + shown(dir_) +
                   " is in use by another rumble run (process id " + holder + ", lock file " +
                   shown(path) +
                   "); two runs into one directory would mix their results. Wait for that run to "
                   "end, or give this one another directory: /outputs/directory, or --output DIR");
  }
  throw RunError("cannot lock the results directory " + shown(dir_) + " (" + shown(path) +
                 "): " + std::strerror(err) +
                 "; put it on a local disk (/outputs/directory, or "
                 "--output DIR)");
}

}  // namespace rumble
