#include "results_file.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <stdexcept>

namespace rumble::fem {
namespace {

namespace fs = std::filesystem;

/// What stands at `path` (lstat'ed into st), not followed, for the messages.
std::string what_stands_at(const fs::path& path, const struct stat& st) {
  if (S_ISLNK(st.st_mode)) {
    std::error_code ec;
    return "a symbolic link (to " + fs::read_symlink(path, ec).string() + ")";
  }
  if (S_ISDIR(st.st_mode)) return "a directory";
  return S_ISREG(st.st_mode) ? "a file" : "a device, pipe or socket";
}

[[noreturn]] void fail(const std::string& where, const std::string& what, const std::string& fix) {
  throw std::runtime_error(where + ": " + what + "; " + fix);
}

/// Makes the folder `at` when it is missing; refuses anything but a real directory there.
void real_directory(const fs::path& at, const std::string& where) {
  struct stat st {};
  if (::lstat(at.c_str(), &st) != 0) {
    if (::mkdir(at.c_str(), 0777) == 0) return;
    const int err = errno;
    if (err != EEXIST || ::lstat(at.c_str(), &st) != 0) {  // (EEXIST: made meanwhile)
      fail(where, "cannot make the folder " + at.string() + ": " + std::strerror(err),
           "check that the results directory can be written");
    }
  }
  if (S_ISDIR(st.st_mode)) return;
  fail(where, at.string() + " is " + what_stands_at(at, st),
       "the file is written only through real directories inside the results directory, never "
       "through a link: move it away, or give another path");
}

}  // namespace

std::string outside_results(const std::string& relative) {
  const fs::path path(relative);
  if (path.is_absolute()) return "it is an absolute path";
  for (const fs::path& part : path)
    if (part == "..") return "it climbs out with \"..\"";
  return "";
}

fs::path new_results_file(const std::string& results_dir, const std::string& relative,
                          const std::string& where) {
  if (const std::string why = outside_results(relative); !why.empty()) {
    fail(where, "not inside the results directory: " + why,
         "give a path relative to the results directory, without \"..\"");
  }
  const fs::path dir(results_dir);
  const fs::path name = fs::path(relative).lexically_normal();
  fs::path at = dir;
  for (auto part = name.begin(); part != name.end() && std::next(part) != name.end(); ++part) {
    at /= *part;
    real_directory(at, where);
  }
  const fs::path path = dir / name;
  const int fd = ::open(path.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_NOFOLLOW | O_CLOEXEC, 0666);
  if (fd >= 0) {
    ::close(fd);
    return path;
  }
  const int err = errno;
  struct stat st {};
  if (::lstat(path.c_str(), &st) == 0) {
    fail(where, path.string() + " is there already (" + what_stands_at(path, st) + ")",
         "the file is written as a new one and nothing standing there is replaced (a rerun of "
         "the same scenario removes its own first): move it away, or give another path");
  }
  fail(where, "cannot create " + path.string() + ": " + std::strerror(err),
       "check that its folder can be written, or give another path");
}

}  // namespace rumble::fem
