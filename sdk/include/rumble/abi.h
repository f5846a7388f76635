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
 * GROWTH RULES (what "append-only" means in practice):
 *   - Every table, descriptor and record that may grow begins with uint32_t struct_size, the
 *     sizeof its producer compiled. A reader touches a field only when the producer's struct_size
 *     covers it: RUMBLE_HAS_FIELD(ptr, type, field). Hosts check a plugin's tables against the
 *     size of the ABI minor the plugin declares, never against the host's own sizeof.
 *   - rumble_common_api is embedded by value in every kind's table (1.0) and is FROZEN: it never
 *     grows. Functions common to every kind added from 1.1 on live in rumble_lifecycle_api,
 *     reached through a pointer appended to each kind's table; that table grows by appending.
 *   - Optional function pointers may be null; the capabilities a factory declares
 *     (rumble_capabilities) say which optional features a component offers.
 *
 * Revisions:
 *   1.0 (2026-11-23) first version: vehicle, soil and coupler kinds.
 *   1.1 (2026-12-01) appended, no field moved (docs/decisions/0005-abi-1-1.md): declared
 *       capabilities on factories; rumble_lifecycle_api (finalize, plugin-held checkpoints);
 *       host services (results directory, thread budget, stop/progress); named participants and
 *       channel groups, step reports with per-group residuals, DISCARD passed to couplers;
 *       probes (3-component velocity and displacement at depth, sampled within a step), field
 *       output, soil wave speeds and linear matrices (CSC); array lengths on every call.
 *   1.2 (2026-12-02) one capability bit, no struct changed (docs/decisions/0008-monolithic.md):
 *       RUMBLE_CAP_MONOLITHIC, a coupler asking the host to integrate the soil inside the
 *       vehicle/track. A 1.2 coupler is refused by a 1.1 host, which would ignore the bit.
 *   1.3 (2026-12-04) appended to the soil's table (docs/decisions/0010-abi-1-3.md):
 *       probe_resolution, the band a soil resolves at each probe, so that every number drawn
 *       from a receiver can say where it stops being valid.
 *   1.4 (2026-12-05) appended to rumble_host (docs/decisions/0012-distributed-soil.md):
 *       communicator, the MPI communicator an instance works on; RUMBLE_CAP_DISTRIBUTED, a soil
 *       whose calls are collective over it, created on every rank of an MPI launch. Appended to
 *       rumble_cosim_host (docs/decisions/0013-coupler-contract.md): footprint_layout, the
 *       footprints' positions and sizes, for a coupler that applies loads of its own
 *       (docs/couplers.md, "The coupler contract").
 *   1.5 (2026-12-05) appended to the soil's table (docs/decisions/0014-abi-1-5.md): size, the
 *       soil's degrees of freedom and its estimate of a run's peak memory, for the host's account
 *       of memory per DOF; statics_done, the end of the host's static iteration, after which a
 *       soil frees what only its statics needed.
 *   1.6 (2026-12-06) appended to rumble_host (docs/decisions/0016-planned-ranks.md):
 *       planned_ranks, the N of a launch on N MPI ranks that a command plans for without
 *       running on them (`rumble mesh --ranks N`), so that a soil reports what each rank would
 *       hold.
 *   1.7 (2026-12-06) one capability bit and one function appended to rumble_cosim_host
 *       (docs/decisions/0017-never-refuses.md): RUMBLE_CAP_NEVER_REFUSES, a vehicle or soil whose
 *       advance never returns DISCARD; may_refuse, which tells a coupler so, so that it
 *       checkpoints a participant only where the other's refusal could need it put back.
 */
#ifndef RUMBLE_ABI_H
#define RUMBLE_ABI_H

#include <stddef.h>
#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

#define RUMBLE_ABI_MAJOR 1
#define RUMBLE_ABI_MINOR 7

/** Name of the one symbol every plugin library exports (see rumble_plugin_entry_fn). */
#define RUMBLE_PLUGIN_ENTRY_SYMBOL "rumble_plugin_entry"

/** Nonzero when the struct at PTR (which begins with uint32_t struct_size, as its producer
 *  compiled it) holds FIELD of TYPE. Use before reading any field added after 1.0. */
#ifdef __cplusplus
#define RUMBLE_HAS_FIELD(PTR, TYPE, FIELD) \
  ((PTR) != nullptr && (PTR)->struct_size >= offsetof(TYPE, FIELD) + sizeof(TYPE::FIELD))
#else
#define RUMBLE_HAS_FIELD(PTR, TYPE, FIELD) \
  ((PTR) != NULL &&                        \
   (PTR)->struct_size >= offsetof(TYPE, FIELD) + sizeof(((const TYPE*)NULL)->FIELD))
#endif

/** Number of checkpoint slots (0 .. RUMBLE_CHECKPOINT_SLOTS - 1) per participant. */
#define RUMBLE_CHECKPOINT_SLOTS 4u

/** Status returned by every call across the waist. */
typedef enum rumble_status {
  RUMBLE_OK = 0,      /**< done */
  RUMBLE_WARNING = 1, /**< done, result valid, last_message says what is doubtful */
  /** Only from a step (advance): the step was refused and the instance state is exactly as
   *  before the call; the caller may retry with a smaller step. (A 1.0 plugin also returned it
   *  from tangent, frequency_response and set_receivers for "not offered"; from 1.1 on a host
   *  reads the declared capabilities instead and never calls what is not offered.) */
  RUMBLE_DISCARD = 2,
  RUMBLE_ERROR = 3, /**< this instance is unusable; the run stops cleanly */
  RUMBLE_FATAL = 4  /**< process state suspect; stop at once */
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
  /* ---- 1.1 (check with RUMBLE_HAS_FIELD before use) */
  /** The run's results directory (UTF-8, exists, no trailing slash); "" when the instance is
   *  not part of a run (validate, a study's checks, soil-frf, calibrate, stability); `rumble
   *  mesh` gives the directory of its mesh.vtu. Files a plugin writes go here, as new files
   *  inside it, and nowhere else: none while it is "" (docs/plugin-guide.md). */
  const char* results_dir;
  /** Threads this instance may use inside one call (>= 1). The host divides the machine among
   *  participants that run at once (a Jacobi step runs two), and may change it between calls
   *  (the statics get every core; the time stepping may keep one for the track): read it at
   *  each call. */
  uint32_t threads;
  uint32_t reserved0; /**< 0 */
  /** Call from inside a long call (every 0.1 s of work or so), from the thread the host called
   *  on: reports progress of that call (fraction in [0, 1], or < 0 when unknown) and returns
   *  nonzero when the host asks the instance to stop (Ctrl-C). The plugin then returns
   *  RUMBLE_ERROR promptly; its state may be left mid-step (the run is over). */
  int32_t (*progress)(void* host_data, double fraction);
  /* ---- 1.4 (docs/decisions/0012-distributed-soil.md) */
  /** The MPI communicator this instance works on, as MPI's Fortran handle (MPI_Comm_c2f; the
   *  plugin turns it back with MPI_Comm_f2c, from the same MPI library as the host's), with this
   *  process's rank in it and its size. A soil declaring RUMBLE_CAP_DISTRIBUTED gets a duplicate
   *  of MPI_COMM_WORLD made for it: under an MPI launcher the host creates it on every rank and
   *  makes each of its calls on every rank with the same inputs. Any other instance gets a
   *  duplicate of MPI_COMM_SELF (size 1). The first call starts MPI when it is not running (a
   *  singleton); the host finishes MPI at exit, after destroying every instance: a plugin never
   *  initialises or finalises MPI itself. Returns ERROR when MPI cannot start (the host logs
   *  why). Null: the host has no MPI; run on one process without it, or refuse. */
  rumble_status (*communicator)(void* host_data, int64_t* fortran_handle, int32_t* rank,
                                int32_t* size);
  /* ---- 1.6 (docs/decisions/0016-planned-ranks.md) */
  /** The MPI ranks a command plans for without running on them (`rumble mesh --ranks N`: N):
   *  the instance runs on its communicator as ever (one process), and a soil that can be split
   *  reports what each of the N ranks would hold (its log). 0: no plan (a run: its ranks are its
   *  communicator's). */
  int32_t planned_ranks;
  uint32_t reserved1; /**< 0 */
} rumble_host;

/** Opaque instance handle created by a factory. */
typedef struct rumble_instance rumble_instance;

/** Functions every kind's table begins with. FROZEN at 1.0 (embedded by value); later common
 *  functions go to rumble_lifecycle_api. */
typedef struct rumble_common_api {
  void (*destroy)(rumble_instance* self);
  /** Text of the last WARNING/DISCARD/ERROR/FATAL; valid until the next call on self. */
  const char* (*last_message)(const rumble_instance* self);
  /** Number of doubles needed to save the full state (0 when save/restore is not supported). */
  rumble_status (*state_size)(rumble_instance* self, uint64_t* n_doubles);
  rumble_status (*save_state)(rumble_instance* self, double* buffer, uint64_t n_doubles);
  rumble_status (*restore_state)(rumble_instance* self, const double* buffer, uint64_t n_doubles);
} rumble_common_api;

/**
 * 1.1: functions common to every kind added after 1.0, reached through each kind table's
 * `lifecycle` pointer (null: none offered). Grows by appending; every pointer may be null.
 */
typedef struct rumble_lifecycle_api {
  uint32_t struct_size;
  /** Called once after the last step of a run that completed or stopped (not after a crash),
   *  before destroy: flush and close files, report. */
  rumble_status (*finalize)(rumble_instance* self);
  /** Plugin-held checkpoints (capability RUMBLE_CAP_OWN_CHECKPOINTS): the plugin keeps the
   *  state of slot 0 .. RUMBLE_CHECKPOINT_SLOTS - 1 itself, so a large state is never copied
   *  across the boundary. restore leaves the slot intact; free releases its memory. */
  rumble_status (*checkpoint_save)(rumble_instance* self, uint32_t slot);
  rumble_status (*checkpoint_restore)(rumble_instance* self, uint32_t slot);
  rumble_status (*checkpoint_free)(rumble_instance* self, uint32_t slot);
} rumble_lifecycle_api;

/* ------------------------------------------------------------------ capabilities --------- */

/** Capability bits (rumble_capabilities.offers and .needs). */
#define RUMBLE_CAP_SAVE_RESTORE (UINT64_C(1) << 0)       /**< full state save/restore */
#define RUMBLE_CAP_OWN_CHECKPOINTS (UINT64_C(1) << 1)    /**< lifecycle checkpoint_* */
#define RUMBLE_CAP_FREQUENCY_RESPONSE (UINT64_C(1) << 2) /**< soil: receptance H(f) */
#define RUMBLE_CAP_RECEIVERS (UINT64_C(1) << 3)          /**< soil: probes (1.1) */
#define RUMBLE_CAP_FIELD_OUTPUT (UINT64_C(1) << 4)       /**< soil: write_fields (VTU) */
#define RUMBLE_CAP_TANGENT (UINT64_C(1) << 5)            /**< vehicle: analytic tangent */
#define RUMBLE_CAP_LINEAR_MATRICES (UINT64_C(1) << 6)    /**< soil: linear_matrix (CSC) */
#define RUMBLE_CAP_THREADS (UINT64_C(1) << 7)            /**< uses rumble_host.threads > 1 */
#define RUMBLE_CAP_ONCE_PER_PROCESS (UINT64_C(1) << 8)   /**< at most one live instance */
#define RUMBLE_CAP_WAVE_SPEEDS (UINT64_C(1) << 9)        /**< soil: wave_speeds */
#define RUMBLE_CAP_SURFACE_RECEIVERS (UINT64_C(1) << 10) /**< soil: 1.0 set_receivers pair */
/** 1.2, coupler: the host integrates the scenario's soil, from its linear matrices, inside the
 *  vehicle/track as one system (a monolithic reference). The coupler then advances the track
 *  only (the soil's outputs follow it; advancing the soil is an error) and must also need
 *  RUMBLE_CAP_LINEAR_MATRICES in soil_needs. */
#define RUMBLE_CAP_MONOLITHIC (UINT64_C(1) << 11)
/** 1.4, soil: every call of this soil is collective over rumble_host.communicator's
 *  communicator (MPI_COMM_WORLD's duplicate): under an MPI launcher the host creates it on every
 *  rank and mirrors each call from rank 0 with the same inputs; outputs are read on rank 0
 *  (docs/decisions/0012-distributed-soil.md). Without a launcher it runs as one rank. On N > 1
 *  ranks it need not give linear_matrix (each rank holds its part): the host refuses what needs
 *  it, a monolithic coupler or `rumble stability`, at validation
 *  (docs/decisions/0015-memory-per-rank.md). */
#define RUMBLE_CAP_DISTRIBUTED (UINT64_C(1) << 12)
/** 1.7, vehicle or soil: advance never returns RUMBLE_DISCARD (the instance never refuses a
 *  step; the host stops a run whose instance refuses anyway, naming this promise). A coupler
 *  asks rumble_cosim_host.may_refuse and need not checkpoint the other participant at each step
 *  for a refusal that cannot come (docs/decisions/0017-never-refuses.md). */
#define RUMBLE_CAP_NEVER_REFUSES (UINT64_C(1) << 13)

/**
 * 1.1: what a component type offers and, for a coupler, what it needs, declared on its factory
 * so that `rumble validate` can match them before any instance exists. A 1.0 factory has none:
 * the host derives its offers from which optional functions are non-null.
 */
typedef struct rumble_capabilities {
  uint32_t struct_size;
  uint32_t reserved0; /**< 0 */
  uint64_t offers;    /**< RUMBLE_CAP_* bits this component offers */
  /** Coupler: RUMBLE_CAP_* bits every soil participant must offer (e.g. SAVE_RESTORE for an
   *  iterating scheme, LINEAR_MATRICES for a monolithic one). 0 for other kinds. */
  uint64_t soil_needs;
  /** [s] largest macro step this component accepts (0: no limit). A step beyond it is refused
   *  at validate time; a plugin may still DISCARD a step it cannot take. */
  double max_macro_step;
  /** Coupler: JSON text of the extra participants it drives besides "track" and "soil", e.g.
   *  {"reduced_soil": {"kind": "soil", "required": true, "description": "..."}}, which a
   *  scenario gives under /coupling/participants/<name> as {type, params}. NULL or "{}": none.
   *  "track_statics": true on (at most) one soil: the track's static equilibrium is found on it
   *  instead of on the scenario's soil, which with the other soils starts from the static
   *  footprint forces found (two_step: the track rests on its reduced soil). */
  const char* participants_json;
} rumble_capabilities;

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
  /* ---- 1.1: the same calls with the length of every array (n_dof = dof_count, checked by the
   * plugin); a 1.1 host calls these when present and the 1.0 ones otherwise. */
  const rumble_lifecycle_api* lifecycle; /**< may be null */
  rumble_status (*mass_matrix2)(rumble_instance* self, const double* q, uint64_t n_dof,
                                double* mass, uint64_t n_mass);
  rumble_status (*forces2)(rumble_instance* self, double t, const double* q, const double* qd,
                           uint64_t n_dof, double* f);
  /** z: n_wheels values; jacobian: n_wheels x n_dof, column-major. */
  rumble_status (*wheel_kinematics2)(rumble_instance* self, const double* q, uint64_t n_dof,
                                     double* z, uint64_t n_wheels, double* jacobian);
  rumble_status (*tangent2)(rumble_instance* self, double t, const double* q, const double* qd,
                            uint64_t n_dof, double* stiffness, double* damping);
  /** Output channel names ("name [unit]"), valid until the next call on self: writes at most
   *  capacity pointers to names and the channel count to *n (call with capacity 0 first). */
  rumble_status (*output_names2)(rumble_instance* self, const char** names, uint64_t capacity,
                                 uint64_t* n);
  rumble_status (*outputs2)(rumble_instance* self, double t, const double* q, const double* qd,
                            uint64_t n_dof, double* values, uint64_t n_values);
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

/** 1.1: a named point of the soil whose motion is recorded (receiver). */
typedef struct rumble_probe {
  const char* name; /**< e.g. "r5.0"; unique; valid during set_probes only (copy it) */
  double x;         /**< [m] along the track */
  double y;         /**< [m] across the track (0 on the track axis) */
  double depth;     /**< [m] below the surface, >= 0 (0: on the surface) */
} rumble_probe;

/** Values per probe and sample in probe_samples, in this order. */
#define RUMBLE_PROBE_VALUES 6u /**< vx, vy, vz [m/s], ux, uy, uz [m]; z down + (as above) */

/** 1.1: a compressed-sparse-column matrix; indices 0-based, rows sorted within a column. */
typedef struct rumble_csc {
  uint64_t rows, cols;
  uint64_t nnz;       /**< set by the plugin when values is null (size query) */
  int64_t* col_ptr;   /**< cols + 1 entries, or null for a size query */
  int64_t* row_index; /**< nnz entries, or null */
  double* values;     /**< nnz entries, or null */
} rumble_csc;

/** 1.1: which matrix linear_matrix returns (M x'' + C x' + K x = B F; u = B^T x, v = B^T x').
 *  They describe the motion about the soil's static state: a host starts them at rest at
 *  K^-1 B F_static and reports each footprint where the soil's own initialize put it plus
 *  B^T (x - K^-1 B F_static). A soil's statics may hold more than K^-1 B F (the FEM soil's
 *  static far field: a few per cent); more than a tenth of the settlement is refused. */
typedef enum rumble_matrix {
  RUMBLE_MATRIX_MASS = 0,      /**< M [kg], n_x x n_x */
  RUMBLE_MATRIX_DAMPING = 1,   /**< C [N s/m] */
  RUMBLE_MATRIX_STIFFNESS = 2, /**< K [N/m] */
  RUMBLE_MATRIX_INPUT = 3      /**< B, n_x x n_footprints: footprint forces to DOFs */
} rumble_matrix;

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
  /* ---- 1.1 */
  const rumble_lifecycle_api* lifecycle; /**< may be null */
  /** Optional (RUMBLE_CAP_RECEIVERS): record the motion of these points from now on, at every
   *  internal step (sample_interval 0) or every sample_interval [s] (interpolated). ERROR with a
   *  message naming the probe when one lies outside the soil. */
  rumble_status (*set_probes)(rumble_instance* self, const rumble_probe* probes, uint64_t n,
                              double sample_interval);
  /** Takes the samples recorded since the last call, oldest first (a restore drops those not
   *  yet taken: their step is taken again): times [s] (capacity
   *  entries at most) and values (capacity x n_probes x RUMBLE_PROBE_VALUES); *n_samples is
   *  the number written, or with capacity 0 the number waiting. */
  rumble_status (*probe_samples)(rumble_instance* self, double* times, double* values,
                                 uint64_t capacity, uint64_t* n_samples);
  /** Optional (RUMBLE_CAP_FIELD_OUTPUT): write the soil's fields at the current time to path
   *  (a VTK XML unstructured grid, .vtu); the host names the files and writes the .pvd index.
   *  A RUMBLE_CAP_DISTRIBUTED soil on N > 1 ranks (1.4) is given, on every rank, a path ending
   *  in .pvtu: each rank r writes its piece, a .vtu at that path with ".pvtu" replaced by
   *  "_<r>.vtu" (r in decimal: soil_000002_0.vtu), its shared points marked in the point array
   *  vtkGhostType (1 on the copies a rank does not own), and rank 0 writes the parallel index
   *  (.pvtu) naming the pieces by their file names (docs/fem-soil.md, "On many ranks"). */
  rumble_status (*write_fields)(rumble_instance* self, double t, const char* path);
  /** Optional (RUMBLE_CAP_WAVE_SPEEDS): the slowest shear and Rayleigh wave speeds [m/s] of
   *  any layer, for the host's critical-speed check (the host never reads a soil's params);
   *  0 when not known for these params (e.g. a soil given by its springs). Needs no layout. */
  rumble_status (*wave_speeds)(rumble_instance* self, double* c_s_min, double* c_r_min);
  /** Optional (RUMBLE_CAP_LINEAR_MATRICES), after accept_layout: one matrix of the soil's linear
   *  equations (rumble_matrix). With out->values null the plugin sets rows, cols and nnz;
   *  then the host calls again with arrays of that size. */
  rumble_status (*linear_matrix)(rumble_instance* self, int32_t which, rumble_csc* out);
  /* ---- 1.3 */
  /** Optional (may be null), after set_probes: the highest frequency [Hz] up to which the soil
   *  carries the motion from the footprints to each probe (n values in set_probes' order; 0
   *  where it cannot say; a FEM soil: its elements per wavelength along the path from the
   *  load), and in *rule how that frequency is found (UTF-8, kept by the soil until its next
   *  call; may be left null). */
  rumble_status (*probe_resolution)(rumble_instance* self, double* f_hz, uint64_t n,
                                    const char** rule);
  /* ---- 1.5 */
  /** Optional (may be null), after accept_layout: the soil's degrees of freedom (*n_dof; 0 when
   *  it has none to speak of) and its estimate of the process's peak resident memory over a run
   *  on this layout [bytes] (*peak_bytes, made before the statics spend it; 0 when it cannot
   *  say). The host writes memory per DOF and the estimate beside what it measured. */
  rumble_status (*size)(rumble_instance* self, uint64_t* n_dof, double* peak_bytes);
  /** Optional (may be null): the host's static iteration is over and the steps come next; the
   *  soil may free what only its statics needed (a factor, a multigrid hierarchy). A later
   *  initialize is still allowed: the soil builds again what it needs. */
  rumble_status (*statics_done)(rumble_instance* self);
} rumble_soil_api;

/* ------------------------------------------------------------------ couplers ------------- */

/** Participant indices in rumble_cosim_host calls: the vehicle/track is always 0 ("track"), the
 *  scenario's soil always 1 ("soil"); a coupler's extra participants follow (1.1). */
#define RUMBLE_PARTICIPANT_TRACK 0u
#define RUMBLE_PARTICIPANT_SOIL 1u

/** 1.1: sides of a participant's interface. */
#define RUMBLE_SIDE_OUTPUT 0u
#define RUMBLE_SIDE_INPUT 1u

/**
 * 1.1: a named group of a participant's interface channels: channels offset .. offset+count-1
 * of its output vector (or input waveform). A coupler links an output group to the input group
 * of the same name on another participant. Groups of the vehicle/track and soils:
 *   "footprint_force" [N]: track output, soil input
 *   "footprint_displacement" [m], "footprint_velocity" [m/s]: soil output, track input
 */
typedef struct rumble_channel_group {
  const char* name; /**< valid while the host lives */
  const char* unit; /**< SI, e.g. "N", "m", "m/s" */
  uint64_t offset;
  uint64_t count;
} rumble_channel_group;

/** 1.1: the interface residual of one channel group at the end of a macro step. */
typedef struct rumble_group_residual {
  const char* group; /**< channel group name */
  double absolute;   /**< max |value used - value produced| over the group [group's unit] */
  double relative;   /**< absolute / the group's scale (see the coupler's documentation) */
} rumble_group_residual;

/** A group residual named with this prefix and then a group's name is not a final residual: it is
 *  the residual of the step's predictor for that group (the inputs extrapolated from past steps
 *  against the values produced: an iterating scheme's first iterate), the coupling error of the
 *  step, of the scheme's order (docs/couplers.md). Hosts record it apart; a scheme reporting none
 *  has final residuals that are its predictor's (an explicit one). A name, not a layout change. */
#define RUMBLE_PREDICTOR_RESIDUAL_PREFIX "predictor:"

/** 1.1: what a coupler reports when a macro step is final. */
typedef struct rumble_step_report {
  uint32_t struct_size;
  uint32_t iterations; /**< 1 for an explicit scheme; passes of an iterating one */
  double t;            /**< [s] step start */
  double H;            /**< [s] step length */
  int32_t converged;   /**< 1: converged (or explicit); 0: accepted at the iteration limit */
  uint32_t n_residuals;
  const rumble_group_residual* residuals; /**< n_residuals entries */
  /** Bit p set: participant p's step [t, t + H] is final (recorded). 0 means every one. */
  uint64_t participants;
} rumble_step_report;

/**
 * The host's participant interface given to a coupler. A coupler never calls a vehicle or soil
 * plugin itself. Interface data, per footprint i of n:
 *   track output: F_i [N] (n values)      -> soil input (waveform of n channels)
 *   soil output:  u_i [m] then v_i [m/s]  -> track input (waveform of 2n channels)
 * Calls on different participants may run concurrently; calls on one participant may not.
 * What the host has done before run (statics: every participant at its static state, the soils'
 * inputs their static footprint forces) and what the coupler owns: docs/couplers.md, "The
 * coupler contract".
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
  /* ---- 1.1 (advance now returns DISCARD when a participant refused the step, state unchanged;
   * a 1.0 coupler keeps the 1.0 behaviour: the host turns it into ERROR for it) */
  uint32_t (*participant_count)(void* ctx);
  /** "track", "soil", or an extra participant's name; NULL for an unknown index. */
  const char* (*participant_name)(void* ctx, uint32_t participant);
  /** Channel groups of a participant's side (RUMBLE_SIDE_*): writes at most capacity and the
   *  count to *n (call with capacity 0 first). */
  rumble_status (*channel_groups)(void* ctx, uint32_t participant, uint32_t side,
                                  rumble_channel_group* out, uint64_t capacity, uint64_t* n);
  /** Replaces step_done: the step is final for the participants in report->participants. */
  rumble_status (*step_report)(void* ctx, const rumble_step_report* report);
  /** Releases a checkpoint slot (its memory, on the host or in the plugin). */
  rumble_status (*free_checkpoint)(void* ctx, uint32_t participant, uint32_t slot);
  /** Nonzero when the participant can save and restore (every soil a coupler needing
   *  RUMBLE_CAP_SAVE_RESTORE drives can: validate checked it). */
  int32_t (*can_checkpoint)(void* ctx, uint32_t participant);
  /* ---- 1.4 */
  /** The footprint layout every soil accepted (accept_layout), in channel order: footprint i is
   *  channel i of footprint_force [N] and of footprint_displacement [m] and footprint_velocity
   *  [m/s] of every participant. Writes at most capacity footprints and the count to *n (call
   *  with capacity 0 first). */
  rumble_status (*footprint_layout)(void* ctx, rumble_footprint* out, uint64_t capacity,
                                    uint64_t* n);
  /* ---- 1.7 */
  /** Nonzero when the participant's advance may return RUMBLE_DISCARD: some vehicle or soil in
   *  it does not offer RUMBLE_CAP_NEVER_REFUSES. A coupler on a host older than 1.7 (no field)
   *  assumes it may. */
  int32_t (*may_refuse)(void* ctx, uint32_t participant);
} rumble_cosim_host;

typedef struct rumble_coupler_api {
  uint32_t struct_size;
  rumble_common_api common;
  rumble_status (*run)(rumble_instance* self, const rumble_cosim_host* host, double t0,
                       double t_end, double H);
  /* ---- 1.1 */
  const rumble_lifecycle_api* lifecycle; /**< may be null */
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
  /* ---- 1.1 */
  const rumble_capabilities* capabilities; /**< may be null (1.0 rules: derived by the host) */
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
