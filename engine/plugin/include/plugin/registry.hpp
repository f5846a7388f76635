// Plugin loading (Boost.DLL) and the registry of component types found in plugin libraries.
//
// A library with a manifest (manifest.hpp) is registered from it and loaded only when one of its
// factories is first used; one without is loaded when it is registered. A library, once loaded,
// stays loaded while anything holds it: the registry does, and every instance created from it
// holds a shared_ptr to it as well (see instance.hpp), so code is never unmapped while an object
// made by it lives.
#pragma once

#include <rumble/abi.h>

#include <cstdint>
#include <filesystem>
#include <memory>
#include <mutex>
#include <string>
#include <string_view>
#include <vector>

namespace boost::dll {
class shared_library;
}

namespace rumble {

/// "vehicle", "soil", "coupler".
const char* kind_name(rumble_kind kind);

/// What a plugin library says of itself: its descriptor's header (abi.h).
struct PluginIdentity {
  std::string name;
  std::string version;
  std::string build_fingerprint;
  std::uint32_t abi_major = 0;
  std::uint32_t abi_minor = 0;
  std::string abi() const { return std::to_string(abi_major) + "." + std::to_string(abi_minor); }
};

struct ComponentType;

/// A plugin library the registry knows: loaded, or known from its manifest (manifest.hpp) and
/// loaded at the first use of one of its factories. Once loaded it stays loaded while anything
/// holds this object: every ComponentType, and through it every instance, holds it. Thread-safe.
class LoadedLibrary {
 public:
  LoadedLibrary(std::filesystem::path path, std::string origin, PluginIdentity identity);
  ~LoadedLibrary();
  LoadedLibrary(const LoadedLibrary&) = delete;
  LoadedLibrary& operator=(const LoadedLibrary&) = delete;

  const std::filesystem::path path;
  /// Where the path came from: "engine plugin directory", "RUMBLE_PLUGIN_PATH",
  /// "scenario /plugins/0", or "named directly" (tests, tools).
  const std::string origin;
  const PluginIdentity identity;

  /// The descriptor's factory `index`. Loads the library first if it is not loaded, and then
  /// throws PluginLoadError when it cannot be loaded or is no longer what its manifest listed.
  const rumble_factory& factory(std::size_t index) const;
  bool loaded() const;

 private:
  friend class PluginRegistry;  // sets what the load or the manifest gave
  void load() const;            // with mutex_ held
  mutable std::mutex mutex_;
  mutable std::shared_ptr<boost::dll::shared_library> library_;
  mutable std::vector<const rumble_factory*> factories_;
  /// The types its manifest listed (without `library`), checked against the factories when it
  /// is loaded.
  std::vector<ComponentType> listed_;
};

/// A library or RUMBLE_PLUGIN_PATH entry of the default search that could not be loaded: it is
/// reported and skipped, so that one bad file does not stop every command.
struct SkippedPlugin {
  std::filesystem::path path;
  std::string origin;  // as LoadedLibrary::origin
  std::string reason;  // the PluginLoadError text
};

/// What a component type offers and needs (rumble_capabilities), as the engine uses it.
struct Capabilities {
  std::uint64_t offers = 0;              // RUMBLE_CAP_* bits
  std::uint64_t soil_needs = 0;          // coupler: bits every soil participant must offer
  double max_macro_step = 0.0;           // [s], 0: no limit
  std::string participants_json = "{}";  // coupler: extra participants (abi.h)
  /// False for an ABI 1.0 factory: offers were derived from non-null optional functions and
  /// save/restore is only known at run time (state_size > 0).
  bool declared = false;
  bool has(std::uint64_t bits) const { return (offers & bits) == bits; }
};

struct ComponentType {
  rumble_kind kind{};
  std::string type_name;
  std::string summary;
  std::string params_schema = "{}";  // JSON Schema text, as the plugin declared it
  bool schema_declared = false;      // false: the factory gave none ("{}" above)
  std::shared_ptr<const LoadedLibrary> library;
  std::size_t index = 0;  // the factory's place in the library's descriptor
  /// A type made in code without a library (tests of the adapter): its factory. One of it and
  /// `library` is set.
  const rumble_factory* unlisted_factory = nullptr;
  Capabilities capabilities;
  std::uint32_t abi_minor = 0;  // the ABI minor the plugin was built for

  /// The plugin's factory; loads its library at the first use (LoadedLibrary::factory).
  const rumble_factory& factory() const {
    return library ? library->factory(index) : *unlisted_factory;
  }
};

class PluginRegistry {
 public:
  /// How libraries with a manifest are taken: from it, loaded at their first use (the default),
  /// or loaded at once (`rumble plugins`, which reports every library that cannot load).
  enum class Manifests { kUse, kIgnore };
  explicit PluginRegistry(Manifests manifests = Manifests::kUse) : manifests_(manifests) {}

  /// Registers one library's types, from its manifest or else by loading it. Throws
  /// PluginLoadError with the exact reason: file not found, not a Rumble plugin, ABI major
  /// mismatch, newer minor, duplicate type. Only regular files are loaded (a FIFO or device
  /// would block or mislead dlopen).
  void load_library(const std::filesystem::path& path,
                    const std::string& origin = "named directly");
  /// Loads every *.so in each directory (non-existent directories are skipped); throws at the
  /// first library that cannot be loaded.
  void load_directory(const std::filesystem::path& dir);
  /// The default search: the engine's own plugin directory, then RUMBLE_PLUGIN_PATH
  /// (':'-separated directories or files). Never throws for one bad library or entry: each is
  /// logged as a warning and listed in skipped(), and the search goes on.
  void load_default_directories();
  const std::vector<SkippedPlugin>& skipped() const { return skipped_; }

  const ComponentType* find(rumble_kind kind, std::string_view type_name) const;
  /// Sorted type names of one kind.
  std::vector<std::string> type_names(rumble_kind kind) const;
  const std::vector<ComponentType>& types() const { return types_; }
  const std::vector<std::shared_ptr<const LoadedLibrary>>& libraries() const { return libraries_; }

  /// Directory of the engine's own plugins: <dir of executable>/../lib/rumble/plugins.
  static std::filesystem::path builtin_plugin_directory();

 private:
  bool already_loaded(const std::filesystem::path& canonical) const;
  void add(const std::shared_ptr<LoadedLibrary>& library, std::vector<ComponentType> types);
  Manifests manifests_;
  void skip(const std::filesystem::path& path, const std::string& origin, std::string reason);
  std::vector<std::shared_ptr<const LoadedLibrary>> libraries_;
  std::vector<ComponentType> types_;
  std::vector<SkippedPlugin> skipped_;
};

}  // namespace rumble
