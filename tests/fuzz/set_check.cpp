#include "set_check.hpp"

#include <exception>
#include <optional>
#include <utility>
#include <vector>

#include "core/errors.hpp"
#include "fuzz_support.hpp"
#include "plugin/registry.hpp"
#include "scenario/check_file.hpp"
#include "scenario/json_position.hpp"
#include "scenario/overrides.hpp"
#include "scenario/scenario.hpp"
#include "scenario/value_text.hpp"

namespace rumble::fuzz {
namespace {

using nlohmann::json;

/// The scenario every option is applied to, read once.
const scenario::Document& set_base_scenario() {
  static const scenario::Document doc = [] {
    const auto file = source_dir() / "tests" / "scenario" / "valid" / "minimal.json";
    std::vector<scenario::Diagnostic> diagnostics;
    auto d = scenario::parse_document(file, read_file(file), diagnostics);
    if (!d) throw std::runtime_error("the base scenario " + file.string() + " does not parse");
    return std::move(*d);
  }();
  return doc;
}

/// The value at `tokens` of `doc`, or null when there is none (any step missing).
const json* value_at(const json& doc, const std::vector<std::string>& tokens, std::size_t count) {
  const json* at = &doc;
  for (std::size_t i = 0; i < count; ++i) {
    if (at->is_object()) {
      const auto it = at->find(tokens[i]);
      if (it == at->end()) return nullptr;
      at = &*it;
    } else if (at->is_array()) {
      std::size_t index = 0;
      for (const char c : tokens[i]) index = index * 10 + static_cast<std::size_t>(c - '0');
      if (index >= at->size()) return nullptr;
      at = &(*at)[index];
    } else {
      return nullptr;
    }
  }
  return at;
}

/// "" when `after` is `before` with o applied and nothing else changed.
std::string check_applied(const json& before, json after, const scenario::Override& o) {
  const std::vector<std::string> tokens = *scenario::split_pointer(o.pointer);
  const json* value = value_at(after, tokens, tokens.size());
  if (value == nullptr || *value != o.value)
    return "applied, but " + o.pointer + " does not hold the value set";
  const std::vector<std::string> created = *scenario::split_pointer(o.applied_at);
  if (created.empty() || created.size() > tokens.size() ||
      !std::equal(created.begin(), created.end(), tokens.begin()))
    return "applied_at \"" + o.applied_at + "\" is not on the way to \"" + o.pointer + "\"";
  // Undo it: remove the member it created, or put the value it replaced back.
  json* parent = const_cast<json*>(value_at(after, created, created.size() - 1));
  if (const json* old = value_at(before, created, created.size())) {
    if (o.applied_at != o.pointer)
      return "applied_at \"" + o.applied_at + "\" existed already but is not the pointer";
    json* at = const_cast<json*>(value_at(after, created, created.size()));
    *at = *old;
  } else if (parent == nullptr || !parent->is_object() || parent->erase(created.back()) != 1) {
    return "applied_at \"" + o.applied_at + "\" was not created by the override";
  }
  if (after != before) return "the override changed more than " + o.pointer;
  return "";
}

std::string check_set(std::string_view option) {
  scenario::Override o;
  try {
    o = scenario::parse_set_option(option);
  } catch (const ConfigError& e) {
    const std::string message = e.what();
    if (scenario::first_invalid_utf8(option)) {
      if (message.find(" is not UTF-8") == std::string::npos)
        return "a text that is not UTF-8 refused without saying so: " + message;
    } else if (message.rfind("--set " + scenario::truncate_text(option, 80) + ": ", 0) != 0) {
      return "refused without naming the option as given: " + message;
    }
    return "";
  }
  const std::string_view pointer = option.substr(0, option.find('='));
  if (o.pointer != pointer) return "parsed the pointer \"" + o.pointer + "\"";
  if (o.label.rfind("--set ", 0) != 0) return "an override labelled \"" + o.label + "\"";
  const std::string text = scenario::override_text(o);
  const scenario::Override again = scenario::parse_set_option(text);
  if (again.pointer != o.pointer || again.value != o.value)
    return "written back as \"" + text.substr(0, 200) + "\" it parses to another override";

  const scenario::Document& base = set_base_scenario();
  scenario::Document doc = base;
  try {
    scenario::apply_override(doc.json, o);
  } catch (const ConfigError& e) {
    if (std::string(e.what()).rfind(o.label + ": ", 0) != 0)
      return std::string("apply_override refused without naming the option: ") + e.what();
    return "";
  }
  if (std::string bad = check_applied(base.json, doc.json, o); !bad.empty()) return bad;

  // The whole check, as `rumble validate --no-load --set OPTION` (the override applied again
  // there, to the file as read).
  std::vector<scenario::Override> overrides{o};
  PluginRegistry registry;
  scenario::CheckOptions options;
  options.load_plugins = false;       // no plugin code runs
  options.results_directory = false;  // nothing on disk is looked at
  const scenario::CheckedScenario checked =
      scenario::check_scenario_document(base, overrides, registry, options);
  if (std::string bad = check_diagnostics(base.text, checked.diagnostics); !bad.empty()) return bad;
  const std::string& root = overrides.front().applied_at;
  for (const scenario::Diagnostic& d : checked.diagnostics) {
    const bool below = d.pointer == root || (d.pointer.size() > root.size() &&
                                             d.pointer.compare(0, root.size(), root) == 0 &&
                                             d.pointer[root.size()] == '/');
    const std::string note = " (set by --set)";
    const bool noted = d.message.size() >= note.size() &&
                       d.message.compare(d.message.size() - note.size(), note.size(), note) == 0;
    if (below != noted)
      return "a diagnostic at \"" + d.pointer + "\" " + (below ? "without" : "with") +
             " the note for the value set at \"" + root + "\": " + d.message;
  }
  return check_reports(checked.doc ? &*checked.doc : nullptr, "fuzz.json", checked.diagnostics);
}

}  // namespace

std::string check_set_option(std::string_view input) {
  try {
    // An option is one command-line argument, which ends at its first NUL byte.
    return check_set(input.substr(0, input.find('\0')));
  } catch (const std::exception& e) {
    return std::string("exception escaped: ") + e.what();
  }
}

}  // namespace rumble::fuzz
