// mbs_schema.cpp: params are either {"file": ...} or an inline definition (docs/vehicles.md).
// The same rules are checked again by the parser, which also reads definition files the host
// never sees; the schema exists so that `rumble validate` and `rumble schema mbs` can show them.
#include "mbs_schema.hpp"

namespace rumble::mbs {

const char* mbs_params_schema() {
  return R"json({
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
    "gravity": {"type": "number", "minimum": 0,
                "description": "gravitational acceleration [m/s^2], default 9.81"},
    "bodies": {"type": "array", "minItems": 1, "items": {"$ref": "#/definitions/body"}},
    "elements": {"type": "array", "items": {"$ref": "#/definitions/element"}},
    "wheels": {"type": "array", "minItems": 1, "items": {"$ref": "#/definitions/wheel"}},
    "loads": {"type": "array", "items": {"$ref": "#/definitions/load"}}
  },
  "definitions": {
    "name": {"type": "string", "minLength": 1},
    "point": {"type": "array", "items": {"type": "number"}, "minItems": 2, "maxItems": 2,
              "description": "[x, z] in the body frame [m], x forward, z down"},
    "body": {
      "type": "object", "additionalProperties": false, "required": ["name", "mass"],
      "properties": {
        "name": {"$ref": "#/definitions/name"},
        "parent": {"type": "string", "default": "reference",
                   "description": "body whose frame the transforms start from, or \"reference\" (the vehicle frame)"},
        "mass": {"type": "number", "exclusiveMinimum": 0, "description": "mass [kg]"},
        "inertia": {"description": "pitch inertia I_yy about the centre of mass [kg m^2], or a symmetric 3x3 tensor (only I_yy is used)",
                    "oneOf": [{"type": "number", "minimum": 0},
                              {"type": "array", "minItems": 3, "maxItems": 3,
                               "items": {"type": "array", "minItems": 3, "maxItems": 3, "items": {"type": "number"}}}]},
        "transforms": {"type": "array", "items": {"$ref": "#/definitions/transform"},
                       "description": "from the parent frame to this body's frame (origin = centre of mass)"}
      }
    },
    "transform": {
      "type": "object", "additionalProperties": false, "required": ["type"],
      "properties": {
        "type": {"enum": ["tx", "tz", "ry"],
                 "description": "translation along the current x or z axis [m], rotation about y [rad] (positive lifts the front)"},
        "value": {"type": "number", "default": 0, "description": "nominal value at q = 0 [m or rad]"},
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
        "k": {"type": "number", "minimum": 0, "default": 0, "description": "stiffness [N/m]"},
        "c": {"type": "number", "minimum": 0, "default": 0, "description": "viscous damping [N s/m]"},
        "preload": {"type": "number", "default": 0, "description": "compression force at q = 0 [N]"}
      }
    },
    "wheel": {
      "type": "object", "additionalProperties": false, "required": ["body"],
      "properties": {
        "name": {"type": "string"},
        "body": {"$ref": "#/definitions/name"},
        "point": {"$ref": "#/definitions/point", "description": "wheel centre in the body frame [m]"},
        "radius": {"type": "number", "exclusiveMinimum": 0, "default": 0.46, "description": "rolling radius [m]"}
      }
    },
    "load": {
      "type": "object", "additionalProperties": false, "required": ["body", "force"],
      "properties": {
        "name": {"type": "string"},
        "body": {"$ref": "#/definitions/name"},
        "point": {"$ref": "#/definitions/point"},
        "force": {"type": "number", "description": "constant vertical force, down + [N]"}
      }
    }
  }
})json";
}

}  // namespace rumble::mbs
