// The engine's scenario schema against docs/scenario.md: every documented key exists with the
// documented default, and every key of the schema is documented. The two are kept in step by
// hand; this test says where they drifted apart.
#include "scenario/scenario_schema.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdlib>
#include <nlohmann/json.hpp>
#include <regex>
#include <set>
#include <sstream>

#include "scenario/schema_check.hpp"
#include "test_support.hpp"

namespace rumble::scenario {
namespace {

using nlohmann::json;

const json& schema() {
  static const json s = json::parse(scenario_schema_text());
  return s;
}

const json* follow(const json* node) {
  for (int i = 0; i < 8 && node != nullptr && node->contains("$ref"); ++i) {
    node = &schema().at(json::json_pointer(node->at("$ref").get<std::string>().substr(1)));
  }
  return node;
}

/// "track.sleepers.count" under {"track"} etc.; "[]" steps into array items.
const json* node_at(const std::vector<std::string>& path) {
  const json* node = &schema();
  for (const std::string& step : path) {
    node = follow(node);
    if (step == "[]") {
      if (!node->contains("items")) return nullptr;
      node = &node->at("items");
      continue;
    }
    if (!node->contains("properties") || !node->at("properties").contains(step)) return nullptr;
    node = &node->at("properties").at(step);
  }
  return follow(node);
}

std::vector<std::string> split(const std::string& s, char sep) {
  std::vector<std::string> parts;
  std::stringstream ss(s);
  std::string part;
  while (std::getline(ss, part, sep)) parts.push_back(part);
  return parts;
}

std::string trim(const std::string& s) {
  const auto a = s.find_first_not_of(' ');
  const auto b = s.find_last_not_of(' ');
  return a == std::string::npos ? "" : s.substr(a, b - a + 1);
}

/// Backticked words outside parentheses: "`class` (`FRA1`..), `seed`" -> class, seed.
std::vector<std::string> keys_in(const std::string& cell) {
  std::vector<std::string> keys;
  int depth = 0;
  for (std::size_t i = 0; i < cell.size(); ++i) {
    if (cell[i] == '(') ++depth;
    if (cell[i] == ')') --depth;
    if (cell[i] == '`' && depth == 0) {
      const auto end = cell.find('`', i + 1);
      keys.push_back(cell.substr(i + 1, end - i - 1));
      i = end;
    }
  }
  return keys;
}

/// "" when the rule cell of a number's row states the schema's range ("[1e-7, 1], <= end",
/// "integer [3, 100000]", "(2, 1e6], default 20"), else what differs: docs/scenario.md's
/// tables and the schema say the same ranges ("Limits").
std::string documented_range_problem(const std::string& rule, const json& node) {
  const auto type = node.find("type");
  if (type == node.end() || !(*type == "number" || *type == "integer") || node.contains("const"))
    return "";
  const auto bound = [&](const char* exclusive, const char* inclusive, bool& open) -> const json* {
    open = node.contains(exclusive);
    const auto it = node.find(open ? exclusive : inclusive);
    return it == node.end() ? nullptr : &*it;
  };
  bool lo_open = false, hi_open = false;
  const json* lo = bound("exclusiveMinimum", "minimum", lo_open);
  const json* hi = bound("exclusiveMaximum", "maximum", hi_open);
  if (lo == nullptr || hi == nullptr) return "";  // parameter_ranges_test.cpp says so
  const std::string wanted =
      std::string(lo_open ? "(" : "[") + lo->dump() + ", " + hi->dump() + (hi_open ? ")" : "]");
  static const std::regex range(R"(([\[(])\s*([-+0-9.eE]+)\s*,\s*([-+0-9.eE]+)\s*([\])]))");
  std::smatch m;
  if (std::regex_search(rule, m, range) && (m[1] == "(") == lo_open && (m[4] == ")") == hi_open &&
      std::strtod(m[2].str().c_str(), nullptr) == lo->get<double>() &&
      std::strtod(m[3].str().c_str(), nullptr) == hi->get<double>())
    return "";
  return "the rule \"" + rule + "\" does not state the schema's range " + wanted;
}

struct DocumentedKeys {
  std::set<std::string> keys;  // "track.sleepers.count", "vehicles.[].speed"
  std::vector<std::string> problems;
};

DocumentedKeys check_document() {
  DocumentedKeys out;
  std::istringstream doc(test::read_file(test::source_dir() / "docs" / "scenario.md"));
  std::vector<std::string> section;
  bool in_section = false;
  std::string line;
  const std::set<std::string> variants = {"none", "dip", "bump", "wheel_flat", "random"};
  while (std::getline(doc, line)) {
    if (line.rfind("## ", 0) == 0 || line.rfind("### ", 0) == 0) {
      const std::string title = line.substr(line.find(' ') + 1);
      in_section = true;
      if (title == "Top level") {
        section = {};
      } else if (title == "`time`" || title == "`track`" || title == "`outputs`" ||
                 title == "`coupling`") {
        section = {title.substr(1, title.size() - 2)};
      } else if (title == "`vehicles[i]`") {
        section = {"vehicles", "[]"};
      } else {
        in_section = false;
      }
      continue;
    }
    if (!in_section || line.rfind("| `", 0) != 0) continue;
    const auto cells = split(line, '|');  // "", key, ..., meaning
    const std::string key = trim(cells[1]).substr(1, trim(cells[1]).size() - 2);
    if (section == std::vector<std::string>{"track"} && variants.count(key) > 0) {
      // The unevenness table: type, keys, meaning.
      const json& branches = schema().at("/definitions/unevenness/allOf"_json_pointer);
      const json* then = nullptr;
      for (const json& b : branches) {
        if (b.at("/if/properties/type/const"_json_pointer) == key) then = &b.at("then");
      }
      if (then == nullptr) {
        out.problems.push_back("unevenness type " + key + " is not in the schema");
        continue;
      }
      std::set<std::string> documented;
      for (const std::string& k : keys_in(cells[2])) documented.insert(k);
      std::set<std::string> in_schema;
      for (const auto& [k, v] : then->at("properties").items()) {
        if (k != "type") in_schema.insert(k);
      }
      if (documented != in_schema) {
        out.problems.push_back("unevenness " + key + ": documented and schema keys differ");
      }
      continue;
    }
    std::vector<std::string> path = section;
    for (const std::string& step : split(key, '.')) path.push_back(step);
    std::string dotted;
    for (const std::string& step : path) dotted += (dotted.empty() ? "" : ".") + step;
    out.keys.insert(dotted);
    const json* node = node_at(path);
    if (node == nullptr) {
      out.problems.push_back(dotted + " is documented but not in the schema");
      continue;
    }
    if (const std::string p = documented_range_problem(trim(cells[3]), *node); !p.empty())
      out.problems.push_back(dotted + ": " + p);
    // Tables with a default column: | key | unit | rule | default | meaning |.
    if (std::count(line.begin(), line.end(), '|') == 6) {
      const std::string documented = trim(cells[4]);
      json value;
      try {
        value = json::parse(documented.front() == '`' ? documented.substr(1, documented.size() - 2)
                                                      : documented);
      } catch (const std::exception&) {
        continue;  // "computed", "from contact stiffness": no schema default
      }
      if (!node->contains("default") || node->at("default") != value) {
        out.problems.push_back(dotted + ": documented default " + documented + ", schema default " +
                               (node->contains("default") ? node->at("default").dump() : "none"));
      }
    }
  }
  return out;
}

void schema_keys(const json& node, const std::string& prefix, std::set<std::string>& out) {
  const json* n = follow(&node);
  if (n->contains("items")) schema_keys(n->at("items"), prefix + "[].", out);
  if (!n->contains("properties")) return;
  for (const auto& [k, v] : n->at("properties").items()) {
    out.insert(prefix + k);
    // Components are documented as a whole ({"type", "params"}), unevenness by its own table.
    const auto ref = v.find("$ref");
    const bool component = ref != v.end() && *ref == "#/definitions/component";
    if (k != "unevenness" && !component) schema_keys(v, prefix + k + ".", out);
  }
}

/// Keys whose schema has no "description" (on the property or on what its $ref names).
void undescribed(const json& node, const std::string& prefix, std::vector<std::string>& out) {
  const json* n = follow(&node);
  if (n->contains("items")) undescribed(n->at("items"), prefix + "[].", out);
  if (n->contains("allOf")) {
    for (const json& branch : n->at("allOf")) {
      if (branch.contains("then")) undescribed(branch.at("then"), prefix, out);
    }
  }
  if (!n->contains("properties")) return;
  for (const auto& [k, v] : n->at("properties").items()) {
    if (k == "type" && v.empty()) continue;  // the discriminator again, in a variant
    if (!v.contains("description") && !follow(&v)->contains("description")) {
      out.push_back(prefix + k);
    }
    undescribed(v, prefix + k + ".", out);
  }
}

TEST(ScenarioSchema, IsAValidSchemaWithADescriptionForEveryKey) {
  EXPECT_NO_THROW(SchemaChecker(std::string(scenario_schema_text())));
  std::vector<std::string> missing;
  undescribed(schema(), "", missing);
  EXPECT_EQ(missing, std::vector<std::string>{}) << "units and meaning go in the description";
}

TEST(ScenarioSchema, MatchesDocsScenarioMd) {
  const DocumentedKeys documented = check_document();
  for (const std::string& p : documented.problems) ADD_FAILURE() << p;
  std::set<std::string> keys;
  schema_keys(schema(), "", keys);
  for (const std::string& k : keys) {
    // An object documented only through its members ("sleepers.count") counts as documented.
    const bool listed = documented.keys.count(k) > 0 ||
                        std::any_of(documented.keys.begin(), documented.keys.end(),
                                    [&](const std::string& d) { return d.rfind(k + ".", 0) == 0; });
    EXPECT_TRUE(listed) << k << " is in the schema but not in docs/scenario.md";
  }
  EXPECT_GT(documented.keys.size(), 40u);  // the tables were found at all
}

}  // namespace
}  // namespace rumble::scenario
