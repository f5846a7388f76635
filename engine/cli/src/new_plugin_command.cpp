// `rumble new-plugin KIND NAME [DIR]`: a new plugin project, copied from the template of that
// kind installed with the SDK (share/rumble/<template>, see sdk/CMakeLists.txt) with every
// occurrence of the template's names replaced, in file names and contents. The templates are
// complete projects with their own test, so the copy builds, tests and loads as it is.
#include <algorithm>
#include <array>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <regex>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "cli/arguments.hpp"
#include "cli/commands.hpp"
#include "cli/exit_codes.hpp"
#include "cli/share_dir.hpp"

namespace rumble::cli {
namespace {

namespace fs = std::filesystem;

/// A template and the two spellings of its name that a copy renames: snake_case (type, plugin,
/// library, project and file names) and CamelCase (the class). The templates use no other.
struct Template {
  const char* kind;
  const char* directory;  // under share/rumble
  const char* snake;
  const char* camel;
};

constexpr std::array<Template, 3> kTemplates{{
    {"soil", "template", "template_soil", "TemplateSoil"},
    {"vehicle", "template_vehicle", "template_vehicle", "TemplateVehicle"},
    {"coupler", "template_coupler", "template_coupler", "TemplateCoupler"},
}};

constexpr const char* kNewPluginUsage = "usage: rumble new-plugin soil|vehicle|coupler NAME [DIR]";

const Template& find_template(const std::string& kind) {
  for (const Template& t : kTemplates) {
    if (kind == t.kind) return t;
  }
  throw UsageError("new-plugin: unknown kind '" + kind +
                   "'; KIND is soil, vehicle or coupler (e.g. rumble new-plugin soil my_soil)");
}

/// NAME becomes a type name, a library file name, a CMake target and (in CamelCase) a C++ class,
/// so it is held to the common subset: lower snake_case, a C identifier.
void check_name(const std::string& name) {
  static const std::regex snake_case("[a-z][a-z0-9]*(_[a-z0-9]+)*");
  if (!std::regex_match(name, snake_case)) {
    throw UsageError("new-plugin: NAME '" + name +
                     "' is not a lower snake_case identifier; use lower-case letters, digits and "
                     "single '_' between words, starting with a letter (e.g. my_soil)");
  }
}

std::string camel_case(const std::string& snake) {
  std::string camel;
  bool upper = true;
  for (const char c : snake) {
    if (c == '_') {
      upper = true;
    } else {
      camel += upper ? static_cast<char>(c - 'a' + 'A') : c;
      upper = false;
    }
  }
  return camel;
}

std::string replace_all(std::string text, const std::string& from, const std::string& to) {
  for (std::size_t at = text.find(from); at != std::string::npos; at = text.find(from, at)) {
    text.replace(at, from.size(), to);
    at += to.size();
  }
  return text;
}

/// The destination must be new or empty: a scaffold never overwrites anyone's files.
void check_destination(const fs::path& dir) {
  if (!fs::exists(dir)) return;
  if (!fs::is_directory(dir)) {
    throw UsageError("new-plugin: '" + dir.string() +
                     "' exists and is not a directory; give a new DIR (default ./NAME)");
  }
  if (!fs::is_empty(dir)) {
    throw UsageError("new-plugin: directory '" + dir.string() +
                     "' exists and is not empty; give a new DIR (default ./NAME) or empty it");
  }
}

/// The prefix to give find_package(Rumble) when this engine was installed with its SDK (the
/// package config lies in <prefix>/lib*/.../cmake/Rumble), or a placeholder.
std::string sdk_prefix_hint() {
  const fs::path prefix = share_directory().parent_path().parent_path();
  std::error_code ec;
  for (fs::recursive_directory_iterator it(prefix / "lib", ec), end; !ec && it != end;
       it.increment(ec)) {
    if (it.depth() > 2) it.disable_recursion_pending();
    if (it->path().filename() == "RumbleConfig.cmake") return prefix.string();
  }
  return "<prefix of the installed Rumble SDK>";
}

std::string read_file(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw std::runtime_error("new-plugin: cannot read '" + path.string() + "'");
  std::ostringstream text;  // (istreambuf_iterator trips GCC 12's -Wnull-dereference here)
  text << in.rdbuf();
  return text.str();
}

void write_file(const fs::path& path, const std::string& text) {
  std::ofstream out(path, std::ios::binary);
  out << text;
  if (!out) {
    throw std::runtime_error("new-plugin: cannot write '" + path.string() +
                             "'; check that its directory is writable");
  }
}

}  // namespace

int new_plugin_command(const std::vector<std::string>& args) {
  const Arguments a(args, {}, {});
  const std::vector<std::string>& p = a.positional();
  if (p.size() < 2 || p.size() > 3) {
    throw UsageError(std::string("new-plugin takes KIND NAME [DIR]; ") + kNewPluginUsage +
                     " (e.g. rumble new-plugin soil my_soil)");
  }
  const Template& t = find_template(p[0]);
  const std::string& name = p[1];
  check_name(name);
  const fs::path dir = p.size() == 3 ? fs::path(p[2]) : fs::path(name);
  check_destination(dir);

  const fs::path source = share_directory() / t.directory;
  if (!fs::is_directory(source)) {
    throw std::runtime_error("new-plugin: the " + std::string(t.kind) + " template '" +
                             source.string() +
                             "' does not exist; reinstall Rumble with its SDK (cmake --install "
                             "<build dir>), which puts the templates in share/rumble");
  }
  std::vector<fs::path> files;
  for (const fs::directory_entry& e : fs::directory_iterator(source)) {
    if (e.is_regular_file()) files.push_back(e.path());
  }
  std::sort(files.begin(), files.end());

  const std::string camel = camel_case(name);
  const auto rename = [&](const std::string& text) {
    return replace_all(replace_all(text, t.snake, name), t.camel, camel);
  };
  fs::create_directories(dir);
  std::ostringstream created;
  for (const fs::path& file : files) {
    const std::string target = rename(file.filename().string());
    write_file(dir / target, rename(read_file(file)));
    created << "  " << (dir / target).string() << '\n';
  }
  std::cout << "created " << t.kind << " plugin '" << name << "' in " << dir.string() << ":\n"
            << created.str() << "next:\n"
            << "  cmake -S " << dir.string() << " -B " << (dir / "build").string()
            << " -DCMAKE_PREFIX_PATH=" << sdk_prefix_hint() << '\n'
            << "  cmake --build " << (dir / "build").string() << " && ctest --test-dir "
            << (dir / "build").string() << '\n'
            << "  RUMBLE_PLUGIN_PATH=" << (dir / "build").string() << " rumble plugins\n";
  return kExitOk;
}

}  // namespace rumble::cli
