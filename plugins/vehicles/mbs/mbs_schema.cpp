// mbs_schema.cpp: params are either {"file": ...} or an inline definition (docs/vehicles.md).
// The same rules are checked again by the parser, which also reads definition files the host
// never sees; the schema exists so that `rumble validate` and `rumble schema mbs` can show them.
#include "mbs_schema.hpp"

namespace rumble::mbs {
namespace {

constexpr const char kMbsParamsSchema[] = R"json({
  "type": "object",
  "additionalProperties": false,
  "description": "multibody vehicle in the vertical plane (one side), defined inline or in a file; see docs/vehicles.md",
  "oneOf": [
    {"required": ["file"], "maxProperties": 1},
    {"required": ["bodies", "wheels"], "not": {"required": ["file"]}}
  ],
  "properties": {
    "file": {"type": "string", "minLength": 1,
             "description": "vehicle definition (JSON with the keys below), relative to the scenario file's directory"},
    "description": {"type": "string"},
    "gravity": {"type": "number", "minimum": 0, "maximum": 30,
                "description": "gravitational acceleration [m/s^2], default 9.81; [0, 30] m/s^2: 9.81 on Earth, 0 switches gravity off"},
    "bodies": {"type": "array", "minItems": 1, "items": {"$ref": "#/definitions/body"}},
    "elements": {"type": "array", "items": {"$ref": "#/definitions/element"}},
    "wheels": {"type": "array", "minItems": 1, "items": {"$ref": "#/definitions/wheel"}},
    "loads": {"type": "array", "items": {"$ref": "#/definitions/load"}}
  },
  "definitions": {
    "name": {"type": "string", "minLength": 1},
    "point": {"type": "array", "items": {"$ref": "#/definitions/coordinate"}, "minItems": 2, "maxItems": 2,
              "description": "[x, z] in the body frame [m], x forward, z down"},
    "coordinate": {"type": "number", "minimum": -100, "maximum": 100,
                   "description": "a coordinate in a body frame [m]; [-100, 100] m: a rail vehicle is at most some 30 m long"},
    "body": {
      "type": "object", "additionalProperties": false, "required": ["name", "mass"],
      "properties": {
        "name": {"$ref": "#/definitions/name"},
        "parent": {"type": "string", "default": "reference",
                   "description": "body whose frame the transforms start from, or \"reference\" (the vehicle frame)"},
        "mass": {"type": "number", "minimum": 0.1, "maximum": 1e6, "description": "mass [kg]; [0.1, 1e6] kg: from a small part to beyond a whole locomotive (some 120 t)"},
        "inertia": {"description": "pitch inertia I_yy about the centre of mass [kg m^2], or a symmetric 3x3 tensor (only I_yy is used); [0, 1e8] kg m^2: a 40 t car body is about 2e6 kg m^2",
                    "oneOf": [{"type": "number", "minimum": 0, "maximum": 1e8, "description": "I_yy [kg m^2]; [0, 1e8] kg m^2: a 40 t car body 25 m long is about 2e6 kg m^2"},
                              {"type": "array", "minItems": 3, "maxItems": 3,
                               "items": {"type": "array", "minItems": 3, "maxItems": 3, "items": {"type": "number", "minimum": -1e8, "maximum": 1e8, "description": "a tensor component [kg m^2]; [-1e8, 1e8] kg m^2: as I_yy's (a 40 t car body is about 2e6 kg m^2)"}}}]},
        "transforms": {"type": "array", "items": {"$ref": "#/definitions/transform"},
                       "description": "from the parent frame to this body's frame (origin = centre of mass)"}
      }
    },
    "transform": {
      "type": "object", "additionalProperties": false, "required": ["type"],
      "properties": {
        "type": {"enum": ["tx", "tz", "ry"],
                 "description": "translation along the current x or z axis [m], rotation about y [rad] (positive lifts the front)"},
        "value": {"type": "number", "minimum": -100, "maximum": 100, "default": 0, "description": "nominal value at q = 0 [m or rad]; [-100, 100]: a rail vehicle is at most some 30 m long, and an angle is within a turn of 2 pi"},
        "dof": {"$ref": "#/definitions/name", "description": "name of the DOF added to value (each DOF drives one transformation)"}
      }
    },
    "element": {
      "type": "object", "additionalProperties": false, "required": ["body_a", "body_b"],
      "properties": {
        "name": {"type": "string"},
        "body_a": {"type": "string", "description": "body name or \"reference\""},
        "point_a": {"$ref": "#/definitions/point"},
        "body_b": {"type": "string", "description": "body name or \"reference\" (usually the lower end)"},
        "point_b": {"$ref": "#/definitions/point"},
        "direction": {"enum": ["z", "x", "line"], "default": "z"},
        "k": {"type": "number", "minimum": 0, "maximum": 1e10, "default": 0, "description": "stiffness [N/m]; [0, 1e10] N/m: suspension springs are 1e5 to 1e7 N/m; 1e10 N/m is practically rigid"},
        "c": {"type": "number", "minimum": 0, "maximum": 1e8, "default": 0, "description": "viscous damping [N s/m]; [0, 1e8] N s/m: suspension dampers are 1e3 to 1e5 N s/m"},
        "preload": {"type": "number", "minimum": -1e7, "maximum": 1e7, "default": 0, "description": "compression force at q = 0 [N]; [-1e7, 1e7] N: a 120 t locomotive weighs 1.2e6 N"}
      }
    },
    "wheel": {
      "type": "object", "additionalProperties": false, "required": ["body"],
      "properties": {
        "name": {"type": "string"},
        "body": {"$ref": "#/definitions/name"},
        "point": {"$ref": "#/definitions/point", "description": "wheel centre in the body frame [m]"},
        "radius": {"type": "number", "minimum": 0.1, "maximum": 2, "default": 0.46, "description": "rolling radius [m]; [0.1, 2] m: from small tram and bogie wheels (0.3 m) to the largest steam locomotive drivers (about 1.1 m)"}
      }
    },
    "load": {
      "type": "object", "additionalProperties": false, "required": ["body", "force"],
      "properties": {
        "name": {"type": "string"},
        "body": {"$ref": "#/definitions/name"},
        "point": {"$ref": "#/definitions/point"},
        "force": {"type": "number", "minimum": -1e7, "maximum": 1e7, "description": "constant vertical force, down + [N]; [-1e7, 1e7] N: a 120 t locomotive weighs 1.2e6 N"}
      }
    }
  }
})json";

}  // namespace

const char* mbs_params_schema() {
  return kMbsParamsSchema;
}

}  // namespace rumble::mbs
