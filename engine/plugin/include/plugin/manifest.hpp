// A plugin library's manifest: what its descriptor says (the plugin's name and version, each
// type's kind, name, summary, params schema and capabilities), written next to the library when
// it is built (`rumble plugins --manifest`, called by rumble_add_plugin()), so that the registry
// knows the library's types without loading it (docs/plugin-guide.md, "The manifest").
//
// Loading a library costs what its dependencies cost: the FEM soil's gmsh and PETSc bring about
// 400 shared libraries, 0.3 s of every `rumble` command. With the manifests a command loads only
// the libraries whose types it creates. A manifest is used only for the very link it was written
// from (the same ELF build ID); otherwise the library is loaded as if it had none.
#pragma once

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "plugin/registry.hpp"

namespace rumble {

/// The file `<library>.manifest.json` next to the library.
std::filesystem::path manifest_path(const std::filesystem::path& library);

/// The GNU build ID of an ELF file in hex ("" when the file has none or is no 64-bit ELF): the
/// linker's hash of the link, kept by strip and by copies.
std::string elf_build_id(const std::filesystem::path& file);

/// A manifest as read: the library's identity and types (library and index set, factory not).
struct Manifest {
  PluginIdentity identity;
  std::vector<ComponentType> types;
};

/// The manifest of an opened library and its types (JSON text).
std::string manifest_text(const LoadedLibrary& library, const std::vector<ComponentType>& types);

/// The manifest of the library at `path` when there is one written for this very file (same
/// build ID) by an engine of this ABI major and no newer minor; nullopt otherwise, and the
/// library is then loaded to learn its types. Never throws: a damaged manifest only costs the
/// load it would have saved (it is logged at debug level).
std::optional<Manifest> read_manifest(const std::filesystem::path& path);

/// "" when `listed` (from the manifest) is `found` (from the library once loaded), else the
/// first difference, for the message that the manifest is stale.
std::string manifest_difference(const ComponentType& listed, const ComponentType& found);

}  // namespace rumble
