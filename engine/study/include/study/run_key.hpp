// The key of a study run: what its results depend on, hashed (SHA-256). Equal keys mean the
// results in the run's directory are those this run would compute again. docs/study.md.
#pragma once

#include <string>

#include "scenario/document.hpp"
#include "study/expansion.hpp"

namespace rumble {
class PluginRegistry;
}

namespace rumble::study {

/// SHA-256 (hex) over: the rumble version; the resolved scenario (the file with the run's
/// patches, validated, defaults filled, dumped with sorted keys); the scenario file's bytes; the
/// bytes of the files that components' params name as "file" at any depth (an mbs vehicle's
/// definition, a FEM soil's mesh.file), relative to the scenario's folder; the study file's entry
/// for the run; and every plugin type the scenario names, with its plugin's name and version.
std::string run_key(const PlannedRun& run, const scenario::Document& resolved,
                    const PluginRegistry& registry);

}  // namespace rumble::study
