#include "plugin/manifest.hpp"

#include <elf.h>

#include <cstring>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "core/logging.hpp"

namespace rumble {
namespace {

namespace fs = std::filesystem;

/// The manifest's format; a reader ignores any other.
constexpr int kManifestFormat = 1;

/// `size` bytes of `file` at `offset`, or nothing when the file is shorter.
std::string read_at(std::ifstream& file, std::uint64_t offset, std::uint64_t size) {
  std::string bytes(size, '\0');
  file.seekg(static_cast<std::streamoff>(offset));
  if (!file.read(bytes.data(), static_cast<std::streamsize>(size))) return {};
  return bytes;
}

/// The GNU build ID among the notes of one PT_NOTE segment, in hex; "" when it has none.
std::string build_id_note(const std::string& notes) {
  std::size_t at = 0;
  const auto align4 = [](std::size_t n) { return (n + 3) & ~std::size_t{3}; };
  while (at + sizeof(Elf64_Nhdr) <= notes.size()) {
    Elf64_Nhdr header;
    std::memcpy(&header, notes.data() + at, sizeof header);
    const std::size_t name_at = at + sizeof header;
    const std::size_t desc_at = name_at + align4(header.n_namesz);
    if (desc_at + header.n_descsz > notes.size()) return {};
    if (header.n_type == NT_GNU_BUILD_ID && header.n_namesz == 4 &&
        std::memcmp(notes.data() + name_at, "GNU", 4) == 0) {
      std::ostringstream hex;
      for (std::size_t i = 0; i < header.n_descsz; ++i)
        hex << "0123456789abcdef"[static_cast<unsigned char>(notes[desc_at + i]) >> 4]
            << "0123456789abcdef"[static_cast<unsigned char>(notes[desc_at + i]) & 15];
      return hex.str();
    }
    at = desc_at + align4(header.n_descsz);
  }
  return {};
}

nlohmann::json type_json(const ComponentType& t) {
  const Capabilities& c = t.capabilities;
  return {{"kind", kind_name(t.kind)},
          {"type", t.type_name},
          {"summary", t.summary},
          {"params_schema", t.schema_declared ? nlohmann::json(t.params_schema) : nullptr},
          {"abi_minor", t.abi_minor},
          {"capabilities",
           {{"declared", c.declared},
            {"offers", c.offers},
            {"soil_needs", c.soil_needs},
            {"max_macro_step", c.max_macro_step},
            {"participants", c.participants_json}}}};
}

rumble_kind kind_named(const std::string& name) {
  for (const rumble_kind kind : {RUMBLE_KIND_VEHICLE, RUMBLE_KIND_SOIL, RUMBLE_KIND_COUPLER})
    if (name == kind_name(kind)) return kind;
  throw std::runtime_error("unknown kind '" + name + "'");
}

ComponentType type_of(const nlohmann::json& j, std::size_t index) {
  ComponentType t;
  t.kind = kind_named(j.at("kind").get<std::string>());
  t.type_name = j.at("type").get<std::string>();
  t.summary = j.at("summary").get<std::string>();
  t.schema_declared = !j.at("params_schema").is_null();
  t.params_schema = t.schema_declared ? j.at("params_schema").get<std::string>() : "{}";
  t.index = index;
  t.abi_minor = j.at("abi_minor").get<std::uint32_t>();
  const nlohmann::json& c = j.at("capabilities");
  t.capabilities.declared = c.at("declared").get<bool>();
  t.capabilities.offers = c.at("offers").get<std::uint64_t>();
  t.capabilities.soil_needs = c.at("soil_needs").get<std::uint64_t>();
  t.capabilities.max_macro_step = c.at("max_macro_step").get<double>();
  t.capabilities.participants_json = c.at("participants").get<std::string>();
  return t;
}

/// The manifest of the library at `path`; throws for one that is damaged, or not written for
/// this file and this engine's ABI.
Manifest parse_manifest(const fs::path& path, const nlohmann::json& j) {
  if (j.at("rumble_plugin_manifest").get<int>() != kManifestFormat)
    throw std::runtime_error("another manifest format");
  const std::string id = j.at("build_id").get<std::string>();
  if (id.empty() || id != elf_build_id(path))
    throw std::runtime_error("written for another build of the library");
  Manifest m;
  const nlohmann::json& plugin = j.at("plugin");
  m.identity = {plugin.at("name").get<std::string>(), plugin.at("version").get<std::string>(),
                plugin.at("build").get<std::string>(), plugin.at("abi_major").get<std::uint32_t>(),
                plugin.at("abi_minor").get<std::uint32_t>()};
  if (m.identity.abi_major != RUMBLE_ABI_MAJOR || m.identity.abi_minor > RUMBLE_ABI_MINOR)
    throw std::runtime_error("for plugin ABI " + m.identity.abi() + ", which loading explains");
  for (const nlohmann::json& t : j.at("types")) m.types.push_back(type_of(t, m.types.size()));
  if (m.types.empty()) throw std::runtime_error("no types");
  return m;
}

}  // namespace

fs::path manifest_path(const fs::path& library) {
  return fs::path(library.string() + ".manifest.json");
}

std::string elf_build_id(const fs::path& path) {
  std::ifstream file(path, std::ios::binary);
  Elf64_Ehdr header;
  if (!file.read(reinterpret_cast<char*>(&header), sizeof header)) return {};
  if (std::memcmp(header.e_ident, ELFMAG, SELFMAG) != 0 || header.e_ident[EI_CLASS] != ELFCLASS64 ||
      header.e_phentsize != sizeof(Elf64_Phdr))
    return {};
  for (std::size_t i = 0; i < header.e_phnum; ++i) {
    Elf64_Phdr segment;
    const std::string bytes = read_at(file, header.e_phoff + i * sizeof segment, sizeof segment);
    if (bytes.size() != sizeof segment) return {};
    std::memcpy(&segment, bytes.data(), sizeof segment);
    if (segment.p_type != PT_NOTE || segment.p_filesz > (1u << 20)) continue;
    const std::string id = build_id_note(read_at(file, segment.p_offset, segment.p_filesz));
    if (!id.empty()) return id;
  }
  return {};
}

std::string manifest_text(const LoadedLibrary& library, const std::vector<ComponentType>& types) {
  nlohmann::json listed = nlohmann::json::array();
  for (const ComponentType& t : types)
    if (t.library.get() == &library) listed.push_back(type_json(t));
  const PluginIdentity& id = library.identity;
  const nlohmann::json j = {{"rumble_plugin_manifest", kManifestFormat},
                            {"build_id", elf_build_id(library.path)},
                            {"plugin",
                             {{"name", id.name},
                              {"version", id.version},
                              {"build", id.build_fingerprint},
                              {"abi_major", id.abi_major},
                              {"abi_minor", id.abi_minor}}},
                            {"types", listed}};
  return j.dump(2) + '\n';
}

std::optional<Manifest> read_manifest(const fs::path& path) {
  const fs::path file = manifest_path(path);
  std::error_code ec;
  if (!fs::is_regular_file(file, ec)) return std::nullopt;
  try {
    std::ifstream in(file);
    return parse_manifest(path, nlohmann::json::parse(in));
  } catch (const std::exception& e) {
    logger("plugins")->debug("{}: not used ({}); the library is loaded to learn its types",
                             file.string(), e.what());
    return std::nullopt;
  }
}

std::string manifest_difference(const ComponentType& listed, const ComponentType& found) {
  const nlohmann::json a = type_json(listed);
  const nlohmann::json b = type_json(found);
  if (a == b) return {};
  for (const auto& [key, value] : a.items())
    if (b.at(key) != value) return "type '" + listed.type_name + "': its " + key + " differs";
  return "type '" + listed.type_name + "' differs";
}

}  // namespace rumble
