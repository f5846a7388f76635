// definition.hpp: a multibody vehicle as read from JSON (see docs/vehicles.md).
//
// Vertical plane (x forward, z down, rotations about y; a positive pitch lifts the front). A body's
// frame is reached from the vehicle reference frame, or from its parent body's frame, by a chain
// of homogeneous transformations, each a translation along the current x or z axis or a rotation
// about y, by a nominal value plus (optionally) one DOF. The frame origin is the body's centre of
// mass. DOFs are numbered in order of first appearance (bodies in file order, then transforms).
#ifndef RUMBLE_MBS_DEFINITION_HPP
#define RUMBLE_MBS_DEFINITION_HPP

#include <nlohmann/json.hpp>
#include <string>
#include <vector>

namespace rumble::mbs {

/// Index of the vehicle reference frame where a body index is expected.
inline constexpr int kReference = -1;
/// dof of a constant transformation.
inline constexpr int kNoDof = -1;

enum class Motion { kTranslateX, kTranslateZ, kRotateY };

struct Transform {
  Motion motion = Motion::kTranslateX;
  double value = 0.0;  // nominal value at q = 0 [m or rad]
  int dof = kNoDof;    // the DOF added to value, or kNoDof
};

struct Body {
  std::string name;
  std::string where;        // JSON pointer of the body, for messages
  std::string parent_name;  // "reference" for the vehicle frame
  int parent = kReference;  // resolved by resolve_topology()
  double mass = 0.0;        // kg
  double inertia_yy = 0.0;  // kg m^2, about the centre of mass, pitch axis
  std::vector<Transform> transforms;
};

/// A point fixed on a body (or on the reference frame), coordinates in that body's frame [m].
struct BodyPoint {
  std::string body_name;
  std::string where;  // JSON pointer of the body name, for messages
  int body = kReference;
  double x = 0.0;
  double z = 0.0;
};

/// kX, kZ: the element acts along the reference frame's x or z axis on the relative displacement
/// of its points along that axis; kLine: along the line joining the points (length-based).
enum class Direction { kX, kZ, kLine };

/// Linear spring-damper. Its force F (compression positive, N) is
///   F = preload - k (s - s0) - c s'
/// with s = coordinate of b minus that of a along the axis (kX, kZ) or the distance |b - a|
/// (kLine), s0 its value at q = 0. F pushes b along +axis (kLine: away from a) and a the other way:
/// with b the lower point, a positive F is the compression of a suspension carrying weight.
struct Element {
  std::string name;
  std::string where;
  BodyPoint a, b;
  Direction direction = Direction::kZ;
  double k = 0.0;        // N/m
  double c = 0.0;        // N s/m
  double preload = 0.0;  // N, F at q = 0 and rest
};

struct WheelDef {
  std::string name;
  std::string where;
  BodyPoint centre;     // wheel centre; the contact point is radius below it, moving with it
  double radius = 0.0;  // m
};

/// A constant vertical force (down +) at a body point: payload not modelled as a body.
struct Load {
  std::string name;
  BodyPoint point;
  double force = 0.0;  // N
};

struct Definition {
  double gravity = 0.0;  // m/s^2
  std::vector<std::string> dof_names;
  std::vector<std::string> dof_where;  // pointer of the transform each DOF drives
  std::vector<Body> bodies;
  std::vector<int> order;  // body indices, every parent before its children
  std::vector<Element> elements;
  std::vector<WheelDef> wheels;
  std::vector<Load> loads;
};

/// Reads a definition; where is the pointer of j ("params", or "<file>#"). Throws
/// std::invalid_argument with pointer, value and fix. Names and the body tree are resolved.
Definition parse_definition(const nlohmann::json& j, const std::string& where);

/// Resolves parent and point body names, rejects unknown names and cycles, fills order.
void resolve_topology(Definition& d);

}  // namespace rumble::mbs

#endif  // RUMBLE_MBS_DEFINITION_HPP
