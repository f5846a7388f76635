#include "plugin/registry.hpp"

#include <algorithm>
#include <boost/dll/runtime_symbol_info.hpp>
#include <boost/dll/shared_library.hpp>
#include <cstddef>
#include <cstdlib>
#include <nlohmann/json.hpp>
#include <optional>
#include <span>
#include <sstream>

#include "core/errors.hpp"
#include "core/input_file.hpp"
#include "core/logging.hpp"
#include "core/malloc_policy.hpp"
#include "plugin/abi_adapter.hpp"
#include "plugin/function_table.hpp"
#include "plugin/manifest.hpp"

namespace rumble {
namespace {

namespace fs = std::filesystem;
namespace dll = boost::dll;

std::string quoted(const fs::path& p) {
  return "'" + p.string() + "'";
}

/// What a path that is no regular file is, for messages.
/// The *.so regular files of dir, sorted (deterministic order, so duplicate errors are too);
/// none when dir is not a directory.
std::vector<fs::path> library_files(const fs::path& dir) {
  std::error_code ec;
  std::vector<fs::path> files;
  if (!fs::is_directory(dir, ec)) return files;
  for (const auto& entry : fs::directory_iterator(dir, ec)) {
    if (entry.is_regular_file(ec) && entry.path().extension() == ".so")
      files.push_back(entry.path());
  }
  std::sort(files.begin(), files.end());
  return files;
}

/// Boost.DLL appends a stale errno ("...: Bad file descriptor"); keep dlerror's text only.
std::string clean_load_error(std::string what) {
  const std::string marker = "dlerror system message: ";
  const auto start = what.find(marker);
  if (start == std::string::npos) return what;
  std::string inner = what.substr(start + marker.size());
  const auto close = inner.rfind(')');
  if (close != std::string::npos) inner.resize(close);
  return inner;
}

/// The canonical path of the plugin file `requested`, which must exist and be a regular file:
/// dlopen on a FIFO blocks until a writer comes, on a device reads it.
fs::path regular_library_file(const fs::path& requested) {
  std::error_code ec;
  if (!fs::exists(requested, ec)) {
    throw PluginLoadError("plugin " + quoted(requested) +
                          ": file not found; check the path (relative paths are relative to the "
                          "scenario file) or RUMBLE_PLUGIN_PATH");
  }
  const fs::path path = fs::canonical(requested, ec);
  if (const auto status = fs::status(path, ec); !fs::is_regular_file(status)) {
    throw PluginLoadError("plugin " + quoted(requested) + ": " + file_kind(status) +
                          ", not a regular file; name a shared library (.so) file");
  }
  return path;
}

/// The library at `path` loaded, with Rumble's entry point.
std::shared_ptr<dll::shared_library> open_plugin_library(const fs::path& path) {
  auto library = std::make_shared<dll::shared_library>();
  try {
    // rtld_now: an unresolved symbol is a load error here, not a crash later
    // (docs/toolchain.md §3).
    library->load(dll::fs::path(path), dll::load_mode::rtld_now | dll::load_mode::rtld_local);
    // Its libraries may have told malloc to keep what is freed (core/malloc_policy.hpp).
    return_freed_memory();
  } catch (const std::exception& e) {
    throw PluginLoadError("plugin " + quoted(path) +
                          ": cannot be loaded: " + clean_load_error(e.what()));
  }
  if (!library->has(RUMBLE_PLUGIN_ENTRY_SYMBOL)) {
    throw PluginLoadError("plugin " + quoted(path) + ": not a Rumble plugin (no '" +
                          std::string(RUMBLE_PLUGIN_ENTRY_SYMBOL) +
                          "' entry point); was it built with rumble_add_plugin() and "
                          "RUMBLE_PLUGIN()?");
  }
  return library;
}

/// The library's descriptor, of an ABI this engine reads, well formed and with factories.
const rumble_plugin_descriptor* plugin_descriptor(const dll::shared_library& library,
                                                  const fs::path& path) {
  const auto entry = library.get<const rumble_plugin_descriptor*()>(RUMBLE_PLUGIN_ENTRY_SYMBOL);
  const rumble_plugin_descriptor* d = entry();
  if (d == nullptr) {
    throw PluginLoadError("plugin " + quoted(path) + ": entry point returned no descriptor");
  }
  const std::string host_abi =
      std::to_string(RUMBLE_ABI_MAJOR) + "." + std::to_string(RUMBLE_ABI_MINOR);
  const std::string plugin_abi = std::to_string(d->abi_major) + "." + std::to_string(d->abi_minor);
  if (d->abi_major != RUMBLE_ABI_MAJOR) {
    throw PluginLoadError("plugin " + quoted(path) + ": built for plugin ABI " + plugin_abi +
                          ", this engine has ABI " + host_abi + " (the major versions differ); " +
                          "rebuild the plugin against Rumble SDK " +
                          std::to_string(RUMBLE_ABI_MAJOR) + ".x");
  }
  if (d->abi_minor > RUMBLE_ABI_MINOR) {
    throw PluginLoadError("plugin " + quoted(path) + ": built for plugin ABI " + plugin_abi +
                          ", newer than this engine's ABI " + host_abi +
                          "; upgrade Rumble or rebuild the plugin against this engine's SDK");
  }
  // A later 1.x appends fields, so a descriptor is only required to hold those of ABI 1.0.
  constexpr std::size_t kDescriptorV1_0 =
      offsetof(rumble_plugin_descriptor, factories) + sizeof(d->factories);
  if (d->struct_size < kDescriptorV1_0 || (d->factories == nullptr && d->n_factories > 0)) {
    const std::string defect =
        d->struct_size < kDescriptorV1_0
            ? "struct_size " + std::to_string(d->struct_size) + " bytes, ABI 1.0 needs " +
                  std::to_string(kDescriptorV1_0)
            : "n_factories is " + std::to_string(d->n_factories) + " but factories is null";
    throw PluginLoadError("plugin " + quoted(path) + ": malformed descriptor (" + defect +
                          "); build the plugin with RUMBLE_PLUGIN() from the Rumble SDK");
  }
  if (d->n_factories == 0) {
    throw PluginLoadError("plugin " + quoted(path) +
                          ": provides no component types (n_factories is 0); list the plugin's "
                          "classes in RUMBLE_PLUGIN(name, version, Classes...)");
  }
  return d;
}

constexpr std::size_t kFactoryV1_0 =
    offsetof(rumble_factory, api) + sizeof(static_cast<rumble_factory*>(nullptr)->api);

/// The factories lie the plugin's sizeof(rumble_factory) apart, which a later 1.x may make
/// larger than this host's: step by the size the plugin states (the first factory's), read only
/// the 1.0 fields.
const rumble_factory& factory_at(const rumble_plugin_descriptor& d, std::uint64_t i) {
  const std::size_t stride = d.factories[0].struct_size;
  return *reinterpret_cast<const rumble_factory*>(reinterpret_cast<const char*>(d.factories) +
                                                  i * std::max(stride, kFactoryV1_0));
}

/// A plugin's kind is an int32_t until it is known to be one of the enum's values: casting
/// any other number to rumble_kind is undefined behaviour (Clang's UBSan stops there).
bool known_kind(const rumble_factory& f) {
  return f.kind == RUMBLE_KIND_VEHICLE || f.kind == RUMBLE_KIND_SOIL ||
         f.kind == RUMBLE_KIND_COUPLER;
}

rumble_kind kind_of(const rumble_factory& f) {
  return known_kind(f) ? static_cast<rumble_kind>(f.kind) : RUMBLE_KIND_VEHICLE;
}

/// "" when the factory is well formed for the descriptor's ABI, else what is wrong.
std::string factory_defect(const rumble_factory& f, const rumble_plugin_descriptor& d) {
  const std::size_t stride = d.factories[0].struct_size;
  std::string defect;
  if (f.struct_size < kFactoryV1_0) {
    defect = "struct_size " + std::to_string(f.struct_size) + " bytes, ABI 1.0 needs " +
             std::to_string(kFactoryV1_0);
  } else if (f.struct_size != stride) {
    defect = "struct_size " + std::to_string(f.struct_size) + " bytes, the first factory's is " +
             std::to_string(stride) + " (all entries of the array have one size)";
  } else if (f.type_name == nullptr) {
    defect = "no type name";
  } else if (!known_kind(f)) {
    defect = "unknown kind " + std::to_string(f.kind);
  } else if (f.create == nullptr) {
    defect = "no create function";
  } else if (f.api == nullptr) {
    defect = "no function table";
  } else {
    defect = function_table_defect(kind_of(f), f.api, d.abi_minor);
  }
  if (defect.empty()) defect = factory_capabilities_defect(f, d.abi_minor);
  return defect;
}

/// Throws when factory i of the library at `path` is malformed.
void check_factory(const rumble_factory& f, std::uint64_t i, const rumble_plugin_descriptor& d,
                   const fs::path& path) {
  const std::string defect = factory_defect(f, d);
  if (defect.empty()) return;
  throw PluginLoadError("plugin " + quoted(path) + ": factory " + std::to_string(i) +
                        (f.struct_size >= kFactoryV1_0 && f.type_name != nullptr
                             ? " ('" + std::string(f.type_name) + "')"
                             : std::string()) +
                        " is malformed: " + defect +
                        "; build the plugin with RUMBLE_PLUGIN() from the Rumble SDK");
}

/// Throws when a type of the name is among those loaded before or added from this library.
void check_unique_type(const std::string& type_name, std::span<const ComponentType> loaded_before,
                       std::span<const ComponentType> added, const fs::path& path) {
  for (const auto existing : {loaded_before, added}) {
    for (const ComponentType& t : existing) {
      if (t.type_name == type_name) {
        throw PluginLoadError("plugin " + quoted(path) + ": type '" + type_name +
                              "' is already provided by " +
                              quoted(t.library ? t.library->path : path) +
                              "; type names must be unique: rename one, or remove one "
                              "library from the plugin path");
      }
    }
  }
}

ComponentType component_type(const rumble_factory& f, std::size_t index, std::uint32_t abi_minor) {
  ComponentType t;
  t.kind = kind_of(f);
  t.type_name = f.type_name;
  t.summary = f.summary != nullptr ? f.summary : "";
  t.schema_declared = f.params_schema != nullptr;
  t.params_schema = t.schema_declared ? f.params_schema : "{}";
  t.index = index;
  t.abi_minor = abi_minor;
  t.capabilities = abi::capabilities_of(t.kind, f);
  return t;
}

/// A library loaded and checked: its handle, identity, factories and their types (`library`
/// not set).
struct OpenedLibrary {
  std::shared_ptr<dll::shared_library> library;
  PluginIdentity identity;
  std::vector<const rumble_factory*> factories;
  std::vector<ComponentType> types;
};

OpenedLibrary open_library(const fs::path& path) {
  OpenedLibrary opened;
  opened.library = open_plugin_library(path);
  const rumble_plugin_descriptor* d = plugin_descriptor(*opened.library, path);
  opened.identity = {d->plugin_name != nullptr ? d->plugin_name : "",
                     d->plugin_version != nullptr ? d->plugin_version : "",
                     d->build_fingerprint != nullptr ? d->build_fingerprint : "", d->abi_major,
                     d->abi_minor};
  for (std::uint64_t i = 0; i < d->n_factories; ++i) {
    const rumble_factory& f = factory_at(*d, i);
    check_factory(f, i, *d, path);
    opened.factories.push_back(&f);
    opened.types.push_back(component_type(f, opened.types.size(), d->abi_minor));
  }
  return opened;
}

/// Throws when the library, loaded, is not what its manifest listed.
void check_listed(const fs::path& path, const std::vector<ComponentType>& listed,
                  const std::vector<ComponentType>& found) {
  std::string difference;
  if (listed.size() != found.size()) {
    difference = "it lists " + std::to_string(listed.size()) + " types, the library has " +
                 std::to_string(found.size());
  }
  for (std::size_t i = 0; i < listed.size() && difference.empty(); ++i)
    difference = manifest_difference(listed[i], found[i]);
  if (difference.empty()) return;
  throw PluginLoadError("plugin " + quoted(path) + ": not what its manifest " +
                        quoted(manifest_path(path)) + " lists (" + difference +
                        "); rebuild the plugin, whose build writes the manifest, or delete the "
                        "manifest");
}

}  // namespace

const char* kind_name(rumble_kind kind) {
  switch (kind) {
    case RUMBLE_KIND_VEHICLE:
      return "vehicle";
    case RUMBLE_KIND_SOIL:
      return "soil";
    case RUMBLE_KIND_COUPLER:
      return "coupler";
  }
  return "unknown";
}

fs::path PluginRegistry::builtin_plugin_directory() {
  const fs::path exe = dll::program_location();
  return exe.parent_path().parent_path() / "lib" / "rumble" / "plugins";
}

bool PluginRegistry::already_loaded(const fs::path& canonical) const {
  return std::any_of(libraries_.begin(), libraries_.end(),
                     [&](const auto& lib) { return lib->path == canonical; });
}

LoadedLibrary::LoadedLibrary(fs::path path_in, std::string origin_in, PluginIdentity identity_in)
    : path(std::move(path_in)), origin(std::move(origin_in)), identity(std::move(identity_in)) {}

LoadedLibrary::~LoadedLibrary() = default;

const rumble_factory& LoadedLibrary::factory(std::size_t index) const {
  const std::lock_guard<std::mutex> lock(mutex_);
  if (!library_) load();
  return *factories_.at(index);
}

bool LoadedLibrary::loaded() const {
  const std::lock_guard<std::mutex> lock(mutex_);
  return library_ != nullptr;
}

void LoadedLibrary::load() const {
  OpenedLibrary opened = open_library(path);
  check_listed(path, listed_, opened.types);
  factories_ = std::move(opened.factories);
  library_ = std::move(opened.library);
  logger("plugins")->debug("loaded {} at its first use", path.string());
}

void PluginRegistry::load_library(const fs::path& requested, const std::string& origin) {
  const fs::path path = regular_library_file(requested);
  if (already_loaded(path)) return;
  if (manifests_ == Manifests::kUse) {
    if (std::optional<Manifest> manifest = read_manifest(path)) {
      auto library = std::make_shared<LoadedLibrary>(path, origin, manifest->identity);
      library->listed_ = manifest->types;
      add(library, std::move(manifest->types));
      return;
    }
  }
  OpenedLibrary opened = open_library(path);
  auto library = std::make_shared<LoadedLibrary>(path, origin, opened.identity);
  library->factories_ = std::move(opened.factories);
  library->library_ = std::move(opened.library);
  add(library, std::move(opened.types));
}

void PluginRegistry::add(const std::shared_ptr<LoadedLibrary>& library,
                         std::vector<ComponentType> types) {
  for (std::size_t i = 0; i < types.size(); ++i) {
    check_unique_type(types[i].type_name, types_, std::span(types).first(i), library->path);
    types[i].library = library;
  }
  libraries_.push_back(library);
  types_.insert(types_.end(), types.begin(), types.end());
}

void PluginRegistry::load_directory(const fs::path& dir) {
  for (const fs::path& f : library_files(dir)) load_library(f);
}

void PluginRegistry::load_default_directories() {
  // One bad library must not stop `rumble plugins` (or a scenario that does not need it):
  // each failure is reported and skipped. A scenario using one of its types then fails at
  // validation with "unknown type", whose hint names what was skipped.
  const auto load = [&](const fs::path& file, const std::string& origin) {
    try {
      load_library(file, origin);
    } catch (const PluginLoadError& e) {
      skip(file, origin, e.what());
    }
  };
  for (const fs::path& f : library_files(builtin_plugin_directory()))
    load(f, "engine plugin directory");
  if (const char* env = std::getenv("RUMBLE_PLUGIN_PATH"); env != nullptr) {
    std::stringstream ss(env);
    std::string item;
    while (std::getline(ss, item, ':')) {
      if (item.empty()) continue;
      const fs::path p(item);
      std::error_code ec;
      if (fs::is_directory(p, ec)) {
        for (const fs::path& f : library_files(p)) load(f, "RUMBLE_PLUGIN_PATH");
      } else if (!fs::exists(p, ec)) {
        skip(p, "RUMBLE_PLUGIN_PATH",
             "RUMBLE_PLUGIN_PATH entry '" + item +
                 "': no such file or directory; correct or remove the entry");
      } else {
        load(p, "RUMBLE_PLUGIN_PATH");  // a library file named in RUMBLE_PLUGIN_PATH
      }
    }
  }
}

void PluginRegistry::skip(const fs::path& path, const std::string& origin, std::string reason) {
  logger("plugins")->warn("{} (from {}); skipped, the other plugins are loaded", reason, origin);
  skipped_.push_back({path, origin, std::move(reason)});
}

const ComponentType* PluginRegistry::find(rumble_kind kind, std::string_view type_name) const {
  for (const ComponentType& t : types_) {
    if (t.kind == kind && t.type_name == type_name) return &t;
  }
  return nullptr;
}

std::vector<std::string> PluginRegistry::type_names(rumble_kind kind) const {
  std::vector<std::string> names;
  for (const ComponentType& t : types_) {
    if (t.kind == kind) names.push_back(t.type_name);
  }
  std::sort(names.begin(), names.end());
  return names;
}

}  // namespace rumble
