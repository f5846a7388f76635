#include "distributed/part_pieces.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <utility>

#include "boundary/absorbing_boundary.hpp"
#include "distributed/rank_sum.hpp"
#include "mesh/track_region.hpp"

namespace rumble::fem {

namespace {

constexpr int kShareWidth = 4;  // a node's share of the surface: area, weighted normal (3)

/// Every rank's values, in rank order (an all-gather of differing counts).
std::vector<double> gather_all(MPI_Comm comm, const std::vector<double>& mine) {
  int ranks = 1;
  MPI_Comm_size(comm, &ranks);
  const int count = static_cast<int>(mine.size());
  std::vector<int> counts(static_cast<std::size_t>(ranks)), starts(counts.size(), 0);
  MPI_Allgather(&count, 1, MPI_INT, counts.data(), 1, MPI_INT, comm);
  for (int r = 1; r < ranks; ++r) starts[r] = starts[r - 1] + counts[r - 1];
  std::vector<double> all(static_cast<std::size_t>(starts.back() + counts.back()));
  MPI_Allgatherv(mine.data(), count, MPI_DOUBLE, all.data(), counts.data(), starts.data(),
                 MPI_DOUBLE, comm);
  return all;
}

/// Whether footprint_weights counts the ground face f of `mesh` (its centroid in a footprint).
bool under_a_footprint(const TetMesh& mesh, const Triangle& f,
                       const std::vector<Footprint>& footprints) {
  const double x = (mesh.nodes(0, f[0]) + mesh.nodes(0, f[1]) + mesh.nodes(0, f[2])) / 3.0;
  const double y = (mesh.nodes(1, f[0]) + mesh.nodes(1, f[1]) + mesh.nodes(1, f[2])) / 3.0;
  return std::any_of(footprints.begin(), footprints.end(), [&](const Footprint& p) {
    return std::abs(x - p.x) <= 0.5 * p.width && std::abs(y - p.y) <= 0.5 * p.length;
  });
}

// A gathered ground face: its index among the whole mesh's ground faces, its nodes' numbers in
// the whole mesh and their coordinates.
constexpr int kFaceDoubles = 13;
using GatheredFace = std::array<double, kFaceDoubles>;

/// The faces as a mesh of their own (nodes numbered by the order of their whole numbers), and
/// each of its nodes' whole number.
std::pair<TetMesh, std::vector<std::int32_t>> faces_mesh(std::vector<GatheredFace> faces) {
  // In the whole mesh's order of its ground faces, on every rank: footprint_weights then sums
  // each weight and area in the one process's order, to the bit.
  std::sort(faces.begin(), faces.end());
  std::vector<std::int32_t> whole;
  for (const GatheredFace& f : faces)
    for (int a = 0; a < 3; ++a) whole.push_back(static_cast<std::int32_t>(f[1 + a]));
  std::sort(whole.begin(), whole.end());
  whole.erase(std::unique(whole.begin(), whole.end()), whole.end());
  TetMesh mesh;
  mesh.nodes.resize(3, static_cast<Eigen::Index>(whole.size()));
  for (const GatheredFace& f : faces) {
    Triangle t{};
    for (int a = 0; a < 3; ++a) {
      t[a] = static_cast<std::int32_t>(
          std::lower_bound(whole.begin(), whole.end(), static_cast<std::int32_t>(f[1 + a])) -
          whole.begin());
      for (int c = 0; c < 3; ++c) mesh.nodes(c, t[a]) = f[4 + 3 * a + c];
    }
    mesh.ground.push_back(t);
  }
  return {std::move(mesh), std::move(whole)};
}

}  // namespace

std::vector<BoundaryNode> part_boundary(const MeshPartition& part, const FemSettings& settings,
                                        const std::vector<Footprint>& footprints) {
  const SurfaceShares mine = truncation_shares(part.mesh, TrackRegion::of(footprints));
  // The shared nodes' shares summed over the ranks (each face is on one rank) and copied back.
  std::vector<double> halo(static_cast<std::size_t>(kShareWidth * part.shared), 0.0);
  std::vector<std::int32_t> index(static_cast<std::size_t>(part.nodes()), -1);
  for (std::size_t k = 0; k < mine.nodes.size(); ++k) {
    index[mine.nodes[k]] = static_cast<std::int32_t>(k);
    if (mine.nodes[k] >= part.shared) continue;
    double* share = halo.data() + kShareWidth * mine.nodes[k];
    share[0] = mine.area[k];
    for (int c = 0; c < 3; ++c) share[1 + c] = mine.weighted_normal[k][c];
  }
  part.halo->sum_to_roots(halo.data(), halo.data(), kShareWidth);
  part.halo->to_leaves(halo.data(), halo.data(), kShareWidth);
  SurfaceShares complete;  // (in local node order)
  for (std::int32_t i = 0; i < part.nodes(); ++i) {
    if (i < part.shared && halo[kShareWidth * i] > 0.0) {
      const double* share = halo.data() + kShareWidth * i;
      complete.nodes.push_back(i);
      complete.area.push_back(share[0]);
      complete.weighted_normal.emplace_back(share[1], share[2], share[3]);
    } else if (i >= part.shared && index[i] >= 0) {
      complete.nodes.push_back(i);
      complete.area.push_back(mine.area[index[i]]);
      complete.weighted_normal.push_back(mine.weighted_normal[index[i]]);
    }
  }
  return fitted_boundary(part.mesh, settings, footprints, complete);
}

FootprintWeights part_footprint_weights(MPI_Comm comm, const MeshPartition& part,
                                        const std::vector<Footprint>& footprints) {
  std::vector<double> mine;
  for (std::size_t k = 0; k < part.mesh.ground.size(); ++k) {
    const Triangle& f = part.mesh.ground[k];
    if (!under_a_footprint(part.mesh, f, footprints)) continue;
    mine.push_back(part.ground_global[k]);
    for (std::int32_t v : f) mine.push_back(part.global[v]);
    for (std::int32_t v : f)
      for (int c = 0; c < 3; ++c) mine.push_back(part.mesh.nodes(c, v));
  }
  const std::vector<double> all = gather_all(comm, mine);
  std::vector<GatheredFace> faces(all.size() / kFaceDoubles);
  for (std::size_t k = 0; k < faces.size(); ++k)
    std::copy_n(all.data() + kFaceDoubles * k, kFaceDoubles, faces[k].begin());
  const auto [mesh, whole] = faces_mesh(std::move(faces));
  FootprintWeights weights = footprint_weights(mesh, footprints);
  for (std::vector<NodalWeight>& footprint : weights) {
    std::vector<NodalWeight> here;
    for (const NodalWeight& w : footprint)
      if (const std::int32_t local = part.local_of(whole[w.node]); local >= 0)
        here.push_back({local, w.weight});
    footprint = std::move(here);
  }
  return weights;
}

std::vector<PartProbe> part_probes(MPI_Comm comm, const MeshPartition& part,
                                   const std::vector<Probe>& probes) {
  std::vector<ProbeCandidate> best;
  std::vector<double> mine;  // per receiver: smallest coordinate, whole tetrahedron (-1: none)
  for (const Probe& p : probes) {
    best.push_back(best_tetrahedron(part.mesh, Eigen::Vector3d(p.x, p.y, p.depth)));
    mine.push_back(best.back().smallest);
    mine.push_back(best.back().tet < 0 ? -1.0 : part.tet_global[best.back().tet]);
  }
  const std::vector<double> all = gather_all(comm, mine);
  const std::size_t ranks = all.size() / std::max<std::size_t>(1, mine.size());
  int rank = 0;
  MPI_Comm_rank(comm, &rank);
  std::vector<PartProbe> here;
  for (std::size_t p = 0; p < probes.size(); ++p) {
    std::size_t winner = 0;  // (the largest coordinate; among equals the first tetrahedron)
    for (std::size_t r = 1; r < ranks; ++r) {
      const double* c = all.data() + 2 * (r * probes.size() + p);
      const double* w = all.data() + 2 * (winner * probes.size() + p);
      if (c[0] > w[0] || (c[0] == w[0] && c[1] >= 0.0 && c[1] < w[1])) winner = r;
    }
    if (!(all[2 * (winner * probes.size() + p)] >= -1e-6))
      refuse_probe_outside(probes[p].name, probes[p].x, probes[p].y, probes[p].depth);
    if (winner == static_cast<std::size_t>(rank)) here.push_back({p, best[p].point});
  }
  return here;
}

double boundary_mean_distance(MPI_Comm comm, const MeshPartition& part,
                              const std::vector<BoundaryNode>& boundary,
                              const std::vector<Footprint>& footprints) {
  int rank = 0;
  MPI_Comm_rank(comm, &rank);
  Eigen::Vector3d centre = Eigen::Vector3d::Zero();  // (as StaticFarField's)
  for (const Footprint& f : footprints) centre += Eigen::Vector3d(f.x, f.y, 0.0);
  if (!footprints.empty()) centre /= static_cast<double>(footprints.size());
  double sum = 0.0, count = 0.0;
  for (const BoundaryNode& b : boundary) {
    if (!part.owns(b.node, rank)) continue;
    sum += (part.mesh.node(b.node) - centre).norm();
    count += 1.0;
  }
  const double all = sum_in_rank_order(comm, count);
  return all > 0.0 ? sum_in_rank_order(comm, sum) / all : 0.0;
}

}  // namespace rumble::fem
