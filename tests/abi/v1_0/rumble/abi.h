/* SPDX-License-Identifier: MIT
 * rumble/abi.h: the C waist between the Rumble engine and its plugins.
 *
 * Only C types cross this boundary: fixed-width integers, double, {pointer, length} views,
 * NUL-terminated UTF-8 strings and opaque handles. Configuration crosses as JSON text.
 * No exception, STL type, Eigen type or JSON object ever crosses.
 *
 * Compiles as C11 and as C++17. Plugin authors normally use the C++ layer (rumble/plugin.hpp)
 * and never touch this file directly.
 *
 * SIGN CONVENTION AT THE TRACK/SOIL CUT (vertical, SI units):
 *   z is positive DOWNWARD, into the soil. A footprint force F_i > 0 [N] pushes the soil down
 *   (compression under the weight of the train); the footprint displacement u_i > 0 [m] and
 *   velocity v_i > 0 [m/s] are downward. Under a static train every F_i >= 0 and u_i >= 0.
 *   The same convention holds for vehicle coordinates (gravity is a positive generalized force
 *   on a vertical DOF), rail deflection and rail unevenness (a dip is positive).
 *
 * VERSIONING: the host accepts a plugin whose ABI major equals RUMBLE_ABI_MAJOR and whose ABI
 * minor is <= RUMBLE_ABI_MINOR. Function tables and descriptors begin with their size in bytes
 * and grow only by appending (a minor bump); any other change is a major bump. The layout of
 * every struct is checked against a committed table (tests/abi/abi_layout_test.cpp).
 *
 * Revisions:
 *   1.0 (2026-11-23) first version: vehicle, soil and coupler kinds.
 */
#ifndef RUMBLE_ABI_H
#define RUMBLE_ABI_H

#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

#define RUMBLE_ABI_MAJOR 1
#define RUMBLE_ABI_MINOR 0

/** Name of the one symbol every plugin library exports (see rumble_plugin_entry_fn). */
#define RUMBLE_PLUGIN_ENTRY_SYMBOL "rumble_plugin_entry"

/** Status returned by every call across the waist. */
typedef enum rumble_status {
  RUMBLE_OK = 0,      /**< done */
  RUMBLE_WARNING = 1, /**< done, result valid, last_message says what is doubtful */
  RUMBLE_DISCARD = 2, /**< step refused, instance state unchanged (caller may retry) */
  RUMBLE_ERROR = 3,   /**< this instance is unusable; the run stops cleanly */
  RUMBLE_FATAL = 4    /**< process state suspect; stop at once */
} rumble_status;

typedef enum rumble_kind {
  RUMBLE_KIND_VEHICLE = 1,
  RUMBLE_KIND_SOIL = 2,
  RUMBLE_KIND_COUPLER = 3
} rumble_kind;

typedef enum rumble_log_level {
  RUMBLE_LOG_DEBUG = 1,
  RUMBLE_LOG_INFO = 2,
  RUMBLE_LOG_WARN = 3,
  RUMBLE_LOG_ERROR = 4
} rumble_log_level;

/** Services the host offers to every instance. Valid for the life of the instance. */
typedef struct rumble_host {
  uint32_t struct_size; /**< sizeof(rumble_host) as the host built it */
  uint32_t abi_minor;   /**< the host's RUMBLE_ABI_MINOR */
  void* host_data;      /**< opaque, passed back to every callback */
  /** Log one line on behalf of an instance; thread-safe. */
  void (*log)(void* host_data, int32_t level, const char* message);
  /** Directory of the scenario file, for resolving relative paths (UTF-8, no trailing slash). */
  const char* scenario_dir;
} rumble_host;

/** Opaque instance handle created by a factory. */
typedef struct rumble_instance rumble_instance;

/** Functions every kind's table begins with. */
typedef struct rumble_common_api {
  void (*destroy)(rumble_instance* self);
  /** Text of the last WARNING/DISCARD/ERROR/FATAL; valid until the next call on self. */
  const char* (*last_message)(const rumble_instance* self);
  /** Number of doubles needed to save the full state (0 when save/restore is not supported). */
  rumble_status (*state_size)(rumble_instance* self, uint64_t* n_doubles);
  rumble_status (*save_state)(rumble_instance* self, double* buffer, uint64_t n_doubles);
  rumble_status (*restore_state)(rumble_instance* self, const double* buffer, uint64_t n_doubles);
} rumble_common_api;

/* ------------------------------------------------------------------ vehicles ------------- */

/** One wheel of a vehicle, in the vehicle's own frame. */
typedef struct rumble_wheel {
  double offset; /**< [m] position along the track relative to the vehicle reference, forward + */
  double radius; /**< [m] rolling radius (used for the Hertz constant when not given) */
} rumble_wheel;

/**
 * Model-exchange vehicle: the plugin states its equations, the engine integrates.
 *   M(q) q'' = f(t, q, q') - sum_w J_w(q)^T F_w,   F_w >= 0 the contact force of wheel w [N]
 * where z_w(q) is the vertical (downward +) position of wheel w's contact point relative to its
 * nominal height [m] and J_w = dz_w/dq. Matrices are dense, column-major, n_dof x n_dof.
 */
typedef struct rumble_vehicle_api {
  uint32_t struct_size;
  rumble_common_api common;
  rumble_status (*dof_count)(rumble_instance* self, uint64_t* n_dof);
  rumble_status (*wheels)(rumble_instance* self, rumble_wheel* out, uint64_t capacity,
                          uint64_t* n_wheels);
  rumble_status (*mass_matrix)(rumble_instance* self, const double* q, double* mass);
  /** Generalized forces except contact (gravity, suspension) [N or N m]. */
  rumble_status (*forces)(rumble_instance* self, double t, const double* q, const double* qd,
                          double* f);
  /** z_w(q) [m] for every wheel, and J (n_wheels x n_dof, column-major). */
  rumble_status (*wheel_kinematics)(rumble_instance* self, const double* q, double* z,
                                    double* jacobian);
  /** Optional (may be null): K = -df/dq and C = -df/dq' (column-major); host differentiates
   *  numerically when absent. */
  rumble_status (*tangent)(rumble_instance* self, double t, const double* q, const double* qd,
                           double* stiffness, double* damping);
  /** Optional (may be null): output channel names, ';'-separated; values via outputs(). */
  const char* (*output_names)(rumble_instance* self);
  rumble_status (*outputs)(rumble_instance* self, double t, const double* q, const double* qd,
                           double* values);
} rumble_vehicle_api;

/* ------------------------------------------------------------------ soils ---------------- */

/** One footprint of the track on the soil (a sleeper's contact patch). */
typedef struct rumble_footprint {
  double x;      /**< [m] centre, along the track */
  double y;      /**< [m] centre, across the track (0 on the track axis) */
  double length; /**< [m] extent ACROSS the track (sleeper length) */
  double width;  /**< [m] extent ALONG the track (sleeper width) */
} rumble_footprint;

/**
 * A waveform over one macro step [t, t + H]: value_i(t + tau H) = sum_k coeff[k n + i] tau^k,
 * tau in [0, 1], k = 0..order. order 0 is a held constant.
 */
typedef struct rumble_waveform {
  uint32_t order;      /**< polynomial order, 0..2 */
  uint64_t n;          /**< number of channels */
  const double* coeff; /**< (order + 1) * n values */
} rumble_waveform;

typedef struct rumble_receiver {
  double x, y; /**< [m] surface point */
} rumble_receiver;

typedef struct rumble_soil_api {
  uint32_t struct_size;
  rumble_common_api common;
  /** Accept the footprint layout announced by the track, or refuse it with ERROR. */
  rumble_status (*accept_layout)(rumble_instance* self, const rumble_footprint* footprints,
                                 uint64_t n);
  /** Static equilibrium under static_force [N]; writes the static displacements u [m]. */
  rumble_status (*initialize)(rumble_instance* self, double t0, const double* static_force,
                              double* static_u, uint64_t n);
  /** Advance over [t, t + H] with the footprint forces given as a waveform. */
  rumble_status (*advance)(rumble_instance* self, double t, double H, const rumble_waveform* force);
  /** Footprint displacement [m] and velocity [m/s] at the current time. */
  rumble_status (*motion)(rumble_instance* self, double* u, double* v, uint64_t n);
  /** Optional: receptance matrix H(f) [m/N] at the footprints, n x n column-major, real and
   *  imaginary parts, e^{+i omega t} convention (u = H F). */
  rumble_status (*frequency_response)(rumble_instance* self, double f_hz, double* re, double* im,
                                      uint64_t n);
  /** Optional: surface receivers; velocity() writes the vertical velocity [m/s] of each. */
  rumble_status (*set_receivers)(rumble_instance* self, const rumble_receiver* r, uint64_t n);
  rumble_status (*receiver_velocity)(rumble_instance* self, double* v, uint64_t n);
} rumble_soil_api;

/* ------------------------------------------------------------------ couplers ------------- */

/** Participant indices in rumble_cosim_host calls. */
#define RUMBLE_PARTICIPANT_TRACK 0u
#define RUMBLE_PARTICIPANT_SOIL 1u

/**
 * The host's participant interface given to a coupler. A coupler never calls a vehicle or soil
 * plugin itself. Interface data, per footprint i of n:
 *   track output: F_i [N] (n values)      -> soil input (waveform of n channels)
 *   soil output:  u_i [m] then v_i [m/s]  -> track input (waveform of 2n channels)
 * Calls on different participants may run concurrently; calls on one participant may not.
 */
typedef struct rumble_cosim_host {
  uint32_t struct_size;
  void* ctx;
  uint64_t (*interface_size)(void* ctx);
  uint64_t (*output_size)(void* ctx, uint32_t participant);
  /** Current outputs of a participant (at its current time). */
  rumble_status (*get_output)(void* ctx, uint32_t participant, double* y, uint64_t n);
  /** Input waveform a participant uses in its next advance. */
  rumble_status (*set_input)(void* ctx, uint32_t participant, const rumble_waveform* u);
  rumble_status (*advance)(void* ctx, uint32_t participant, double t, double H);
  /** Checkpoint (slot 0..3) of a participant's full state, held by the host. */
  rumble_status (*save)(void* ctx, uint32_t participant, uint32_t slot);
  rumble_status (*restore)(void* ctx, uint32_t participant, uint32_t slot);
  /** Tell the host macro step [t, t + H] is final: it records outputs. Returns ERROR when the
   *  run must stop (Ctrl-C, diverging results); the coupler then returns that status. */
  rumble_status (*step_done)(void* ctx, double t, double H, double interface_residual);
  void (*log)(void* ctx, int32_t level, const char* message);
} rumble_cosim_host;

typedef struct rumble_coupler_api {
  uint32_t struct_size;
  rumble_common_api common;
  rumble_status (*run)(rumble_instance* self, const rumble_cosim_host* host, double t0,
                       double t_end, double H);
} rumble_coupler_api;

/* ------------------------------------------------------------------ descriptor ----------- */

typedef rumble_status (*rumble_create_fn)(const char* params_json, const rumble_host* host,
                                          rumble_instance** out, const char** error_message);

/** One component type a library provides. */
typedef struct rumble_factory {
  uint32_t struct_size;
  int32_t kind;              /**< rumble_kind */
  const char* type_name;     /**< e.g. "winkler"; unique in a process */
  const char* summary;       /**< one line */
  const char* params_schema; /**< JSON Schema (draft 7) of the component's params object */
  /** Creates an instance. On failure *error_message points to static or thread-local text. */
  rumble_create_fn create;
  const void* api; /**< rumble_vehicle_api / rumble_soil_api / rumble_coupler_api by kind */
} rumble_factory;

typedef struct rumble_plugin_descriptor {
  uint32_t struct_size;
  uint32_t abi_major;
  uint32_t abi_minor;
  const char* plugin_name;       /**< e.g. "winkler" */
  const char* plugin_version;    /**< semver */
  const char* build_fingerprint; /**< compiler and build type, printed, never enforced */
  uint64_t n_factories;          /**< at least 1 */
  /** n_factories entries, each factories[0].struct_size bytes (the plugin's sizeof) apart. */
  const rumble_factory* factories;
} rumble_plugin_descriptor;

/** The exported entry point: returns a descriptor with static storage duration. */
typedef const rumble_plugin_descriptor* (*rumble_plugin_entry_fn)(void);

#ifdef __cplusplus
} /* extern "C" */
#endif

#endif /* RUMBLE_ABI_H */
