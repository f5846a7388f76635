#include "scenario/scenario_schema.hpp"

#include <string>

#include "scenario/schema_check.hpp"

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
        "end": {"type": "number", "minimum": 1e-6, "maximum": 3600, "description": "simulated duration, starting at t = 0 [s]; [1e-6, 3600] s: from a few of the shortest macro steps to an hour (a train passes a point in seconds to a minute; the run's size is limited apart, docs/scenario.md, Run size)"},
        "macro_step": {"type": "number", "minimum": 1e-7, "maximum": 1, "description": "coupling step H, <= end [s]; [1e-7, 1] s: usually 1e-4 to 1e-3 s; 1e-7 s is 100 times below the track's micro-step (about 1e-5 s, from the wheel/rail contact), and a step beyond 1 s couples none of a train's vibration (1 to some 100 Hz)"}
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
          "speed": {"type": "number", "minimum": 0, "maximum": 200, "description": "constant forward speed [m/s]; [0, 200] m/s: from standing to beyond the rail speed record (574.8 km/h, 160 m/s)"},
          "start": {"type": "number", "minimum": -1e6, "maximum": 1e6, "description": "position of the vehicle reference at t = 0, along the track [m]; [-1e6, 1e6] m: 1000 km either way of sleeper 0 is beyond any track (at most 100000 sleepers 2 m apart, 200 km); on the rail, checked apart"},
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
            "count": {"type": "integer", "minimum": 3, "maximum": 100000, "description": "number of sleepers; [3, 100000]: a rail needs supports on both sides of a wheel; 100000 is 60 km at 0.6 m"},
            "spacing": {"type": "number", "minimum": 0.1, "maximum": 2, "description": "distance between sleepers; sleeper i is at x = i * spacing [m]; [0.1, 2] m: sleepers and slab-track supports lie 0.5 to 0.75 m apart, old timber track up to about 1 m"},
            "mass": {"type": "number", "minimum": 1, "maximum": 5000, "description": "mass per rail seat (half sleeper) [kg]; [1, 5000] kg: half a timber sleeper is about 40 kg, half a concrete one about 150 kg; 5 t covers a slab-track segment's share"},
            "footprint": {
              "type": "object",
              "description": "contact patch of a whole sleeper on the soil",
              "additionalProperties": false,
              "required": ["length", "width"],
              "properties": {
                "length": {"type": "number", "minimum": 0.1, "maximum": 10, "description": "footprint extent across the track (whole sleeper) [m]; [0.1, 10] m: sleepers are 2.3 to 2.8 m long, slab track about 3 m wide"},
                "width": {"type": "number", "minimum": 0.01, "maximum": 2, "description": "footprint extent along the track [m]; [0.01, 2] m: a sleeper's base is 0.2 to 0.3 m wide"}
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
            "E": {"type": "number", "minimum": 1e9, "maximum": 1e12, "description": "Young's modulus [Pa]; [1e9, 1e12] Pa: rail steel is 2.1e11 Pa; from timber or polymer beams (about 10 GPa) to beyond any metal"},
            "I": {"type": "number", "minimum": 1e-8, "maximum": 1e-2, "description": "second moment of area, vertical bending [m^4]; [1e-8, 1e-2] m^4: a UIC60 rail is 3.055e-5 m^4, light rails about 1e-6 m^4; 1e-2 m^4 is a rail with a girder or slab"},
            "mass_per_length": {"type": "number", "minimum": 1, "maximum": 5000, "description": "rail mass per length [kg/m]; [1, 5000] kg/m: a UIC60 rail is 60.3 kg/m, light rails 10 to 30 kg/m; 5 t/m is a rail with a girder or slab"},
            "elements_per_bay": {"type": "integer", "minimum": 1, "maximum": 32, "default": 4, "description": "beam elements between two sleepers; [1, 32]: cubic beam elements, 4 per bay resolve the rail's bending between sleepers; 32 per bay are finer than anything a wheel excites"},
            "overhang_bays": {"type": "integer", "minimum": 0, "maximum": 20, "default": 1, "description": "rail bays beyond the first and last sleeper; [0, 20]: the rail ends free (docs/decisions/0003-track-solver.md); its deflection under a wheel dies out within a few bays"}
          }
        },
        "railpad": {
          "type": "object",
          "description": "spring-dashpot from rail to sleeper, per rail seat",
          "additionalProperties": false,
          "required": ["k", "c"],
          "properties": {
            "k": {"type": "number", "minimum": 1e5, "maximum": 1e11, "description": "stiffness per rail seat [N/m]; [1e5, 1e11] N/m: railpads are 2e7 (soft) to 1e9 N/m (stiff)"},
            "c": {"type": "number", "minimum": 0, "maximum": 1e7, "description": "damping per rail seat [N s/m]; [0, 1e7] N s/m: railpads are 1e4 to 1e5 N s/m"}
          }
        },
        "ballast": {
          "type": "object",
          "description": "spring-dashpot from sleeper to footprint, per half sleeper",
          "additionalProperties": false,
          "required": ["k", "c"],
          "properties": {
            "k": {"type": "number", "minimum": 1e5, "maximum": 1e11, "description": "stiffness per half sleeper [N/m]; [1e5, 1e11] N/m: ballast under a half sleeper is 2e7 to 2e8 N/m"},
            "c": {"type": "number", "minimum": 0, "maximum": 1e7, "description": "damping per half sleeper [N s/m]; [0, 1e7] N s/m: ballast is 3e4 to 1e5 N s/m"}
          }
        },
        "contact": {
          "type": "object",
          "description": "Hertzian wheel/rail contact",
          "additionalProperties": false,
          "default": {},
          "properties": {
            "hertz_constant": {"type": "number", "minimum": 1e9, "maximum": 1e13, "description": "Hertz constant C_H; computed from the wheel and rail radii when absent [N/m^1.5]; [1e9, 1e13] N/m^1.5: steel wheels on steel rails give about 1e11"},
            "rail_radius": {"type": "number", "minimum": 0.01, "maximum": 100, "default": 0.3, "description": "rail crown transverse radius [m]; [0.01, 100] m: new crowns are 0.08 to 0.3 m, worn ones flatter"},
            "E": {"type": "number", "minimum": 1e10, "maximum": 1e12, "default": 2.1e11, "description": "Young's modulus of wheel and rail steel [Pa]; [1e10, 1e12] Pa: steel is 2.1e11 Pa"},
            "nu": {"type": "number", "minimum": 0, "exclusiveMaximum": 0.5, "default": 0.3, "description": "Poisson's ratio of wheel and rail steel [-]; [0, 0.5): steel is 0.3; 0.5 is incompressible"}
          }
        },
        "unevenness": {"$ref": "#/definitions/unevenness"},
        "integrator": {
          "type": "object",
          "description": "Newmark time integration of track and vehicles",
          "additionalProperties": false,
          "default": {},
          "properties": {
            "micro_step": {"type": "number", "minimum": 1e-9, "maximum": 1, "description": "track/vehicle step h, <= macro_step; from the contact stiffness when absent [s]; [1e-9, 1] s: the contact needs about 1e-5 s (a twentieth of its period)"},
            "gamma": {"type": "number", "minimum": 0.5, "maximum": 1, "default": 0.5, "description": "Newmark gamma; beta = (gamma + 1/2)^2 / 4 [-]; [0.5, 1]: 0.5 is undamped (average acceleration), above it the scheme damps high frequencies, unconditionally stable throughout"}
          }
        },
        "damping": {
          "type": "object",
          "description": "Rayleigh damping of the rail",
          "additionalProperties": false,
          "default": {},
          "properties": {
            "rayleigh_alpha": {"type": "number", "minimum": 0, "maximum": 1e4, "default": 0, "description": "mass-proportional rail damping [1/s]; [0, 1e4] 1/s: alpha = 2 zeta omega, 10 % of critical at 1 kHz is 1.3e3 1/s"},
            "rayleigh_beta": {"type": "number", "minimum": 0, "maximum": 0.1, "default": 0, "description": "stiffness-proportional rail damping [s]; [0, 0.1] s: beta = 2 zeta / omega, 10 % of critical at 10 Hz is 3e-3 s"}
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
            "displacement_factor": {"type": "number", "exclusiveMinimum": 2, "maximum": 1e6, "default": 20, "description": "bound on |footprint displacement| as a multiple of the largest static one [-]; (2, 1e6]: a passing train amplifies the static settlement a few times at most; not applied to a soil with no static load (below 1 um: a coupler that prescribes the forces)"}
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
              {"type": "number", "exclusiveMinimum": 0, "maximum": 1000, "description": "distance from the track axis [m]; (0, 1000] m: ground vibration from trains is assessed within some 100 m of the track"},
              {
                "type": "object",
                "additionalProperties": false,
                "required": ["name", "y"],
                "properties": {
                  "name": {"type": "string", "minLength": 1, "maxLength": 64, "pattern": "^[A-Za-z0-9][A-Za-z0-9 _.=+()-]*$", "description": "column name in receivers.csv, unique among the receivers: a letter or digit, then letters, digits, spaces and _ . = + ( ) - (no comma, quote or bracket, which would break the CSV header)"},
                  "y": {"type": "number", "minimum": -1000, "maximum": 1000, "description": "distance across the track from its axis [m]; [-1000, 1000] m: ground vibration from trains is assessed within some 100 m of the track"},
                  "x": {"type": "number", "minimum": -1e6, "maximum": 1e6, "description": "position along the track [m]; default the middle of the sleepers; [-1e6, 1e6] m: 1000 km either way of sleeper 0 is beyond any track (200 km at most)"},
                  "depth": {"type": "number", "minimum": 0, "maximum": 1000, "default": 0, "description": "depth below the surface [m]; [0, 1000] m: train vibration reaches some 10 m down (a Rayleigh wavelength)"}
                }
              }
            ]
          },
          "default": [],
          "description": "receivers whose motion is recorded (soils that offer them)"
        },
        "receiver_interval": {"type": "number", "minimum": 0, "maximum": 1, "default": 0, "description": "sampling interval of receivers [s]; 0: every step of the soil; [0, 1] s: a train's vibration (1 to some 100 Hz) needs a few ms; slower than 1 s records none of it"},
        "fields": {
          "type": "object",
          "additionalProperties": false,
          "required": ["interval"],
          "description": "soil field snapshots (VTU, soils that offer them) and their ParaView index soil.pvd",
          "properties": {
            "interval": {"type": "number", "minimum": 1e-6, "maximum": 3600, "description": "time between snapshots, the first at t = 0 [s]; [1e-6, 3600] s: at most time.end's largest (an hour), at least 1e-6 s (finer than any soil step); the number of snapshots is limited apart (docs/scenario.md, Run size)"}
          }
        },
        "post": {
          "type": "object",
          "additionalProperties": false,
          "default": {},
          "description": "the vibration indicators written to post/ after a run with receivers (docs/post-processing.md); rumble post RESULTS_DIR recomputes them with these, its options overriding",
          "properties": {
            "cwt_distances": {"type": "array", "items": {"type": "number", "minimum": 0, "maximum": 1000, "description": "distance from the track [m]; [0, 1000] m: as the receivers' (ground vibration from trains is assessed within some 100 m of the track)"}, "default": [2.5, 5.0], "description": "distances from the track [m] whose nearest receivers get a wavelet transform of v_z (the seed paper's Figures 6 and 7: 2.5 and 5 m)"},
            "f_max": {"type": "number", "minimum": 1, "maximum": 2000, "default": 200, "description": "highest frequency of the wavelet transforms [Hz]; give what the soil resolves (a FEM soil: rumble mesh reports it per distance), or the scalograms show what the mesh cannot carry; [1, 2000] Hz: from the lowest frequency of train vibration (about 1 Hz) to the FEM soil's highest mesh.f_max"},
            "reference": {"enum": ["iso", "vdb"], "default": "iso", "description": "velocity reference of the one-third-octave levels: iso (ISO 1683, 1e-9 m/s) or vdb (VdB, 2.54e-8 m/s = 1 micro-inch/s)"}
          }
        },
        "every": {"type": "integer", "minimum": 1, "maximum": 10000000, "default": 1, "description": "record every n-th macro step; [1, 1e7]: a run has at most 1e7 macro steps (docs/scenario.md, Run size)"},
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
              "position": {"type": "number", "minimum": -1e6, "maximum": 1e6, "description": "centre of the dip along the track [m]; [-1e6, 1e6] m: 1000 km either way of sleeper 0 is beyond any track (200 km at most)"},
              "length": {"type": "number", "minimum": 1e-3, "maximum": 100, "description": "length of the cosine dip [m]; [1e-3, 100] m: rail joints and welds are 0.1 to 1 m, hanging sleepers and transitions some 10 m"},
              "depth": {"type": "number", "minimum": 1e-7, "maximum": 0.1, "description": "depth of the dip (rail joint) [m]; [1e-7, 0.1] m: rail roughness is microns, joint dips 1 to 5 mm; 0.1 m is a step no wheel rides"}
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
              "position": {"type": "number", "minimum": -1e6, "maximum": 1e6, "description": "centre of the bump along the track [m]; [-1e6, 1e6] m: 1000 km either way of sleeper 0 is beyond any track (200 km at most)"},
              "length": {"type": "number", "minimum": 1e-3, "maximum": 100, "description": "length of the cosine bump [m]; [1e-3, 100] m: welds and squats are 0.01 to 1 m, track geometry faults some 10 m"},
              "height": {"type": "number", "minimum": 1e-7, "maximum": 0.1, "description": "height of the bump [m]; [1e-7, 0.1] m: rail roughness is microns, weld bumps about 1 mm; 0.1 m is a step no wheel rides"}
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
              "length": {"type": "number", "minimum": 1e-3, "maximum": 1, "description": "length of the rounded flat [m]; [1e-3, 1] m: wheel flats are 20 to 100 mm long (some 60 mm is the usual limit for taking a wheel out of service)"},
              "depth": {"type": "number", "minimum": 1e-7, "maximum": 0.1, "description": "depth of the flat [m]; default L^2/(16 R), a worn (rounded) flat of length L; [1e-7, 0.1] m: a 60 mm flat on a 0.46 m wheel is 0.5 to 2 mm deep"},
              "wheel": {"type": "integer", "minimum": 0, "maximum": 10000, "default": 0, "description": "index of the flat wheel among all wheels; [0, 10000]: a long freight train has some hundreds of wheels on a rail"},
              "first_impact": {"type": "number", "minimum": 0, "maximum": 1e6, "description": "rolled distance at which the flat's centre first meets the rail [m]; default pi R (half a turn); [0, 1e6] m: 1000 km is beyond any track (200 km at most)"}
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
              "seed": {"type": "integer", "minimum": 0, "maximum": 9007199254740991, "description": "random seed; [0, 9007199254740991]: up to 2^53 - 1, the integers a JSON number holds exactly (many JSON readers round larger ones)"},
              "wavelength_min": {"type": "number", "minimum": 1e-3, "maximum": 1000, "description": "shortest wavelength [m]; [1e-3, 1000] m: from rail roughness (ISO 3095 starts at 2.82 mm) to track geometry (1 to some 100 m); each class's own band is checked apart"},
              "wavelength_max": {"type": "number", "minimum": 1e-3, "maximum": 1000, "description": "longest wavelength [m], > wavelength_min; [1e-3, 1000] m: from rail roughness (ISO 3095 starts at 2.82 mm) to track geometry (1 to some 100 m); each class's own band is checked apart"}
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

const SchemaChecker& engine_checker() {
  static const SchemaChecker checker{std::string(kSchema)};
  return checker;
}

nlohmann::json track_with_defaults(nlohmann::json track) {
  engine_checker().fill_defaults(track, "/properties/track");
  return track;
}

nlohmann::json unevenness_with_defaults(nlohmann::json unevenness) {
  engine_checker().fill_defaults(unevenness, "/definitions/unevenness");
  return unevenness;
}

}  // namespace rumble::scenario
