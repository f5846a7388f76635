#include "scenario_check.hpp"

#include <exception>
#include <utility>
#include <vector>

#include "fuzz_support.hpp"
#include "plugin/registry.hpp"
#include "scenario/check_file.hpp"
#include "scenario/json_position.hpp"
#include "scenario/scenario.hpp"

namespace rumble::fuzz {
namespace {

using nlohmann::json;
using scenario::Diagnostic;

/// Every value of `root` with its pointer (containers too), without recursion: the parser
/// accepts 256 levels of nesting.
std::vector<std::pair<std::string, const json*>> all_values(const json& root) {
  std::vector<std::pair<std::string, const json*>> out;
  std::vector<std::pair<std::string, const json*>> todo{{"", &root}};
  while (!todo.empty()) {
    auto [pointer, value] = std::move(todo.back());
    todo.pop_back();
    if (value->is_object()) {
      for (const auto& [key, member] : value->items())
        todo.emplace_back(pointer + "/" + scenario::escape_pointer_token(key), &member);
    } else if (value->is_array()) {
      for (std::size_t i = 0; i < value->size(); ++i)
        todo.emplace_back(pointer + "/" + std::to_string(i), &(*value)[i]);
    }
    out.emplace_back(std::move(pointer), value);
  }
  return out;
}

/// "" when the position index places every parsed value, else the first one it misplaces.
std::string check_positions(std::string_view text, const json& parsed) {
  const scenario::PositionIndex index(text);
  for (const auto& [pointer, value] : all_values(parsed)) {
    const auto span = index.value(pointer);
    if (!span || span->begin > span->end || span->end > text.size())
      return "value at \"" + pointer + "\" not found in the text (data lost)";
    if (value->is_structured()) continue;
    const std::string_view found = text.substr(span->begin, span->end - span->begin);
    const json again = json::parse(found, nullptr, false);
    if (again.is_discarded() || again != *value) {
      return "value at \"" + pointer + "\" is " + value->dump() + " but the text there is \"" +
             std::string(found.substr(0, 80)) + "\" (data misplaced)";
    }
  }
  return "";
}

}  // namespace

std::string check_scenario_text(std::string_view text) {
  try {
    std::vector<Diagnostic> diagnostics;
    std::optional<scenario::Document> doc =
        scenario::parse_document("fuzz.json", std::string(text), diagnostics);
    if (!doc && diagnostics.empty()) return "refused without a diagnostic";
    if (doc) {
      if (std::string lost = check_positions(doc->text, doc->json); !lost.empty()) return lost;
      PluginRegistry registry;
      std::vector<scenario::Override> overrides;
      scenario::CheckOptions options;
      options.load_plugins = false;       // rumble validate --no-load: no plugin code runs
      options.results_directory = false;  // nothing on disk is looked at
      scenario::CheckedScenario checked =
          scenario::check_scenario_document(std::move(*doc), overrides, registry, options);
      doc = std::move(checked.doc);
      diagnostics = std::move(checked.diagnostics);
    }
    if (std::string bad = check_diagnostics(text, diagnostics); !bad.empty()) return bad;
    if (std::string bad = check_reports(doc ? &*doc : nullptr, "fuzz.json", diagnostics);
        !bad.empty())
      return bad;
  } catch (const std::exception& e) {
    return std::string("exception escaped: ") + e.what();
  }
  return "";
}

}  // namespace rumble::fuzz
