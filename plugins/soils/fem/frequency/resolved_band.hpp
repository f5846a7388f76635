// The band the mesh carries from the load to a receiver (docs/fem-soil.md §2.2). Linear
// tetrahedra carry a wave without visible dispersion at about n = elements_per_wavelength
// elements per wavelength, the rule the mesh's sizes were chosen by; the slowest surface wave,
// Rayleigh's, has the shortest wavelength that matters at the surface. The wave a receiver
// records has crossed every element between the track and it, so the largest one on that path
// bounds the band: f = c_R / (n h), h the mean edge length of the largest tetrahedron the
// straight path from the nearest point of the footprints to the receiver crosses.
#pragma once

#include <Eigen/Dense>
#include <vector>

#include "mesh/tet_mesh.hpp"
#include "mesh/track_region.hpp"

namespace rumble::fem {

/// The frequency [Hz] resolved at each point (x, y, depth) [m] for Rayleigh speed c_r [m/s] and
/// n elements per wavelength: the path is sampled at kPathSamples points, each in the
/// tetrahedron holding it (one pass over the mesh). 0 for a point no sample of which is in the
/// mesh.
std::vector<double> path_resolved_frequency(const TetMesh& mesh, const TrackRegion& region,
                                            const std::vector<Eigen::Vector3d>& points, double c_r,
                                            double n);

/// Samples along each path (its ends included).
inline constexpr int kPathSamples = 64;

}  // namespace rumble::fem
