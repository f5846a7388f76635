// Every number of every schema has a physical range (issue #30 item 3): a lower and an upper
// bound, stated with the reason in its description ("[1e5, 1e12] Pa: from peat to hard rock"),
// so that a hostile value is refused by validation instead of hanging or crashing the engine.
// Walks the engine's scenario schema, the params schema of every in-tree plugin type (what
// `rumble schema TYPE` prints) and those of the SDK templates (what third parties copy), and
// names every number without both bounds or whose description does not state them
// (docs/scenario.md, "Limits").
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <nlohmann/json.hpp>
#include <regex>
#include <string>
#include <vector>

#include "plugin/registry.hpp"
#include "scenario/scenario_schema.hpp"
#include "test_support.hpp"

// A named namespace: the scenario tests share a unity build, and the other files' anonymous
// namespaces have helpers of the same kind.
namespace rumble::scenario::parameter_ranges {

using nlohmann::json;

struct RangeBound {
  bool given = false;
  double value = 0.0;
  bool exclusive = false;
  std::string text;  // as the schema writes it
};

RangeBound range_bound(const json& node, const char* exclusive, const char* inclusive) {
  if (const auto e = node.find(exclusive); e != node.end() && e->is_number())
    return {true, e->get<double>(), true, e->dump()};
  if (const auto i = node.find(inclusive); i != node.end() && i->is_number())
    return {true, i->get<double>(), false, i->dump()};
  return {};
}

bool numeric_type(const json& node) {
  const auto t = node.find("type");
  if (t == node.end()) return false;
  const auto numeric = [](const json& name) { return name == "number" || name == "integer"; };
  if (t->is_string()) return numeric(*t);
  if (t->is_array()) {
    for (const json& name : *t)
      if (numeric(name)) return true;
  }
  return false;
}

bool same_number(double a, double b) {
  return a == b || std::abs(a - b) <= 1e-12 * std::max(std::abs(a), std::abs(b));
}

/// Whether `description` states the range as "[lo, hi] unit: reason" (brackets for inclusive,
/// parentheses for exclusive bounds; the unit may be empty).
bool states_range(const std::string& description, const RangeBound& lo, const RangeBound& hi) {
  static const std::regex range(
      R"(([\[(])\s*([-+0-9.eE]+)\s*,\s*([-+0-9.eE]+)\s*([\])])[ A-Za-z0-9/^.]{0,16}:)");
  for (auto it = std::sregex_iterator(description.begin(), description.end(), range);
       it != std::sregex_iterator(); ++it) {
    const std::smatch& m = *it;
    const double a = std::strtod(m[2].str().c_str(), nullptr);
    const double b = std::strtod(m[3].str().c_str(), nullptr);
    if (same_number(a, lo.value) && same_number(b, hi.value) && (m[1] == "(") == lo.exclusive &&
        (m[4] == ")") == hi.exclusive)
      return true;
  }
  return false;
}

/// "mesh.radius", "layers[].E", "definitions.point[]", "receivers[] (oneOf 0)".
std::string readable(const std::vector<std::string>& path) {
  std::string name;
  for (std::size_t i = 0; i < path.size(); ++i) {
    const std::string& step = path[i];
    const bool named =
        (step == "properties" || step == "patternProperties" || step == "definitions") &&
        i + 1 < path.size();
    if (named) {
      name += std::string(name.empty() ? "" : ".") + (step == "definitions" ? "definitions." : "") +
              path[++i];
    } else if (step == "items") {
      name += "[]";
    } else if ((step == "oneOf" || step == "anyOf" || step == "allOf") && i + 1 < path.size()) {
      name += " (" + step + " " + path[++i] + ")";
    } else if (step != "then" && step != "else") {
      name += " " + step;
    }
  }
  return name.empty() ? "(the whole value)" : name;
}

/// Every number of `schema` without a lower and an upper bound, or whose description (its own,
/// else the nearest enclosing one: an array's items, a variant of oneOf) does not state them,
/// as "<where>: <param>: <what is missing>". A const or enum is its own range.
void unbounded(const json& node, std::vector<std::string>& path, const std::string& description,
               const std::string& where, std::vector<std::string>& out) {
  if (node.is_array()) {
    for (std::size_t i = 0; i < node.size(); ++i) {
      path.push_back(std::to_string(i));
      unbounded(node[i], path, description, where, out);
      path.pop_back();
    }
    return;
  }
  if (!node.is_object()) return;
  const auto own = node.find("description");
  const std::string said =
      own != node.end() && own->is_string() ? own->get<std::string>() : description;
  if (numeric_type(node) && !node.contains("const") && !node.contains("enum")) {
    const RangeBound lo = range_bound(node, "exclusiveMinimum", "minimum");
    const RangeBound hi = range_bound(node, "exclusiveMaximum", "maximum");
    const std::string name = where + ": " + readable(path) + ": ";
    if (!lo.given) out.push_back(name + "no lower bound (minimum or exclusiveMinimum)");
    if (!hi.given) out.push_back(name + "no upper bound (maximum or exclusiveMaximum)");
    if (lo.given && hi.given && !states_range(said, lo, hi)) {
      out.push_back(name + "the description does not state the range as \"" +
                    (lo.exclusive ? "(" : "[") + lo.text + ", " + hi.text +
                    (hi.exclusive ? ")" : "]") + " unit: reason\": " + said);
    }
  }
  for (const auto& [key, child] : node.items()) {
    if (key == "description" || key == "default" || key == "const" || key == "enum") continue;
    path.push_back(key);
    unbounded(child, path, said, where, out);
    path.pop_back();
  }
}

std::vector<std::string> unbounded_numbers(const std::string& schema_text,
                                           const std::string& where) {
  std::vector<std::string> out;
  json schema;
  try {
    schema = json::parse(schema_text);
  } catch (const std::exception& e) {
    return {where + ": the schema is not JSON: " + e.what()};
  }
  std::vector<std::string> path;
  unbounded(schema, path, "", where, out);
  return out;
}

std::string listed(const std::vector<std::string>& problems) {
  std::string text;
  for (const std::string& p : problems) text += "\n  " + p;
  return text;
}

/// The text params_schema() returns in an SDK template's source: the raw string literal
/// R"(...)" after it.
std::string template_schema(const std::string& relative_path) {
  const std::string source = test::read_file(test::source_dir() / relative_path);
  const auto at = source.find("params_schema()");
  const auto begin = source.find("R\"(", at);
  const auto end = source.find(")\"", begin);
  if (at == std::string::npos || begin == std::string::npos || end == std::string::npos)
    return "not found in " + relative_path;
  return source.substr(begin + 3, end - begin - 3);
}

TEST(ParameterRanges, TheCheckNamesANumberWithoutBothBoundsOrWithoutItsReason) {
  const std::string schema = R"({
    "type": "object",
    "properties": {
      "k": {"type": "number", "exclusiveMinimum": 0, "description": "stiffness [N/m]"},
      "n": {"type": "integer", "minimum": 1, "maximum": 8, "description": "count"},
      "nu": {"type": "number", "minimum": 0, "exclusiveMaximum": 0.5,
             "description": "Poisson ratio [-]; [0, 0.5): 0.5 is incompressible"},
      "E": {"type": "number", "minimum": 1e5, "maximum": 1e12,
            "description": "modulus [Pa]; [1e5, 1e12] Pa: from peat to hard rock"},
      "point": {"type": "array", "items": {"type": "number", "maximum": 1}},
      "version": {"type": "integer", "const": 1}
    }
  })";
  EXPECT_EQ(unbounded_numbers(schema, "example"),
            (std::vector<std::string>{
                "example: k: no upper bound (maximum or exclusiveMaximum)",
                "example: n: the description does not state the range as \"[1, 8] unit: "
                "reason\": count",
                "example: point[]: no lower bound (minimum or exclusiveMinimum)"}));
}

TEST(ParameterRanges, EveryNumberOfTheScenarioSchemaHasARangeAndItsReason) {
  const auto problems = unbounded_numbers(std::string(scenario_schema_text()), "scenario");
  EXPECT_TRUE(problems.empty()) << problems.size()
                                << " numbers of the scenario schema:" << listed(problems);
}

TEST(ParameterRanges, EveryNumberOfEveryPluginTypeHasARangeAndItsReason) {
  PluginRegistry registry;
  registry.load_directory(RUMBLE_TEST_PLUGIN_DIR);
  // The in-tree types, so that a plugin that failed to build or load does not pass unseen.
  const std::vector<std::pair<rumble_kind, std::string>> expected = {
      {RUMBLE_KIND_VEHICLE, "single_wheel"},
      {RUMBLE_KIND_VEHICLE, "quarter_car"},
      {RUMBLE_KIND_VEHICLE, "mbs"},
      {RUMBLE_KIND_SOIL, "winkler"},
      {RUMBLE_KIND_SOIL, "clm"},
      {RUMBLE_KIND_SOIL, "fem"},
      {RUMBLE_KIND_COUPLER, "gauss_seidel"},
      {RUMBLE_KIND_COUPLER, "jacobi"},
      {RUMBLE_KIND_COUPLER, "implicit"},
      {RUMBLE_KIND_COUPLER, "two_step"},
      {RUMBLE_KIND_COUPLER, "monolithic"}};
  for (const auto& [kind, name] : expected)
    EXPECT_NE(registry.find(kind, name), nullptr)
        << name << " is not in " << RUMBLE_TEST_PLUGIN_DIR;
  std::vector<std::string> problems;
  for (const ComponentType& t : registry.types()) {
    const auto found = unbounded_numbers(t.params_schema, t.type_name);
    problems.insert(problems.end(), found.begin(), found.end());
  }
  EXPECT_TRUE(problems.empty()) << problems.size()
                                << " numbers of the plugins' schemas:" << listed(problems);
}

TEST(ParameterRanges, EveryNumberOfTheSdkTemplatesHasARangeAndItsReason) {
  std::vector<std::string> problems;
  for (const char* file :
       {"sdk/template/template_soil.cpp", "sdk/template_vehicle/template_vehicle.cpp",
        "sdk/template_coupler/template_coupler.cpp"}) {
    const auto found = unbounded_numbers(template_schema(file), file);
    problems.insert(problems.end(), found.begin(), found.end());
  }
  EXPECT_TRUE(problems.empty()) << problems.size()
                                << " numbers of the templates' schemas:" << listed(problems);
}

}  // namespace rumble::scenario::parameter_ranges
