#include "plugin/built_soils.hpp"

#include <algorithm>

namespace rumble {
namespace {

bool same_layout(const std::vector<rumble_footprint>& a, const std::vector<rumble_footprint>& b) {
  return std::equal(a.begin(), a.end(), b.begin(), b.end(),
                    [](const rumble_footprint& p, const rumble_footprint& q) {
                      return p.x == q.x && p.y == q.y && p.length == q.length && p.width == q.width;
                    });
}

}  // namespace

std::unique_ptr<SoilInstance> lay_soil(const ComponentType& type, const std::string& pointer,
                                       const nlohmann::json& params,
                                       const std::filesystem::path& dir,
                                       const std::vector<rumble_footprint>& layout) {
  auto soil = std::make_unique<SoilInstance>(type, pointer, params, dir);
  try {
    soil->accept_layout(layout);
  } catch (const ConfigError& e) {
    throw LayoutRefused(e.what());
  }
  return soil;
}

std::unique_ptr<SoilInstance> BuiltSoils::take_or_lay(const ComponentType& type,
                                                      const std::string& pointer,
                                                      const nlohmann::json& params,
                                                      const std::filesystem::path& dir,
                                                      const std::vector<rumble_footprint>& layout) {
  if (auto kept = take(pointer, type.type_name, params, layout)) return kept;
  return lay_soil(type, pointer, params, dir, layout);
}

void BuiltSoils::keep(const std::string& pointer, const std::string& type,
                      const nlohmann::json& params, const std::vector<rumble_footprint>& layout,
                      std::unique_ptr<SoilInstance> soil) {
  std::erase_if(kept_, [&](const Kept& k) { return k.pointer == pointer; });
  kept_.push_back({pointer, type, params, layout, std::move(soil)});
}

std::unique_ptr<SoilInstance> BuiltSoils::take(const std::string& pointer, const std::string& type,
                                               const nlohmann::json& params,
                                               const std::vector<rumble_footprint>& layout) {
  const auto it = std::find_if(kept_.begin(), kept_.end(), [&](const Kept& k) {
    return k.pointer == pointer && k.type == type && k.params == params &&
           same_layout(k.layout, layout);
  });
  if (it == kept_.end()) return nullptr;
  std::unique_ptr<SoilInstance> soil = std::move(it->soil);
  kept_.erase(it);
  return soil;
}

}  // namespace rumble
