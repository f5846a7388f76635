#include "results/results_directory.hpp"

#include <fcntl.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <fstream>
#include <functional>
#include <nlohmann/json.hpp>
#include <vector>

#include "core/errors.hpp"
#include "core/input_file.hpp"
#include "core/logging.hpp"
#include "results/dead_run.hpp"
#include "results/new_file.hpp"

namespace rumble {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

constexpr const char* kManifestTmp = ".rumble-manifest.json.tmp";
constexpr int kManifestVersion = 1;
// `rumble soil-frf`'s and `rumble mesh`'s default outputs, beside a scenario's results: not a
// run's to list or remove.
constexpr const char* kSoilFrfDirectory = "soil_frf";
constexpr const char* kMeshFile = "mesh.vtu";

/// Names at the top of the directory that no run lists, refuses or removes.
bool reserved(const std::string& relative) {
  return relative == ResultsDirectory::kLockFile || relative == ResultsDirectory::kManifestFile ||
         relative == kManifestTmp || relative == kSoilFrfDirectory || relative == kMeshFile;
}

/// A name a run could have listed: relative, inside the directory (no "..", ".", empty part).
bool inside(const std::string& relative) {
  if (relative.empty() || relative.front() == '/' || reserved(relative)) return false;
  std::size_t start = 0;
  while (start <= relative.size()) {
    std::size_t end = relative.find('/', start);
    if (end == std::string::npos) end = relative.size();
    const std::string_view part(relative.data() + start, end - start);
    if (part.empty() || part == "." || part == "..") return false;
    start = end + 1;
  }
  return true;
}

/// What identifies "the same scenario": its canonical path; "" for a pipe or a stream.
std::string scenario_identity(const fs::path& file) {
  std::error_code ec;
  if (!fs::is_regular_file(file, ec)) return "";
  const fs::path canonical = fs::weakly_canonical(fs::absolute(file), ec);
  return ec ? fs::absolute(file).lexically_normal().string() : canonical.string();
}

std::string shown(const fs::path& p) {
  return p.lexically_normal().string();
}

struct Entry {
  std::string relative;  // generic form, "fields/soil_000000.vtu"
  bool directory = false;
  dev_t dev = 0;
  ino_t ino = 0;
};

/// Everything in dir (the reserved names at its top excepted), links not followed; descends into
/// the directories `descend` accepts.
std::vector<Entry> scan(const fs::path& dir,
                        const std::function<bool(const std::string&)>& descend) {
  std::vector<Entry> out;
  std::error_code ec;
  auto it = fs::recursive_directory_iterator(dir, ec);
  for (; !ec && it != fs::recursive_directory_iterator(); it.increment(ec)) {
    Entry e;
    e.relative = it->path().lexically_relative(dir).generic_string();
    if (it.depth() == 0 && reserved(e.relative)) {
      it.disable_recursion_pending();
      continue;
    }
    struct stat st {};
    if (::lstat(it->path().c_str(), &st) != 0) continue;  // gone meanwhile
    e.directory = S_ISDIR(st.st_mode);
    e.dev = st.st_dev;
    e.ino = st.st_ino;
    if (e.directory && !descend(e.relative)) it.disable_recursion_pending();
    out.push_back(std::move(e));
  }
  if (ec) {
    throw RunError("cannot read the results directory " + shown(dir) + ": " + ec.message() +
                   "; check its permissions");
  }
  return out;
}

std::string join(const std::vector<std::string>& parts, const char* separator) {
  std::string out;
  for (const auto& p : parts) out += (out.empty() ? "" : separator) + p;
  return out;
}

}  // namespace

/// The manifest of the run before this one, as read.
struct ResultsDirectory::Previous {
  bool present = false;
  std::string unreadable;  // why it cannot be used; "" when it can
  std::string scenario;
  std::vector<std::string> overrides;  // absent in the manifest: none
  std::vector<std::string> files, directories;
  std::vector<std::string> outside;  // entries that are no path inside the directory
};

ResultsDirectory::ResultsDirectory(fs::path directory, const fs::path& scenario_file,
                                   bool overwrite, std::vector<std::string> overrides)
    : dir_(std::move(directory)),
      scenario_(scenario_identity(scenario_file)),
      overrides_(std::move(overrides)) {
  std::error_code ec;
  fs::create_directories(dir_, ec);
  if (ec) {
    throw RunError("cannot create results directory " + dir_.string() + ": " + ec.message() +
                   "; set /outputs/directory to a writable place");
  }
  lock();
  try {
    clear_previous(overwrite);
    write_manifest();
    for (const Entry& e : scan(dir_, [](const std::string&) { return true; }))
      before_[e.relative] = {e.dev, e.ino};
  } catch (...) {
    release();
    throw;
  }
}

ResultsDirectory::ResultsDirectory(fs::path directory, Reopen) : dir_(std::move(directory)) {
  struct stat st {};
  if (::lstat(dir_.c_str(), &st) != 0 || !S_ISDIR(st.st_mode)) {
    throw ConfigError(shown(dir_) +
                      " is not a directory; give the results directory of a run (the "
                      "scenario's /outputs/directory, or the --output DIR it ran with)");
  }
  lock();
  try {
    const Previous prev = read_manifest();
    if (!prev.present && adoptable_for_post()) {
      // receivers.csv without a manifest (copied, or from another tool): post/ is new, and the
      // manifest written at the end lists it alone, so a second `rumble post` replaces it.
      for (const Entry& e : scan(dir_, [](const std::string&) { return true; }))
        before_[e.relative] = {e.dev, e.ino};
      return;
    }
    if (!prev.present || !prev.unreadable.empty() || !prev.outside.empty()) {
      throw ConfigError(shown(dir_) + " holds no results of a rumble run that rumble can add to (" +
                        (!prev.present
                             ? "no " + std::string(kManifestFile)
                             : shown(dir_ / kManifestFile) + " cannot be used: " +
                                   (prev.unreadable.empty() ? "it lists files outside the directory"
                                                            : prev.unreadable)) +
                        "); run the scenario into it first, or give the directory a run wrote");
    }
    scenario_ = prev.scenario;
    files_.insert(prev.files.begin(), prev.files.end());
    directories_.insert(prev.directories.begin(), prev.directories.end());
    for (const Entry& e : scan(dir_, [](const std::string&) { return true; }))
      before_[e.relative] = {e.dev, e.ino};
  } catch (...) {
    release();
    throw;
  }
}

bool ResultsDirectory::adoptable_for_post() const {
  struct stat st {};
  if (::lstat((dir_ / "receivers.csv").c_str(), &st) != 0 || !S_ISREG(st.st_mode)) return false;
  if (::lstat((dir_ / "post").c_str(), &st) == 0) {
    throw ConfigError(shown(dir_) + " holds receivers.csv but no " + std::string(kManifestFile) +
                      ", and " + shown(dir_ / "post") +
                      " is there already: rumble replaces only what it wrote, and nothing says "
                      "it wrote that; move or remove it, then run rumble post again");
  }
  return true;
}

ResultsDirectory::~ResultsDirectory() {
  try {
    list_new_files();
  } catch (const std::exception& e) {
    try {
      logger("engine")->warn("{}", e.what());
    } catch (...) {
      // Nothing left to tell it with.
    }
  }
  release();
}

void ResultsDirectory::release() noexcept {
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
    // The lock was free: a summary that still says "running" is a dead run's.
    if (const std::string died = settle_dead_run(dir_); !died.empty())
      logger("engine")->warn("{}: {}", shown(dir_), died);
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

ResultsDirectory::Previous ResultsDirectory::read_manifest() const {
  const fs::path manifest_path = dir_ / kManifestFile;
  Previous prev;
  struct stat st {};
  prev.present = ::lstat(manifest_path.c_str(), &st) == 0;
  if (prev.present) {
    try {
      if (!S_ISREG(st.st_mode)) throw std::runtime_error("it is not a regular file");
      const json m = json::parse(read_input_file(manifest_path, kMaxResultJsonBytes));
      if (m.at("version").get<int>() != kManifestVersion)
        throw std::runtime_error("version " + m.at("version").dump() + " is not known here");
      prev.scenario =
          m.at("scenario_file").is_null() ? "" : m.at("scenario_file").get<std::string>();
      if (m.contains("overrides"))
        prev.overrides = m.at("overrides").get<std::vector<std::string>>();
      for (const char* key : {"files", "directories"}) {
        for (const json& entry : m.at(key)) {
          const auto name = entry.get<std::string>();
          if (!inside(name)) {
            prev.outside.push_back(name);
          } else {
            (key[0] == 'f' ? prev.files : prev.directories).push_back(name);
          }
        }
      }
    } catch (const std::exception& e) {
      prev = Previous{};
      prev.present = true;
      prev.unreadable = e.what();
    }
  }
  return prev;
}

void ResultsDirectory::clear_previous(bool overwrite) {
  const fs::path manifest_path = dir_ / kManifestFile;
  const Previous prev = read_manifest();

  // What stands there that no manifest lists (the contents of an unlisted directory count once).
  const std::set<std::string> listed_files(prev.files.begin(), prev.files.end());
  const std::set<std::string> listed_dirs(prev.directories.begin(), prev.directories.end());
  std::vector<std::string> unlisted;
  for (const Entry& e :
       scan(dir_, [&](const std::string& d) { return listed_dirs.count(d) != 0; })) {
    const bool listed =
        e.directory ? listed_dirs.count(e.relative) != 0 : listed_files.count(e.relative) != 0;
    if (!listed) unlisted.push_back(e.relative + (e.directory ? "/" : ""));
  }

  std::sort(unlisted.begin(), unlisted.end());
  std::vector<std::string> problems;
  if (!prev.unreadable.empty()) {
    problems.push_back("has a manifest " + shown(manifest_path) + " that rumble cannot use (" +
                       prev.unreadable + ")");
  } else if (!prev.outside.empty()) {
    problems.push_back("has a manifest " + shown(manifest_path) + " that lists \"" +
                       prev.outside.front() + "\", which is no file inside the directory");
  } else if (prev.present && (scenario_.empty() || prev.scenario != scenario_)) {
    problems.push_back(
        "holds the results of another scenario (" +
        (prev.scenario.empty() ? std::string("one not read from a file") : prev.scenario) +
        ", says " + shown(manifest_path) + ")");
  } else if (prev.present && prev.overrides != overrides_) {
    std::vector<std::string> set;
    for (const std::string& o : prev.overrides) set.push_back("--set " + o);
    problems.push_back("holds the results of another run of " + prev.scenario + " (" +
                       (set.empty() ? std::string("without --set") : join(set, " ")) + ", says " +
                       shown(manifest_path) + ")");
  }
  if (!unlisted.empty()) {
    constexpr std::size_t kShown = 5;
    std::vector<std::string> names(unlisted.begin(),
                                   unlisted.begin() + std::min(unlisted.size(), kShown));
    if (unlisted.size() > kShown)
      names.push_back("and " + std::to_string(unlisted.size() - kShown) + " more");
    problems.push_back("holds " + std::to_string(unlisted.size()) +
                       (unlisted.size() == 1 ? " file" : " files") +
                       " that no rumble manifest lists (" + join(names, ", ") + ")" +
                       (prev.present ? "" : ", e.g. the results of an older rumble"));
  }
  if (!problems.empty() && !overwrite) {
    throw ConfigError(
        "results directory " + shown(dir_) + " " + join(problems, " and ") +
        ". A run replaces only the results of the same scenario file and never deletes a file "
        "no manifest lists. Choose another directory (/outputs/directory, or --output DIR), or "
        "pass --overwrite to write here anyway: it removes the files the manifest lists, "
        "replaces the ones this run writes and keeps the rest");
  }

  // Exactly what the previous run listed: files, then its directories when they are empty.
  for (const std::string& f : prev.files) remove_listed(f);
  std::vector<std::string> dirs = prev.directories;
  std::sort(dirs.begin(), dirs.end(),
            [](const std::string& a, const std::string& b) { return a.size() > b.size(); });
  for (const std::string& d : dirs) ::rmdir((dir_ / d).c_str());  // kept when not empty
}

void ResultsDirectory::remove_listed(const std::string& relative) const {
  // Only through real directories: a link standing for one of them is not followed.
  fs::path at = dir_;
  const fs::path rel(relative);
  for (auto part = rel.begin(); part != rel.end(); ++part) {
    at /= *part;
    struct stat st {};
    if (::lstat(at.c_str(), &st) != 0) return;  // gone already
    if (std::next(part) != rel.end()) {
      if (!S_ISDIR(st.st_mode)) return;
    } else if (S_ISDIR(st.st_mode)) {
      return;  // listed as a file, a directory now: not ours to delete
    }
  }
  if (::unlink(at.c_str()) != 0 && errno != ENOENT) {
    const int err = errno;
    throw RunError("cannot remove " + shown(at) + ", which the previous run wrote (listed in " +
                   shown(dir_ / kManifestFile) + "): " + std::strerror(err) +
                   "; check its permissions, or choose another directory with --output DIR");
  }
}

fs::path ResultsDirectory::file(const std::string& relative) {
  if (files_.insert(relative).second) write_manifest();
  return dir_ / relative;
}

fs::path ResultsDirectory::subdirectory(const std::string& relative) {
  const fs::path path = dir_ / relative;
  if (directories_.insert(relative).second) write_manifest();
  struct stat st {};
  if (::lstat(path.c_str(), &st) == 0 && S_ISDIR(st.st_mode)) return path;
  if ((::unlink(path.c_str()) != 0 && errno != ENOENT) || ::mkdir(path.c_str(), 0777) != 0) {
    const int err = errno;
    throw RunError("cannot create " + shown(path) + ": " + std::strerror(err) +
                   "; check that the results directory is writable");
  }
  return path;
}

void ResultsDirectory::list_new_files() {
  bool changed = false;
  for (const Entry& e : scan(dir_, [](const std::string&) { return true; })) {
    const auto was = before_.find(e.relative);
    if (e.directory) {
      if (was == before_.end() && directories_.insert(e.relative).second) changed = true;
      continue;
    }
    if (files_.count(e.relative) != 0) continue;
    if (was != before_.end() && was->second == std::make_pair(e.dev, e.ino)) continue;  // kept
    files_.insert(e.relative);
    changed = true;
  }
  if (changed) write_manifest();
}

void ResultsDirectory::write_manifest() const {
  json m;
  m["about"] =
      "what the last rumble run wrote here; the next run of the same scenario file removes "
      "exactly these before it writes (docs/scenario.md)";
  m["version"] = kManifestVersion;
  m["scenario_file"] = scenario_.empty() ? json(nullptr) : json(scenario_);
  if (!overrides_.empty()) m["overrides"] = overrides_;
  m["files"] = files_;
  m["directories"] = directories_;
  replace_file(dir_ / kManifestFile, dir_ / kManifestTmp, m.dump(2) + "\n");
}

}  // namespace rumble
