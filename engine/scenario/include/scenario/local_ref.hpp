// A schema's local "$ref" ("#/definitions/unevenness": a JSON pointer into the same document),
// for the readers of schemas that walk them by hand (the messages of schema_check, the tables of
// schema_print); valijson resolves them itself when it validates.
#pragma once

#include <optional>
#include <stdexcept>
#include <string>

namespace rumble::scenario {

/// When `node` is an object with a local "$ref": the node of `root` it names, or nullptr when it
/// names nothing there (a broken reference). std::nullopt when `node` has no local $ref. Json is
/// nlohmann::json or nlohmann::ordered_json.
template <class Json>
std::optional<const Json*> local_ref(const Json& root, const Json& node) {
  if (!node.is_object()) return std::nullopt;
  const auto ref = node.find("$ref");
  if (ref == node.end() || !ref->is_string()) return std::nullopt;
  const std::string& target = ref->template get_ref<const std::string&>();
  if (target.empty() || target[0] != '#') return std::nullopt;
  try {
    const typename Json::json_pointer pointer(target.substr(1));
    return root.contains(pointer) ? &root.at(pointer) : nullptr;
  } catch (const std::exception&) {
    return nullptr;  // not a JSON pointer
  }
}

}  // namespace rumble::scenario
