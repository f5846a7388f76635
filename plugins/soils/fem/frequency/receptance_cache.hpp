// FEM receptances kept on disk beside the meshes (mesh_cache.hpp's directory), one file per
// soil and frequency, so that `rumble calibrate` and then `rumble soil-frf` on the same soil, or
// a second calibration, solve each frequency once (one complex LU of the whole mesh each:
// minutes on a 1e5-DOF mesh). The name hashes everything the receptance depends on: the mesh
// (its nodes, tetrahedra, layers and faces), the soil's params as validated (materials,
// damping, boundary), the footprint weights and the frequency's exact value. Written whole with
// a checksum; a file that fails a check is ignored and the frequency solved again.
#pragma once

#include <complex>
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "mesh/tet_mesh.hpp"
#include "operator/footprint_loads.hpp"

namespace rumble::fem {

/// A hash of the soil (mesh, params text as validated, footprint weights): the part of the
/// name that does not change with the frequency.
std::uint64_t receptance_soil_key(const TetMesh& mesh, const std::string& params_json,
                                  const FootprintWeights& weights);

/// The file name (hex hash + ".frf") of the soil's receptance at f_hz.
std::string receptance_cache_name(std::uint64_t soil_key, double f_hz);

/// Reads n x n values (column-major) stored for f_hz at path into H; false when absent or not
/// intact (H is then unspecified).
bool read_cached_receptance(const std::filesystem::path& path, double f_hz, std::size_t n,
                            std::complex<double>* H);

/// Stores them; false when it could not (the caller carries on).
bool write_cached_receptance(const std::filesystem::path& path, double f_hz, std::size_t n,
                             const std::complex<double>* H);

}  // namespace rumble::fem
