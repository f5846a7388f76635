// Filling a value with the defaults its schema declares, where the value takes them (variants
// only where the value matches them), so that what reads a scenario finds every parameter set.
#include "schema_check_parts.hpp"

namespace rumble::scenario {
namespace {

using nlohmann::json;

}  // namespace

void SchemaChecker::fill_defaults(json& value, const std::string& schema_pointer) const {
  if (too_long_for_regex(value)) return;  // invalid anyway, and unsafe to match
  std::vector<Ref> refs;
  closure(schema_pointer, value, Closure::kMatching, 0, refs);
  fill_at(refs, value, 0);
}

void SchemaChecker::fill_at(const std::vector<Ref>& refs, json& value, int depth) const {
  if (depth > 512) return;
  if (value.is_object()) {
    for (const Ref& ref : refs) {
      if (!ref.node->is_object()) continue;
      const auto props = ref.node->find("properties");
      if (props == ref.node->end() || !props->is_object()) continue;
      for (const auto& [key, sub] : props->items()) {
        if (value.contains(key)) continue;
        if (const json* d = declared(schema_, &sub, "default"); d != nullptr) value[key] = *d;
      }
    }
    for (auto& [key, child] : value.items()) {
      const auto child_refs = children(refs, value, key, Closure::kMatching);
      if (!child_refs.empty()) fill_at(child_refs, child, depth + 1);
    }
  } else if (value.is_array()) {
    for (std::size_t i = 0; i < value.size(); ++i) {
      const auto child_refs = children(refs, value, std::to_string(i), Closure::kMatching);
      if (!child_refs.empty()) fill_at(child_refs, value[i], depth + 1);
    }
  }
}

}  // namespace rumble::scenario
