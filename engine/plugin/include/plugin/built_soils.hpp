// Soils that validation built and laid on the track's footprints, kept for the run (or the
// build-only command) that follows the validation in the same process. A FEM soil meshes,
// assembles and prepares its static solver when it accepts the layout: at 9.4e5 DOFs about 21 s
// and 6 GB, which `rumble run` used to spend twice (validation threw its soil away).
#pragma once

#include <memory>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "plugin/instance.hpp"

namespace rumble {

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
