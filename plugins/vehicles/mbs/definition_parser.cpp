// definition_parser.cpp: JSON -> Definition, with every value checked where it is read.
#include <cmath>
#include <map>
#include <string>
#include <vector>

#include "definition.hpp"
#include "json_reader.hpp"

namespace rumble::mbs {
namespace {

using nlohmann::json;
using vehicles::fail;
using vehicles::ObjectReader;
using vehicles::shown;

constexpr double kDefaultWheelRadius = 0.46;  // m, main-line stock (docs/physics.md §1.2)
constexpr const char* kReferenceName = "reference";

std::string index_pointer(const std::string& array_where, std::size_t i) {
  return array_where + "/" + std::to_string(i);
}

/// [x, z] in m; absent: the frame origin.
void read_point(ObjectReader& r, const char* key, BodyPoint& p) {
  const json* v = r.value(key);
  if (v == nullptr) return;
  if (!v->is_array() || v->size() != 2 || !(*v)[0].is_number() || !(*v)[1].is_number()) {
    fail(r.at(key), "expected a point [x, z] in m (two numbers, body frame)", shown(*v));
  }
  p.x = (*v)[0].get<double>();
  p.z = (*v)[1].get<double>();
}

std::string read_name(ObjectReader& r, const char* key, const char* meaning) {
  const std::string name = r.string(key, meaning);
  if (name.empty()) fail(r.at(key), "must not be empty", "\"\"", meaning);
  return name;
}

double read_inertia(ObjectReader& r) {
  constexpr const char* kFix =
      "give I_yy in kg m^2 (about the centre of mass) or a symmetric 3x3 tensor [[Ixx, Ixy, Ixz], "
      "[Ixy, Iyy, Iyz], [Ixz, Iyz, Izz]]";
  const json* v = r.value("inertia");
  if (v == nullptr) return 0.0;
  if (v->is_number()) {
    const double iyy = v->get<double>();
    if (!(iyy >= 0.0) || !std::isfinite(iyy))
      fail(r.at("inertia"), "must be >= 0 kg m^2", shown(*v), kFix);
    return iyy;
  }
  bool ok = v->is_array() && v->size() == 3;
  for (std::size_t i = 0; ok && i < 3; ++i) {
    ok = (*v)[i].is_array() && (*v)[i].size() == 3;
    for (std::size_t j = 0; ok && j < 3; ++j) ok = (*v)[i][j].is_number();
  }
  if (!ok) fail(r.at("inertia"), "expected a number or a 3x3 array of numbers", shown(*v), kFix);
  for (std::size_t i = 0; i < 3; ++i) {
    for (std::size_t j = i + 1; j < 3; ++j) {
      const double a = (*v)[i][j].get<double>();
      const double b = (*v)[j][i].get<double>();
      if (std::abs(a - b) > 1e-9 * (std::abs(a) + std::abs(b))) {
        fail(r.at("inertia"), "the tensor must be symmetric", shown(*v), kFix);
      }
    }
    if (!((*v)[i][i].get<double>() >= 0.0)) {
      fail(r.at("inertia"), "diagonal terms must be >= 0 kg m^2", shown(*v), kFix);
    }
  }
  // Only pitch occurs in the vertical plane: omega = (0, theta', 0), so only I_yy matters.
  return (*v)[1][1].get<double>();
}

Motion read_motion(ObjectReader& r) {
  static const std::vector<std::string> kTypes{"tx", "tz", "ry"};
  const std::string type = r.string("type", "one of \"tx\", \"tz\", \"ry\"");
  if (type == "tx") return Motion::kTranslateX;
  if (type == "tz") return Motion::kTranslateZ;
  if (type == "ry") return Motion::kRotateY;
  fail(r.at("type"), "unknown transformation" + vehicles::did_you_mean(type, kTypes),
       shown(json(type)),
       "use \"tx\" or \"tz\" (translation along the current x or z axis, m) or \"ry\" (rotation "
       "about y, rad, positive lifts the front)");
}

void read_transforms(ObjectReader& br, Body& body, Definition& d,
                     std::map<std::string, std::string>& dof_users) {
  const json& list = br.array("transforms", false, "a list of {\"type\", \"value\", \"dof\"}");
  for (std::size_t k = 0; k < list.size(); ++k) {
    ObjectReader tr(list[k], index_pointer(br.at("transforms"), k));
    Transform t;
    t.motion = read_motion(tr);
    t.value = tr.number_or("value", 0.0);
    if (tr.value("dof") != nullptr) {  // value() also marks "dof" as a known key
      const std::string name = read_name(tr, "dof", "name the DOF this transformation adds to");
      const auto used = dof_users.find(name);
      if (used != dof_users.end()) {
        fail(tr.at("dof"), "DOF \"" + name + "\" already drives " + used->second, {},
             "a DOF drives exactly one transformation; give this one another name");
      }
      dof_users.emplace(name, tr.where());
      t.dof = static_cast<int>(d.dof_names.size());
      d.dof_names.push_back(name);
      d.dof_where.push_back(tr.where());
    }
    tr.finish();
    body.transforms.push_back(t);
  }
}

void read_bodies(ObjectReader& r, Definition& d) {
  const json& list = r.array("bodies", true, "give the vehicle's bodies");
  if (list.empty()) fail(r.at("bodies"), "must list at least one body", "[]");
  std::map<std::string, std::string> names;      // body name -> pointer
  std::map<std::string, std::string> dof_users;  // DOF name -> pointer of its transformation
  for (std::size_t i = 0; i < list.size(); ++i) {
    ObjectReader br(list[i], index_pointer(r.at("bodies"), i));
    Body b;
    b.where = br.where();
    b.name = read_name(br, "name", "name the body (unique)");
    if (b.name == kReferenceName) {
      fail(br.at("name"), "\"reference\" is reserved for the vehicle reference frame",
           shown(json(b.name)), "choose another name");
    }
    if (const auto it = names.find(b.name); it != names.end()) {
      fail(br.at("name"), "body name \"" + b.name + "\" is already used by " + it->second, {},
           "give each body a unique name");
    }
    names.emplace(b.name, b.where);
    b.parent_name = br.string_or("parent", kReferenceName);
    b.mass = br.positive("mass", "kg", "give the body's mass in kg (one side of the vehicle)");
    b.inertia_yy = read_inertia(br);
    read_transforms(br, b, d, dof_users);
    br.finish();
    d.bodies.push_back(std::move(b));
  }
}

void read_point_on(ObjectReader& r, const char* body_key, const char* point_key, BodyPoint& p,
                   bool reference_allowed) {
  p.body_name = reference_allowed ? r.string_or(body_key, kReferenceName)
                                  : read_name(r, body_key, "name the body it is attached to");
  if (!reference_allowed && p.body_name == kReferenceName) {
    fail(r.at(body_key), "must be a body, not the reference frame", shown(json(p.body_name)),
         "name one of the bodies");
  }
  p.where = r.at(body_key);
  read_point(r, point_key, p);
}

Direction read_direction(ObjectReader& r) {
  static const std::vector<std::string> kDirections{"z", "x", "line"};
  const std::string s = r.string_or("direction", "z");
  if (s == "z") return Direction::kZ;
  if (s == "x") return Direction::kX;
  if (s == "line") return Direction::kLine;
  fail(r.at("direction"), "unknown direction" + vehicles::did_you_mean(s, kDirections),
       shown(json(s)),
       "use \"z\" or \"x\" (along that axis of the reference frame) or \"line\" (along the line "
       "between the two points)");
}

void read_elements(ObjectReader& r, Definition& d) {
  const json& list = r.array("elements", false, "a list of spring-damper elements");
  for (std::size_t i = 0; i < list.size(); ++i) {
    ObjectReader er(list[i], index_pointer(r.at("elements"), i));
    Element e;
    e.where = er.where();
    e.name = er.string_or("name", "element" + std::to_string(i));
    read_point_on(er, "body_a", "point_a", e.a, true);
    read_point_on(er, "body_b", "point_b", e.b, true);
    if (e.a.body_name == e.b.body_name) {
      fail(er.at("body_b"), "an element must join two different bodies", shown(json(e.b.body_name)),
           "name another body (or \"reference\") for body_a or body_b");
    }
    e.direction = read_direction(er);
    e.k = er.non_negative_or("k", 0.0, "N/m", "give the stiffness in N/m");
    e.c = er.non_negative_or("c", 0.0, "N s/m", "give the viscous damping in N s/m");
    e.preload = er.number_or("preload", 0.0);
    er.finish();
    d.elements.push_back(std::move(e));
  }
}

void read_wheels(ObjectReader& r, Definition& d) {
  const json& list = r.array("wheels", true, "give the wheels (at least one)");
  if (list.empty()) fail(r.at("wheels"), "must list at least one wheel", "[]");
  for (std::size_t i = 0; i < list.size(); ++i) {
    ObjectReader wr(list[i], index_pointer(r.at("wheels"), i));
    WheelDef w;
    w.where = wr.where();
    w.name = wr.string_or("name", "wheel" + std::to_string(i));
    read_point_on(wr, "body", "point", w.centre, false);
    w.radius = wr.positive_or("radius", kDefaultWheelRadius, "m", "give the rolling radius in m");
    wr.finish();
    d.wheels.push_back(std::move(w));
  }
}

void read_loads(ObjectReader& r, Definition& d) {
  const json& list = r.array("loads", false, "a list of constant vertical loads");
  for (std::size_t i = 0; i < list.size(); ++i) {
    ObjectReader lr(list[i], index_pointer(r.at("loads"), i));
    Load l;
    l.name = lr.string_or("name", "load" + std::to_string(i));
    read_point_on(lr, "body", "point", l.point, false);
    l.force = lr.number("force", "give the force in N, downward positive");
    lr.finish();
    d.loads.push_back(std::move(l));
  }
}

}  // namespace

Definition parse_definition(const json& j, const std::string& where) {
  ObjectReader r(j, where);
  Definition d;
  r.string_or("description", "");
  d.gravity = r.non_negative_or("gravity", vehicles::kStandardGravity, "m/s^2",
                                "9.81 on Earth, 0 to switch gravity off");
  read_bodies(r, d);
  read_elements(r, d);
  read_wheels(r, d);
  read_loads(r, d);
  r.finish();
  resolve_topology(d);
  return d;
}

}  // namespace rumble::mbs
