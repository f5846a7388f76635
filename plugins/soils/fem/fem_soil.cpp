// fem: the soil as a 3D finite-element half-space (docs/soils.md, "FEM soil"). Meshed with gmsh
// when the track announces its footprints; linear tetrahedra, lumped mass, Rayleigh damping,
// Lysmer-Kuhlemeyer dashpots with springs on the truncation surface; the static state from one
// sparse Cholesky solve, the motion about it by explicit central differences sub-cycled inside
// each macro step. The footprint forces act as uniform pressures on the footprints; the track
// sees their area-averaged vertical motion (footprint_loads.hpp).
//
// This file makes the soil and registers it, so that what the plugin is and how the host finds
// it read in one place; what it does per call lives by concern in the files fem_soil.hpp names.
#include "fem_soil.hpp"

#include <cstdint>
#include <nlohmann/json.hpp>
#include <rumble/params_file.hpp>
#include <sstream>
#include <string>

#include "operator/blas_threads.hpp"
#include "wave_speeds.hpp"

namespace rumble::fem {

std::string FemSoil::format(double x, int digits) {
  std::ostringstream s;
  s.precision(digits);
  s << x;
  return s.str();
}

FemSoil::FemSoil(const std::string& params_json, const rumble::Host& host)
    : settings_(rumble::fem::read_settings(params_json)),
      params_(nlohmann::json::parse(params_json).dump()),
      host_(host) {
  // A mesh file is found (and sized) at once, so that validation names it at params.
  if (!settings_.mesh.file.empty()) {
    const double limit = settings_.mesh.max_file_bytes();
    mesh_file_ =
        rumble::checked_params_file(
            "fem: params/mesh/file", settings_.mesh.file,
            nlohmann::json(settings_.mesh.file).dump(), host_.scenario_dir(),
            {.noun = "a mesh file",
             .file_noun = "a gmsh mesh file (.msh)",
             .max_bytes = static_cast<std::uintmax_t>(limit),
             .too_large_fix = "is this the right file? (the limit is 256 bytes per "
                              "mesh.max_dofs, now " +
                              format(settings_.mesh.max_dofs) + "; raise it for a larger mesh)"})
            .lexically_normal()
            .string();
  }
  if (const int blas = keep_blas_on_one_thread(); blas > 0)
    host_.log(RUMBLE_LOG_DEBUG, "fem: OpenBLAS on one thread beside the soil's own (it had " +
                                    std::to_string(blas) + "; operator/blas_threads.hpp)");
  join_ranks();  // (under mpirun -n N, N > 1: this rank's share of the mesh, fem_distributed.cpp)
}

void FemSoil::wave_speeds(double& c_s_min, double& c_r_min) const {
  const auto s = rumble::soils::slowest_wave_speeds(settings_.layers, settings_.half_space);
  c_s_min = s.shear;
  c_r_min = s.rayleigh;
}

}  // namespace rumble::fem

RUMBLE_PLUGIN("fem", "0.2.0", rumble::fem::FemSoil)
