#include "scenario/scenario_schema.hpp"

namespace rumble::scenario {
namespace {

// Kept in step with docs/scenario.md by hand; the golden tests in tests/scenario pin both the
// rules and the messages they produce.
constexpr std::string_view kSchema = R"json({
  "$schema": "http://json-schema.org/draft-07/schema#",
  "title": "Rumble scenario",
  "description": "One co-simulation run: vehicles on a track on a soil, joined by a coupler. SI units; z positive downward.",
  "type": "object",
  "additionalProperties": false,
  "required": ["schema_version", "name", "time", "vehicles", "track", "soil", "coupling", "outputs"],
  "properties": {
    "schema_version": {"type": "integer", "const": 1, "description": "format version of this file; must be 1"},
    "name": {"type": "string", "minLength": 1, "description": "title used in results and plots"},
    "description": {"type": "string", "description": "free text"},
    "plugins": {
      "type": "array",
      "description": "extra plugin libraries (paths to .so files, relative to the scenario file), loaded before validation",
      "items": {"type": "string", "minLength": 1},
      "default": []
    },
    "time": {
      "type": "object",
      "description": "simulated time: {\"end\": [s], \"macro_step\": [s]}",
      "additionalProperties": false,
      "required": ["end", "macro_step"],
      "properties": {
        "end": {"type": "number", "exclusiveMinimum": 0, "description": "simulated duration, starting at t = 0 [s]"},
        "macro_step": {"type": "number", "exclusiveMinimum": 0, "description": "coupling step H, <= end [s]"}
      }
    },
    "vehicles": {
      "type": "array",
      "minItems": 1,
      "description": "the vehicles on the track: [{\"type\", \"speed\", \"start\", \"params\"}, ...]",
      "items": {
        "type": "object",
        "additionalProperties": false,
        "required": ["type", "speed", "start"],
        "properties": {
          "type": {"type": "string", "description": "a vehicle plugin type, e.g. single_wheel"},
          "name": {"type": "string", "minLength": 1, "maxLength": 64, "pattern": "^[A-Za-z0-9][A-Za-z0-9 _.=+()-]*$", "description": "label in results (default vehicle<i>), unique among the vehicles: a letter or digit, then letters, digits, spaces and _ . = + ( ) - (no comma, quote or bracket, which would break the CSV headers)"},
          "speed": {"type": "number", "minimum": 0, "description": "constant forward speed [m/s]"},
          "start": {"type": "number", "description": "position of the vehicle reference at t = 0, along the track [m]"},
          "params": {"type": "object", "default": {}, "description": "validated against the vehicle plugin's schema"}
        }
      }
    },
    "track": {
      "type": "object",
      "additionalProperties": false,
      "required": ["sleepers", "rail", "railpad", "ballast"],
      "description": "one rail of a symmetric track; values per rail (per rail seat, per half sleeper)",
      "properties": {
        "sleepers": {
          "type": "object",
          "description": "the sleepers, evenly spaced, and their footprints on the soil",
          "additionalProperties": false,
          "required": ["count", "spacing", "mass", "footprint"],
          "properties": {
            "count": {"type": "integer", "minimum": 3, "maximum": 100000, "description": "number of sleepers (at most 100000: 60 km at 0.6 m)"},
            "spacing": {"type": "number", "exclusiveMinimum": 0, "description": "distance between sleepers; sleeper i is at x = i * spacing [m]"},
            "mass": {"type": "number", "exclusiveMinimum": 0, "description": "mass per rail seat (half sleeper) [kg]"},
            "footprint": {
              "type": "object",
              "description": "contact patch of a whole sleeper on the soil",
              "additionalProperties": false,
              "required": ["length", "width"],
              "properties": {
                "length": {"type": "number", "exclusiveMinimum": 0, "description": "footprint extent across the track (whole sleeper) [m]"},
                "width": {"type": "number", "exclusiveMinimum": 0, "description": "footprint extent along the track [m]"}
              }
            }
          }
        },
        "rail": {
          "type": "object",
          "description": "the rail, an Euler-Bernoulli beam",
          "additionalProperties": false,
          "required": ["E", "I", "mass_per_length"],
          "properties": {
            "E": {"type": "number", "exclusiveMinimum": 0, "description": "Young's modulus [Pa]"},
            "I": {"type": "number", "exclusiveMinimum": 0, "description": "second moment of area, vertical bending [m^4]"},
            "mass_per_length": {"type": "number", "exclusiveMinimum": 0, "description": "rail mass per length [kg/m]"},
            "elements_per_bay": {"type": "integer", "minimum": 1, "maximum": 32, "default": 4, "description": "beam elements between two sleepers"},
            "overhang_bays": {"type": "integer", "minimum": 0, "maximum": 20, "default": 1, "description": "rail bays beyond the first and last sleeper"}
          }
        },
        "railpad": {
          "type": "object",
          "description": "spring-dashpot from rail to sleeper, per rail seat",
          "additionalProperties": false,
          "required": ["k", "c"],
          "properties": {
            "k": {"type": "number", "exclusiveMinimum": 0, "description": "stiffness per rail seat [N/m]"},
            "c": {"type": "number", "minimum": 0, "description": "damping per rail seat [N s/m]"}
          }
        },
        "ballast": {
          "type": "object",
          "description": "spring-dashpot from sleeper to footprint, per half sleeper",
          "additionalProperties": false,
          "required": ["k", "c"],
          "properties": {
            "k": {"type": "number", "exclusiveMinimum": 0, "description": "stiffness per half sleeper [N/m]"},
            "c": {"type": "number", "minimum": 0, "description": "damping per half sleeper [N s/m]"}
          }
        },
        "contact": {
          "type": "object",
          "description": "Hertzian wheel/rail contact",
          "additionalProperties": false,
          "default": {},
          "properties": {
            "hertz_constant": {"type": "number", "exclusiveMinimum": 0, "description": "Hertz constant C_H; computed from the wheel and rail radii when absent [N/m^1.5]"},
            "rail_radius": {"type": "number", "exclusiveMinimum": 0, "default": 0.3, "description": "rail crown transverse radius [m]"},
            "E": {"type": "number", "exclusiveMinimum": 0, "default": 2.1e11, "description": "Young's modulus of wheel and rail steel [Pa]"},
            "nu": {"type": "number", "minimum": 0, "exclusiveMaximum": 0.5, "default": 0.3, "description": "Poisson's ratio of wheel and rail steel"}
          }
        },
        "unevenness": {"$ref": "#/definitions/unevenness"},
        "integrator": {
          "type": "object",
          "description": "Newmark time integration of track and vehicles",
          "additionalProperties": false,
          "default": {},
          "properties": {
            "micro_step": {"type": "number", "exclusiveMinimum": 0, "description": "track/vehicle step h; from the contact stiffness when absent [s]"},
            "gamma": {"type": "number", "minimum": 0.5, "maximum": 1, "default": 0.5, "description": "Newmark gamma; beta = (gamma + 1/2)^2 / 4"}
          }
        },
        "damping": {
          "type": "object",
          "description": "Rayleigh damping of the rail",
          "additionalProperties": false,
          "default": {},
          "properties": {
            "rayleigh_alpha": {"type": "number", "minimum": 0, "default": 0, "description": "mass-proportional rail damping [1/s]"},
            "rayleigh_beta": {"type": "number", "minimum": 0, "default": 0, "description": "stiffness-proportional rail damping [s]"}
          }
        }
      }
    },
    "soil": {"$ref": "#/definitions/component", "description": "the soil: a soil plugin type and its params"},
    "coupling": {
      "type": "object",
      "additionalProperties": false,
      "required": ["type"],
      "description": "the coupling scheme: a coupler plugin type, its params, and the extra participants it drives",
      "properties": {
        "type": {"type": "string", "description": "a coupler plugin type"},
        "params": {"type": "object", "default": {}, "description": "validated against the plugin's schema"},
        "participants": {
          "type": "object",
          "default": {},
          "description": "extra soil participants the coupler drives besides the track and /soil, by the names the coupler declares (e.g. two_step's reduced_soil)",
          "patternProperties": {"^[a-z][a-z0-9_]*$": {"$ref": "#/definitions/component"}},
          "additionalProperties": false
        },
        "divergence": {
          "type": "object",
          "additionalProperties": false,
          "default": {},
          "description": "what a diverging run does: a footprint speed that keeps growing at one exponential rate past twice anything the run did before, or a soil footprint displacement beyond displacement_factor x that soil's largest static one, counts as diverging (docs/couplers.md, Divergence)",
          "properties": {
            "action": {"enum": ["stop", "continue"], "default": "stop", "description": "stop: the run ends failed, with the time and the fix; continue: warn once, record it in summary.json and go on (a displacement beyond 1 m or not finite still stops it)"},
            "displacement_factor": {"type": "number", "exclusiveMinimum": 2, "maximum": 1e6, "default": 20, "description": "bound on |footprint displacement| as a multiple of the largest static one [-]; a passing train amplifies the static settlement a few times at most"}
          }
        }
      }
    },
    "outputs": {
      "type": "object",
      "description": "where and what to record: {\"directory\": ...}",
      "additionalProperties": false,
      "required": ["directory"],
      "properties": {
        "directory": {"type": "string", "minLength": 1, "description": "results directory, relative to the scenario file"},
        "receivers": {
          "type": "array",
          "items": {
            "description": "a distance from the track axis of a surface receiver at mid-track [m], or a named point {name, y, x, depth}",
            "oneOf": [
              {"type": "number", "exclusiveMinimum": 0},
              {
                "type": "object",
                "additionalProperties": false,
                "required": ["name", "y"],
                "properties": {
                  "name": {"type": "string", "minLength": 1, "maxLength": 64, "pattern": "^[A-Za-z0-9][A-Za-z0-9 _.=+()-]*$", "description": "column name in receivers.csv, unique among the receivers: a letter or digit, then letters, digits, spaces and _ . = + ( ) - (no comma, quote or bracket, which would break the CSV header)"},
                  "y": {"type": "number", "description": "distance across the track from its axis [m]"},
                  "x": {"type": "number", "description": "position along the track [m]; default the middle of the sleepers"},
                  "depth": {"type": "number", "minimum": 0, "default": 0, "description": "depth below the surface [m]"}
                }
              }
            ]
          },
          "default": [],
          "description": "receivers whose motion is recorded (soils that offer them)"
        },
        "receiver_interval": {"type": "number", "minimum": 0, "default": 0, "description": "sampling interval of receivers [s]; 0: every step of the soil"},
        "fields": {
          "type": "object",
          "additionalProperties": false,
          "required": ["interval"],
          "description": "soil field snapshots (VTU, soils that offer them) and their ParaView index soil.pvd",
          "properties": {
            "interval": {"type": "number", "exclusiveMinimum": 0, "description": "time between snapshots, the first at t = 0 [s]"}
          }
        },
        "post": {
          "type": "object",
          "additionalProperties": false,
          "default": {},
          "description": "the vibration indicators written to post/ after a run with receivers (docs/post-processing.md); rumble post RESULTS_DIR recomputes them with these, its options overriding",
          "properties": {
            "cwt_distances": {"type": "array", "items": {"type": "number", "minimum": 0}, "default": [2.5, 5.0], "description": "distances from the track [m] whose nearest receivers get a wavelet transform of v_z (the seed paper's Figures 6 and 7: 2.5 and 5 m)"},
            "f_max": {"type": "number", "exclusiveMinimum": 0, "default": 200, "description": "highest frequency of the wavelet transforms [Hz]; give what the soil resolves (a FEM soil: rumble mesh reports it per distance), or the scalograms show what the mesh cannot carry"},
            "reference": {"enum": ["iso", "vdb"], "default": "iso", "description": "velocity reference of the one-third-octave levels: iso (ISO 1683, 1e-9 m/s) or vdb (VdB, 2.54e-8 m/s = 1 micro-inch/s)"}
          }
        },
        "every": {"type": "integer", "minimum": 1, "default": 1, "description": "record every n-th macro step"},
        "plots": {"type": "boolean", "default": true, "description": "run tools/plot_results.py after the run when python3 and matplotlib exist"}
      }
    }
  },
  "definitions": {
    "component": {
      "type": "object",
      "additionalProperties": false,
      "required": ["type"],
      "properties": {
        "type": {"type": "string", "description": "a plugin type of the right kind"},
        "params": {"type": "object", "default": {}, "description": "validated against the plugin's schema"}
      }
    },
    "unevenness": {
      "type": "object",
      "description": "rail surface profile r(x), positive downward",
      "default": {"type": "none"},
      "required": ["type"],
      "properties": {
        "type": {"enum": ["none", "dip", "bump", "wheel_flat", "random"], "description": "kind of profile"}
      },
      "allOf": [
        {
          "if": {"required": ["type"], "properties": {"type": {"const": "none"}}},
          "then": {"additionalProperties": false, "properties": {"type": {}}}
        },
        {
          "if": {"required": ["type"], "properties": {"type": {"const": "dip"}}},
          "then": {
            "additionalProperties": false,
            "required": ["position", "length", "depth"],
            "properties": {
              "type": {},
              "position": {"type": "number", "description": "centre of the dip along the track [m]"},
              "length": {"type": "number", "exclusiveMinimum": 0, "description": "length of the cosine dip [m]"},
              "depth": {"type": "number", "exclusiveMinimum": 0, "description": "depth of the dip (rail joint) [m]"}
            }
          }
        },
        {
          "if": {"required": ["type"], "properties": {"type": {"const": "bump"}}},
          "then": {
            "additionalProperties": false,
            "required": ["position", "length", "height"],
            "properties": {
              "type": {},
              "position": {"type": "number", "description": "centre of the bump along the track [m]"},
              "length": {"type": "number", "exclusiveMinimum": 0, "description": "length of the cosine bump [m]"},
              "height": {"type": "number", "exclusiveMinimum": 0, "description": "height of the bump [m]"}
            }
          }
        },
        {
          "if": {"required": ["type"], "properties": {"type": {"const": "wheel_flat"}}},
          "then": {
            "additionalProperties": false,
            "required": ["length"],
            "properties": {
              "type": {},
              "length": {"type": "number", "exclusiveMinimum": 0, "description": "length of the rounded flat [m]"},
              "depth": {"type": "number", "exclusiveMinimum": 0, "description": "depth of the flat [m]; default L^2/(16 R), a worn (rounded) flat of length L"},
              "wheel": {"type": "integer", "minimum": 0, "default": 0, "description": "index of the flat wheel among all wheels"},
              "first_impact": {"type": "number", "minimum": 0, "description": "rolled distance at which the flat's centre first meets the rail [m]; default pi R (half a turn)"}
            }
          }
        },
        {
          "if": {"required": ["type"], "properties": {"type": {"const": "random"}}},
          "then": {
            "additionalProperties": false,
            "required": ["class", "seed", "wavelength_min", "wavelength_max"],
            "properties": {
              "type": {},
              "class": {"enum": ["FRA1", "FRA2", "FRA3", "FRA4", "FRA5", "FRA6", "ISO3095"], "description": "PSD the profile follows: US FRA track class 1 (worst) .. 6, or the ISO 3095:2013 rail roughness limit"},
              "seed": {"type": "integer", "minimum": 0, "description": "random seed"},
              "wavelength_min": {"type": "number", "exclusiveMinimum": 0, "description": "shortest wavelength [m]"},
              "wavelength_max": {"type": "number", "exclusiveMinimum": 0, "description": "longest wavelength [m]"}
            }
          }
        }
      ]
    }
  }
})json";

}  // namespace

std::string_view scenario_schema_text() {
  return kSchema;
}

}  // namespace rumble::scenario
