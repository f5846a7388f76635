#include "scenario/validate.hpp"

#include <algorithm>
#include <map>
#include <memory>
#include <mutex>
#include <utility>

#include "core/errors.hpp"
#include "plugin/registry.hpp"
#include "scenario/capability_check.hpp"
#include "scenario/did_you_mean.hpp"
#include "scenario/json_position.hpp"
#include "scenario/scenario_schema.hpp"
#include "scenario/schema_check.hpp"
#include "scenario/value_text.hpp"

namespace rumble::scenario {
namespace {

using nlohmann::json;
namespace fs = std::filesystem;

/// Compiled plugin schemas, by schema text: a process validates the same few types many times.
std::shared_ptr<const SchemaChecker> plugin_checker(const std::string& schema_text) {
  static std::mutex mutex;
  static std::map<std::string, std::shared_ptr<const SchemaChecker>> cache;
  std::lock_guard<std::mutex> lock(mutex);
  auto& slot = cache[schema_text];
  if (!slot) slot = std::make_shared<const SchemaChecker>(schema_text);  // may throw SchemaError
  return slot;
}

/// Positions of every value of the document, built once: one validation may look up many.
class Positions {
 public:
  explicit Positions(const Document& doc) : doc_(doc), index_(doc.text) {}

  void place(Diagnostic& d, bool at_key) const {
    if (const auto span = index_.nearest(d.pointer, at_key)) {
      const LineColumn lc = index_.line_column(span->begin);
      d.line = lc.line;
      d.column = lc.column;
    }
  }

  /// The value as the user wrote it ("-2.5e7", not -25000000.0) when it is a scalar in the text
  /// and still the value there (one set by --set replaced what the text says).
  std::string written(const std::string& pointer) const {
    const json* current = nullptr;
    try {
      const json::json_pointer p(pointer);
      if (doc_.json.contains(p)) current = &doc_.json.at(p);
    } catch (const std::exception&) {
    }
    if (const auto span = index_.value(pointer)) {
      const std::string_view token =
          std::string_view(doc_.text).substr(span->begin, span->end - span->begin);
      if (!token.empty() && token[0] != '{' && token[0] != '[' &&
          (current == nullptr || json::parse(token, nullptr, false) == *current))
        return truncate_text(token, 40);
    }
    if (current != nullptr) return short_json(*current);
    return "?";
  }

  Diagnostic make(std::string pointer, std::string message, std::string hint = "") const {
    Diagnostic d;
    d.pointer = std::move(pointer);
    d.message = std::move(message);
    d.hint = std::move(hint);
    place(d, false);
    return d;
  }

  Diagnostic from_issue(const std::string& prefix, const SchemaIssue& issue) const {
    Diagnostic d;
    d.pointer = prefix + issue.pointer;
    d.message = issue.message;
    if (issue.show_value) d.message += ", got " + written(d.pointer);
    d.hint = issue.hint;
    place(d, issue.at_key);
    return d;
  }

 private:
  const Document& doc_;
  PositionIndex index_;
};

/// Counts values and measures depth without recursion (a hand-built document may be deep).
void measure(const json& root, std::size_t& values, std::size_t& depth) {
  values = 0;
  depth = 0;
  std::vector<std::pair<const json*, std::size_t>> stack{{&root, 1}};
  while (!stack.empty()) {
    const auto [v, d] = stack.back();
    stack.pop_back();
    ++values;
    depth = std::max(depth, d);
    if (depth > kMaxNestingDepth || values > kMaxValues) return;
    if (v->is_structured()) {
      for (const json& child : *v) stack.emplace_back(&child, d + 1);
    }
  }
}

void check_time(const Document& doc, const Positions& at, std::vector<Diagnostic>& out) {
  const auto time = doc.json.find("time");
  if (time == doc.json.end() || !time->is_object()) return;
  const auto end = time->find("end");
  const auto step = time->find("macro_step");
  if (end == time->end() || step == time->end() || !end->is_number() || !step->is_number()) return;
  const double t_end = end->get<double>();
  const double h = step->get<double>();
  if (t_end > 0 && h > 0 && h > t_end) {
    out.push_back(at.make("/time/macro_step",
                          "must be <= /time/end (" + at.written("/time/end") + "), got " +
                              at.written("/time/macro_step"),
                          "the coupling step cannot be longer than the whole run"));
  }
}

struct Component {
  std::string pointer;
  rumble_kind kind;
};

/// The names the engine schema accepts under /coupling/participants (safe in a JSON pointer).
bool valid_participant_name(const std::string& name) {
  return !name.empty() && name[0] >= 'a' && name[0] <= 'z' &&
         std::all_of(name.begin(), name.end(), [](char ch) {
           return (ch >= 'a' && ch <= 'z') || (ch >= '0' && ch <= '9') || ch == '_';
         });
}

std::vector<Component> components(const json& root) {
  std::vector<Component> list;
  if (const auto v = root.find("vehicles"); v != root.end() && v->is_array()) {
    for (std::size_t i = 0; i < v->size(); ++i) {
      list.push_back({"/vehicles/" + std::to_string(i), RUMBLE_KIND_VEHICLE});
    }
  }
  list.push_back({"/soil", RUMBLE_KIND_SOIL});
  list.push_back({"/coupling", RUMBLE_KIND_COUPLER});
  const auto c = root.find("coupling");
  if (c == root.end() || !c->is_object()) return list;
  const auto extras = c->find("participants");
  if (extras == c->end() || !extras->is_object()) return list;
  for (const auto& [name, component] : extras->items()) {
    if (valid_participant_name(name))
      list.push_back({"/coupling/participants/" + name, RUMBLE_KIND_SOIL});
  }
  return list;
}

std::string unknown_type_hint(const PluginRegistry& registry, rumble_kind kind,
                              const std::string& name) {
  const std::string k = kind_name(kind);
  const auto known = registry.type_names(kind);
  std::string hint;
  for (const rumble_kind other : {RUMBLE_KIND_VEHICLE, RUMBLE_KIND_SOIL, RUMBLE_KIND_COUPLER}) {
    if (other != kind && registry.find(other, name) != nullptr) {
      hint = "\"" + name + "\" is a " + kind_name(other) + " type; ";
    }
  }
  if (const auto m = closest_match(name, known)) hint += "did you mean \"" + *m + "\"? ";
  // A library skipped by the default search may have been the one providing it.
  std::string skipped;
  for (const SkippedPlugin& s : registry.skipped())
    skipped += (skipped.empty() ? "" : ", ") + s.path.string();
  if (!skipped.empty()) skipped = "; not loaded (see the warnings above): " + skipped;
  if (known.empty()) {
    return hint + "no " + k + " plugins are loaded; list the library in /plugins or in " +
           "RUMBLE_PLUGIN_PATH" + skipped;
  }
  return hint + "known " + k + " types: " + join(known) + skipped;
}

bool blank(const std::string& s) {
  return std::all_of(s.begin(), s.end(),
                     [](char c) { return c == ' ' || c == '\t' || c == '\n' || c == '\r'; });
}

void check_component(Document& doc, const Positions& at, const PluginRegistry& registry,
                     const Component& c, std::vector<Diagnostic>& out) {
  json* obj = nullptr;
  try {
    const json::json_pointer p(c.pointer);
    if (doc.json.contains(p)) obj = &doc.json.at(p);
  } catch (const std::exception&) {
  }
  if (obj == nullptr || !obj->is_object()) return;  // the engine schema has said why
  const auto type = obj->find("type");
  if (type == obj->end() || !type->is_string()) return;
  const std::string name = type->get<std::string>();
  const std::string kind = kind_name(c.kind);
  const std::string type_pointer = c.pointer + "/type";

  const ComponentType* t = registry.find(c.kind, name);
  if (t == nullptr) {
    out.push_back(at.make(type_pointer, "unknown " + kind + " type " + short_json(*type, 60),
                          unknown_type_hint(registry, c.kind, name)));
    return;
  }
  const std::string plugin = t->library ? t->library->path.string() : std::string("?");
  try {  // a library known from its manifest is loaded here, so that valid means it loads
    t->factory();
  } catch (const PluginLoadError& e) {
    out.push_back(at.make(type_pointer, e.what(),
                          "fix or rebuild the plugin; `rumble plugins` lists what loads"));
    return;
  }
  if (!t->schema_declared || blank(t->params_schema)) {
    out.push_back(
        at.make(type_pointer,
                kind + " type \"" + name +
                    "\" declares no params schema, so its params cannot be "
                    "checked (a bug in plugin " +
                    plugin + ")",
                "the plugin must give its factory a JSON Schema of its params; report this to the "
                "plugin's author"));
    return;
  }
  std::shared_ptr<const SchemaChecker> checker;
  try {
    checker = plugin_checker(t->params_schema);
  } catch (const SchemaError& e) {
    out.push_back(at.make(type_pointer,
                          kind + " type \"" + name +
                              "\" has an unusable params schema (a bug in plugin " + plugin +
                              "): " + truncate_text(e.what(), 300),
                          "report this to the plugin's author"));
    return;
  }
  auto params = obj->find("params");
  if (params == obj->end()) params = obj->emplace("params", json::object()).first;
  if (!params->is_object()) return;  // the engine schema has said why
  for (const SchemaIssue& issue : checker->check(*params)) {
    out.push_back(at.from_issue(c.pointer + "/params", issue));
  }
  checker->fill_defaults(*params);
}

void name_vehicles(json& root) {
  const auto v = root.find("vehicles");
  if (v == root.end() || !v->is_array()) return;
  for (std::size_t i = 0; i < v->size(); ++i) {
    json& vehicle = (*v)[i];
    if (vehicle.is_object() && !vehicle.contains("name")) {
      vehicle["name"] = "vehicle" + std::to_string(i);
    }
  }
}

}  // namespace

void load_scenario_plugins(const Document& doc, PluginRegistry& registry) {
  if (!doc.json.is_object()) return;
  const auto list = doc.json.find("plugins");
  if (list == doc.json.end() || !list->is_array()) return;
  const fs::path base = doc.path.parent_path();
  for (std::size_t i = 0; i < list->size(); ++i) {
    const json& entry = (*list)[i];
    if (!entry.is_string() || entry.get_ref<const std::string&>().empty()) continue;
    const fs::path p(entry.get<std::string>());
    const std::string where = doc.path.string() + ": /plugins/" + std::to_string(i) + ": ";
    try {
      registry.load_library(p.is_absolute() ? p : base / p,
                            "scenario /plugins/" + std::to_string(i));
    } catch (const PluginLoadError& e) {
      throw PluginLoadError(where + e.what());
    } catch (const std::exception& e) {
      throw PluginLoadError(where + "cannot be loaded: " + e.what());
    }
  }
}

Diagnostic make_diagnostic(const Document& doc, std::string pointer, std::string message,
                           std::string hint, Diagnostic::Severity severity) {
  Diagnostic d;
  d.severity = severity;
  d.pointer = std::move(pointer);
  d.message = std::move(message);
  d.hint = std::move(hint);
  if (const auto span = find_nearest(doc.text, d.pointer, false)) {
    const LineColumn lc = line_column(doc.text, span->begin);
    d.line = lc.line;
    d.column = lc.column;
  }
  return d;
}

void sort_diagnostics(std::vector<Diagnostic>& diagnostics) {
  std::stable_sort(diagnostics.begin(), diagnostics.end(),
                   [](const Diagnostic& a, const Diagnostic& b) {
                     return std::pair(a.line, a.column) < std::pair(b.line, b.column);
                   });
}

std::vector<Diagnostic> validate(Document& doc, const PluginRegistry& registry,
                                 bool check_plugins) {
  std::vector<Diagnostic> out;
  std::size_t values = 0;
  std::size_t depth = 0;
  measure(doc.json, values, depth);
  if (depth > kMaxNestingDepth) {
    out.push_back(make_diagnostic(
        doc, "",
        "nesting is too deep (more than " + std::to_string(kMaxNestingDepth) + " levels)"));
    return out;
  }
  if (values > kMaxValues) {
    out.push_back(make_diagnostic(doc, "",
                                  "too many values (more than " + std::to_string(kMaxValues) +
                                      " numbers, strings, arrays and objects)",
                                  "a scenario holds parameters, not data; is this the right "
                                  "file?"));
    return out;
  }

  const Positions at(doc);
  const SchemaChecker& engine = engine_checker();
  for (const SchemaIssue& issue : engine.check(doc.json)) out.push_back(at.from_issue("", issue));
  engine.fill_defaults(doc.json);
  check_time(doc, at, out);
  if (doc.json.is_object()) {
    if (check_plugins) {
      for (const Component& c : components(doc.json)) check_component(doc, at, registry, c, out);
    }
    name_vehicles(doc.json);
  }
  if (out.empty() &&
      check_plugins) {  // capabilities are matched on a scenario whose shape is right
    for (Diagnostic& d : check_capabilities(doc.json, registry)) {
      Diagnostic placed = at.make(d.pointer, d.message, d.hint);
      placed.severity = d.severity;
      out.push_back(std::move(placed));
    }
  }

  sort_diagnostics(out);
  if (out.size() > kMaxDiagnostics) {
    const std::size_t cut = out.size() - kMaxDiagnostics;
    out.resize(kMaxDiagnostics);
    Diagnostic more;
    more.message = std::to_string(cut) + " more errors not shown";
    more.hint = "fix the ones above first";
    out.push_back(std::move(more));
  }
  return out;
}

}  // namespace rumble::scenario
