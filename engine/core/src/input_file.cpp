#include "core/input_file.hpp"

#include <cerrno>
#include <cstring>
#include <fstream>
#include <sstream>
#include <stdexcept>

namespace rumble {

namespace fs = std::filesystem;

std::string file_kind(const fs::file_status& status) {
  switch (status.type()) {
    case fs::file_type::directory:
      return "a directory";
    case fs::file_type::fifo:
      return "a FIFO (named pipe)";
    case fs::file_type::character:
    case fs::file_type::block:
      return "a device";
    case fs::file_type::socket:
      return "a socket";
    default:
      return "not a file";
  }
}

std::string input_file_problem(const fs::path& path, std::uintmax_t max_bytes) {
  std::error_code ec;
  const fs::file_status status = fs::status(path, ec);
  if (!fs::exists(status))
    return ec && ec != std::errc::no_such_file_or_directory ? "cannot be read: " + ec.message()
                                                            : "does not exist";
  if (!fs::is_regular_file(status)) return "is " + file_kind(status) + ", not a regular file";
  const std::uintmax_t size = fs::file_size(path, ec);
  if (ec) return "cannot be read: " + ec.message();
  if (size > max_bytes) {
    std::ostringstream m;
    m.precision(3);
    m << "is " << static_cast<double>(size) << " bytes, more than the "
      << static_cast<double>(max_bytes) << " that rumble reads of it";
    return m.str();
  }
  return "";
}

std::string read_input_file(const fs::path& path, std::uintmax_t max_bytes) {
  if (const std::string problem = input_file_problem(path, max_bytes); !problem.empty())
    throw std::runtime_error("'" + path.string() + "' " + problem);
  std::ifstream in(path, std::ios::binary);
  std::ostringstream text;  // (istreambuf_iterator trips GCC 12's -Wnull-dereference)
  if (in) text << in.rdbuf();
  if (!in || in.bad())
    throw std::runtime_error("'" + path.string() + "' cannot be read: " + std::strerror(errno));
  // A file that grew after the check is cut at the bound, never read past it.
  std::string content = std::move(text).str();
  if (content.size() > max_bytes) content.resize(max_bytes);
  return content;
}

}  // namespace rumble
