// topology.cpp: body names -> indices, the body tree's evaluation order, and its errors.
#include <string>
#include <vector>

#include "definition.hpp"
#include "json_reader.hpp"

namespace rumble::mbs {
namespace {

using vehicles::fail;

int find_body(const Definition& d, const std::string& name) {
  for (std::size_t i = 0; i < d.bodies.size(); ++i) {
    if (d.bodies[i].name == name) return static_cast<int>(i);
  }
  return kReference - 1;  // not found
}

std::vector<std::string> body_names(const Definition& d) {
  std::vector<std::string> names;
  for (const Body& b : d.bodies) names.push_back(b.name);
  return names;
}

/// Index of a named body, kReference for "reference" when allowed; else a "did you mean" error.
int resolve(const Definition& d, const std::string& name, const std::string& where,
            bool reference_allowed) {
  if (reference_allowed && name == "reference") return kReference;
  const int i = find_body(d, name);
  if (i >= 0) return i;
  std::vector<std::string> candidates = body_names(d);
  std::string known;
  for (const std::string& c : candidates) known += (known.empty() ? "" : ", ") + c;
  if (reference_allowed) candidates.push_back("reference");
  fail(where, "no body is named \"" + name + "\"" + vehicles::did_you_mean(name, candidates), {},
       "name one of the bodies (" + known + ")" +
           (reference_allowed ? " or \"reference\" for the vehicle frame" : ""));
}

/// Depth-first: appends b after its ancestors; state 0 unseen, 1 on the current path, 2 done.
void visit(Definition& d, int b, std::vector<int>& state, std::vector<int>& path) {
  if (state[b] == 2) return;
  if (state[b] == 1) {
    // The cycle is the part of the path from b's first occurrence on.
    std::size_t start = 0;
    while (path[start] != b) ++start;
    std::string loop;
    for (std::size_t k = start; k < path.size(); ++k) loop += d.bodies[path[k]].name + " -> ";
    loop += d.bodies[b].name;
    fail(d.bodies[b].where + "/parent", "the bodies' parents form a cycle: " + loop, {},
         "every chain of parents must end at \"reference\"; attach one of these bodies to "
         "\"reference\" or to a body outside the cycle");
  }
  state[b] = 1;
  path.push_back(b);
  const int parent = d.bodies[b].parent;
  if (parent != kReference) visit(d, parent, state, path);
  path.pop_back();
  state[b] = 2;
  d.order.push_back(b);
}

}  // namespace

void resolve_topology(Definition& d) {
  for (Body& b : d.bodies) b.parent = resolve(d, b.parent_name, b.where + "/parent", true);
  std::vector<int> state(d.bodies.size(), 0);
  std::vector<int> path;
  for (std::size_t b = 0; b < d.bodies.size(); ++b) visit(d, static_cast<int>(b), state, path);
  for (Element& e : d.elements) {
    e.a.body = resolve(d, e.a.body_name, e.a.where, true);
    e.b.body = resolve(d, e.b.body_name, e.b.where, true);
  }
  for (WheelDef& w : d.wheels)
    w.centre.body = resolve(d, w.centre.body_name, w.centre.where, false);
  for (Load& l : d.loads) l.point.body = resolve(d, l.point.body_name, l.point.where, false);
}

}  // namespace rumble::mbs
