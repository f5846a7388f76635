#include "study/output_lock.hpp"

#include <fcntl.h>
#include <sys/file.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <string>

#include "core/errors.hpp"

namespace rumble::study {

OutputLock::OutputLock(const std::filesystem::path& output) {
  std::error_code ec;
  std::filesystem::create_directories(output, ec);
  if (ec) {
    throw RunError("cannot create the study's output folder " + output.string() + ": " +
                   ec.message() + "; set \"output\" in the study file to a writable place");
  }
  const std::filesystem::path path = output / ".rumble-study.lock";
  fd_ = ::open(path.c_str(), O_RDWR | O_CREAT | O_NOFOLLOW | O_CLOEXEC, 0666);
  if (fd_ < 0) {
    throw RunError("cannot open the lock file " + path.string() + ": " + std::strerror(errno) +
                   "; check that the study's output folder is writable");
  }
  if (::flock(fd_, LOCK_EX | LOCK_NB) != 0) {
    char text[32] = {};
    const ssize_t n = ::pread(fd_, text, sizeof text - 1, 0);
    std::string holder = n > 0 ? std::string(text, static_cast<std::size_t>(n)) : "unknown";
    while (!holder.empty() && holder.back() == '\n') holder.pop_back();
    ::close(fd_);
    throw RunError("the study's output folder " + output.string() +
                   " is in use by another rumble study (process id " + holder +
                   "); wait for it to end, or set another \"output\" in the study file");
  }
  const std::string pid = std::to_string(::getpid()) + "\n";
  if (::ftruncate(fd_, 0) != 0 || ::pwrite(fd_, pid.data(), pid.size(), 0) < 0) {
    // The lock holds without the process id; only the message of a second study loses it.
  }
}

OutputLock::~OutputLock() {
  if (::ftruncate(fd_, 0) != 0) {
    // Harmless: a stale process id, and the lock is what counts.
  }
  ::close(fd_);
}

}  // namespace rumble::study
