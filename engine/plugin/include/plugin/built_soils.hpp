// How a soil comes to be: built from its params and laid on the track's footprints, by one
// function for validation, the run and the commands that look at a soil (mesh, soil-frf,
// calibrate, stability). A FEM soil meshes, assembles and prepares its static solver when it
// accepts the layout: at 9.4e5 DOFs about 21 s and 6 GB, so the soil validation built is kept
// (BuiltSoils) for what follows it in the same process instead of being built twice.
#pragma once

#include <filesystem>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "core/errors.hpp"
#include "plugin/instance.hpp"

namespace rumble {

/// The soil refused the footprints it was to lie on (its params were accepted).
class LayoutRefused : public ConfigError {
 public:
  using ConfigError::ConfigError;
};

/// The soil of type `type` at `pointer` built from `params` (files relative to `dir`) and laid
/// on `layout`; throws LayoutRefused when it refuses the layout, what the plugin threw when it
/// refuses its params (ConfigError, PluginError).
std::unique_ptr<SoilInstance> lay_soil(const ComponentType& type, const std::string& pointer,
                                       const nlohmann::json& params,
                                       const std::filesystem::path& dir,
                                       const std::vector<rumble_footprint>& layout);

class BuiltSoils {
 public:
  /// Keeps `soil` (type `type`, built from `params`, layout accepted) under its pointer.
  void keep(const std::string& pointer, const std::string& type, const nlohmann::json& params,
            const std::vector<rumble_footprint>& layout, std::unique_ptr<SoilInstance> soil);

  /// The soil kept under `pointer` when it was built from the same type, params and layout
  /// (it is then handed over, once); nullptr otherwise, and the caller builds its own.
  std::unique_ptr<SoilInstance> take(const std::string& pointer, const std::string& type,
                                     const nlohmann::json& params,
                                     const std::vector<rumble_footprint>& layout);

  /// The soil kept under `pointer` for these type, params and layout, else a new one laid by
  /// lay_soil(): what the run and the soil commands call.
  std::unique_ptr<SoilInstance> take_or_lay(const ComponentType& type, const std::string& pointer,
                                            const nlohmann::json& params,
                                            const std::filesystem::path& dir,
                                            const std::vector<rumble_footprint>& layout);

 private:
  struct Kept {
    std::string pointer;
    std::string type;
    nlohmann::json params;
    std::vector<rumble_footprint> layout;
    std::unique_ptr<SoilInstance> soil;
  };
  std::vector<Kept> kept_;
};

}  // namespace rumble
