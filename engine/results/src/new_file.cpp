#include "results/new_file.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>

#include "core/errors.hpp"

namespace rumble {
namespace {

/// unlink, then open exclusively and never through a link; -1 with errno set on failure.
int create_new(const char* path) noexcept {
  if (::unlink(path) != 0 && errno != ENOENT) return -1;
  return ::open(path, O_WRONLY | O_CREAT | O_EXCL | O_NOFOLLOW | O_CLOEXEC, 0666);
}

bool write_all(int fd, std::string_view text) noexcept {
  while (!text.empty()) {
    const ssize_t n = ::write(fd, text.data(), text.size());
    if (n < 0 && errno == EINTR) continue;
    if (n < 0) return false;
    if (n == 0) {
      errno = EIO;
      return false;
    }
    text.remove_prefix(static_cast<std::size_t>(n));
  }
  return true;
}

}  // namespace

std::string what_stands_at(const std::filesystem::path& path) {
  struct stat st {};
  if (::lstat(path.c_str(), &st) != 0) return "";
  if (S_ISLNK(st.st_mode)) {
    std::error_code ec;
    return "a symbolic link (to " + std::filesystem::read_symlink(path, ec).string() + ")";
  }
  if (S_ISDIR(st.st_mode)) return "a directory";
  return S_ISREG(st.st_mode) ? "a file" : "a device, pipe or socket";
}

std::string write_error(const std::filesystem::path& path, int err) {
  const char* fix = "check that outputs.directory is writable";
  if (err == ENOSPC || err == EDQUOT) {
    fix = "free disk space or set outputs.directory to another disk";
  } else if (err == EFBIG) {
    fix = "the process's file size limit (ulimit -f) is reached; raise it";
  } else if (err == EISDIR) {
    fix = "a directory has the name of a results file; move it away";
  }
  return "cannot write results file " + path.string() + ": " + std::strerror(err) + "; " + fix;
}

int open_new_file(const std::filesystem::path& path) {
  const int fd = create_new(path.c_str());
  if (fd < 0) throw RunError(write_error(path, errno));
  return fd;
}

int replace_file_noexcept(const char* path, const char* tmp,
                          std::initializer_list<std::string_view> pieces) noexcept {
  const int fd = create_new(tmp);
  if (fd < 0) return errno;
  bool ok = true;
  for (const std::string_view piece : pieces) ok = ok && write_all(fd, piece);
  int err = ok ? 0 : errno;
  if (::close(fd) != 0 && err == 0) err = errno;
  if (err == 0 && std::rename(tmp, path) != 0) err = errno;
  if (err != 0) ::unlink(tmp);
  return err;
}

void replace_file(const std::filesystem::path& path, const std::filesystem::path& tmp,
                  std::string_view text) {
  const int err = replace_file_noexcept(path.c_str(), tmp.c_str(), {text});
  if (err != 0) throw RunError(write_error(path, err));
}

}  // namespace rumble
