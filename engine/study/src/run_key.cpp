#include "study/run_key.hpp"

#include <fstream>
#include <set>
#include <vector>

#include "core/input_file.hpp"
#include "plugin/registry.hpp"
#include "study/sha256.hpp"

namespace rumble::study {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

/// A piece with its length first, so that no two sequences of pieces hash alike.
void piece(Sha256& h, std::string_view label, std::string_view bytes) {
  h.update(label);
  h.update(std::string_view("\0", 1));
  h.update(std::to_string(bytes.size()));
  h.update(std::string_view("\0", 1));
  h.update(bytes);
}

/// Every "type" string of an object and every "file" string at any depth of a "params" object
/// (an mbs vehicle's params/file, a FEM soil's params/mesh/file), below `v`.
void collect(const json& v, bool in_params, std::set<std::string>& types,
             std::set<std::string>& files) {
  if (v.is_object()) {
    for (const auto& [key, child] : v.items()) {
      if (key == "type" && child.is_string()) types.insert(child.get<std::string>());
      if (in_params && key == "file" && child.is_string()) files.insert(child.get<std::string>());
      collect(child, in_params || key == "params", types, files);
    }
  } else if (v.is_array()) {
    for (const json& child : v) collect(child, in_params, types, files);
  }
}

/// The SHA-256 of a file's bytes, read in 1 MiB pieces: a FEM soil's mesh file may be hundreds
/// of megabytes, which the key need not hold at once.
std::string file_digest(const fs::path& p) {
  // Regular files only: a FIFO would wait for a writer, a device never end (any size: the digest
  // reads in pieces).
  if (!input_file_problem(p, UINTMAX_MAX).empty()) return "(unreadable)";
  std::ifstream in(p, std::ios::binary);
  if (!in) return "(unreadable)";
  Sha256 h;
  std::vector<char> chunk(std::size_t{1} << 20);
  while (in) {
    in.read(chunk.data(), static_cast<std::streamsize>(chunk.size()));
    h.update(std::string_view(chunk.data(), static_cast<std::size_t>(in.gcount())));
  }
  return h.hex();
}

}  // namespace

std::string run_key(const PlannedRun& run, const scenario::Document& resolved,
                    const PluginRegistry& registry) {
  Sha256 h;
  piece(h, "rumble", RUMBLE_VERSION);
  piece(h, "scenario", resolved.json.dump(-1, ' ', false, json::error_handler_t::replace));
  piece(h, "scenario file", resolved.text);
  piece(h, "study entry", run.entry.dump(-1, ' ', false, json::error_handler_t::replace));
  std::set<std::string> types, files;
  collect(resolved.json, false, types, files);
  for (const std::string& f : files) {
    const fs::path p = fs::path(f).is_absolute() ? fs::path(f) : resolved.path.parent_path() / f;
    std::error_code ec;
    piece(h, "file " + f, fs::is_regular_file(p, ec) ? file_digest(p) : "(not a file)");
  }
  for (const std::string& t : types) {
    for (const rumble_kind kind : {RUMBLE_KIND_VEHICLE, RUMBLE_KIND_SOIL, RUMBLE_KIND_COUPLER}) {
      const ComponentType* type = registry.find(kind, t);
      if (type == nullptr) continue;
      const PluginIdentity& id = type->library->identity;
      piece(h, std::string("plugin ") + kind_name(kind) + " " + t, id.name + " " + id.version);
    }
  }
  return h.hex();
}

}  // namespace rumble::study
