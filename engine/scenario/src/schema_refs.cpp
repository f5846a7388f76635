// Which schema nodes speak for a value: local $refs followed, allOf always, anyOf/oneOf and
// if/then/else as the value matches them, properties, patternProperties and items down a path.
// The messages need the exact keyword behind an error (its bound, its enum, its description),
// which valijson does not give; this walk finds it, and the defaults are filled along it.
#include <algorithm>
#include <regex>

#include "scenario/json_position.hpp"
#include "scenario/local_ref.hpp"
#include "schema_check_parts.hpp"

namespace rumble::scenario {
namespace {

using nlohmann::json;

// $ref chains and allOf nesting are followed this deep (a cyclic $ref stops here too).
constexpr int kMaxClosureDepth = 32;

std::optional<std::size_t> to_index(const std::string& token) {
  if (token.empty() || token.size() > 18) return std::nullopt;
  std::size_t v = 0;
  for (const char c : token) {
    if (c < '0' || c > '9') return std::nullopt;
    v = v * 10 + static_cast<std::size_t>(c - '0');
  }
  return v;
}

const json* child_of(const json& parent, const std::string& token) {
  if (parent.is_object()) {
    const auto it = parent.find(token);
    return it == parent.end() ? nullptr : &*it;
  }
  if (parent.is_array()) {
    const auto i = to_index(token);
    return (i && *i < parent.size()) ? &parent[*i] : nullptr;
  }
  return nullptr;
}

}  // namespace

std::string to_pointer(const std::vector<std::string>& path) {
  std::string p;
  for (const std::string& t : path) p += "/" + escape_pointer_token(t);
  return p;
}

const json* navigate(const json& root, const std::vector<std::string>& path) {
  const json* v = &root;
  for (const std::string& t : path) {
    v = child_of(*v, t);
    if (v == nullptr) return nullptr;
  }
  return v;
}

const json* declared(const json& root, const json* node, const char* keyword) {
  for (int i = 0; node != nullptr && i < kMaxClosureDepth; ++i) {
    if (!node->is_object()) return nullptr;
    if (const auto it = node->find(keyword); it != node->end()) return &*it;
    const std::optional<const json*> target = local_ref(root, *node);
    if (!target) return nullptr;
    node = *target;
  }
  return nullptr;
}

void SchemaChecker::closure(const std::string& pointer, const json& value, Closure mode, int depth,
                            std::vector<Ref>& out) const {
  if (depth > kMaxClosureDepth) return;
  if (std::any_of(out.begin(), out.end(), [&](const Ref& r) { return r.pointer == pointer; })) {
    return;
  }
  const json* node = node_at(pointer);
  if (node == nullptr) return;
  out.push_back(Ref{pointer, node});
  if (!node->is_object()) return;
  if (const auto ref = node->find("$ref"); ref != node->end() && ref->is_string()) {
    const std::string& target = ref->get_ref<const std::string&>();
    if (starts_with(target, "#")) closure(target.substr(1), value, mode, depth + 1, out);
    return;  // draft 7: the siblings of a $ref are ignored
  }
  const auto each = [&](const char* keyword, bool only_matching) {
    const auto list = node->find(keyword);
    if (list == node->end() || !list->is_array()) return;
    for (std::size_t i = 0; i < list->size(); ++i) {
      const std::string p = pointer + "/" + keyword + "/" + std::to_string(i);
      if (!only_matching || matches(p, value)) closure(p, value, mode, depth + 1, out);
    }
  };
  each("allOf", false);
  if (mode != Closure::kActive) {
    each("anyOf", mode == Closure::kMatching);
    each("oneOf", mode == Closure::kMatching);
  }
  if (node->contains("if")) {
    const char* branch = matches(pointer + "/if", value) ? "then" : "else";
    if (node->contains(branch)) closure(pointer + "/" + branch, value, mode, depth + 1, out);
  }
}

std::vector<SchemaChecker::Ref> SchemaChecker::children(const std::vector<Ref>& parents,
                                                        const json& parent_value,
                                                        const std::string& token,
                                                        Closure mode) const {
  std::vector<Ref> out;
  const json* child = child_of(parent_value, token);
  if (child == nullptr) return out;
  for (const Ref& ref : parents) {
    const json& node = *ref.node;
    if (!node.is_object()) continue;
    if (parent_value.is_object()) {
      bool matched = false;
      if (const auto props = node.find("properties");
          props != node.end() && props->is_object() && props->contains(token)) {
        closure(ref.pointer + "/properties/" + escape_pointer_token(token), *child, mode, 0, out);
        matched = true;
      }
      if (const auto pp = node.find("patternProperties"); pp != node.end() && pp->is_object()) {
        for (const auto& [pattern, s] : pp->items()) {
          try {
            if (!std::regex_search(token, std::regex(pattern, std::regex::ECMAScript))) continue;
          } catch (const std::exception&) {
            continue;
          }
          closure(ref.pointer + "/patternProperties/" + escape_pointer_token(pattern), *child, mode,
                  0, out);
          matched = true;
        }
      }
      if (const auto ap = node.find("additionalProperties");
          !matched && ap != node.end() && ap->is_object()) {
        closure(ref.pointer + "/additionalProperties", *child, mode, 0, out);
      }
    } else if (parent_value.is_array()) {
      const auto items = node.find("items");
      if (items == node.end()) continue;
      if (items->is_object() || items->is_boolean()) {
        closure(ref.pointer + "/items", *child, mode, 0, out);
      } else if (items->is_array()) {
        const std::size_t i = to_index(token).value_or(0);
        if (i < items->size()) {
          closure(ref.pointer + "/items/" + token, *child, mode, 0, out);
        } else if (node.contains("additionalItems")) {
          closure(ref.pointer + "/additionalItems", *child, mode, 0, out);
        }
      }
    }
  }
  return out;
}

std::vector<SchemaChecker::Ref> SchemaChecker::resolve(const std::string& pointer,
                                                       const json& value,
                                                       const std::vector<std::string>& path,
                                                       Closure mode) const {
  std::vector<Ref> refs;
  closure(pointer, value, mode, 0, refs);
  const json* v = &value;
  for (const std::string& token : path) {
    refs = children(refs, *v, token, mode);
    v = child_of(*v, token);
    if (v == nullptr) return {};
  }
  return refs;
}

}  // namespace rumble::scenario
