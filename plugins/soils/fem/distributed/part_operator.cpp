#include "distributed/part_operator.hpp"

#include <optional>
#include <utility>

#include "boundary/absorbing_boundary.hpp"
#include "distributed/part_pieces.hpp"
#include "distributed/part_stiffness.hpp"
#include "distributed/rank_agreement.hpp"
#include "operator/elasticity.hpp"

namespace rumble::fem {

std::unique_ptr<DistributedOperator> part_operator(const MeshPartition& part,
                                                   const FemSettings& settings,
                                                   const std::vector<Footprint>& footprints,
                                                   unsigned threads, StepPrecision precision,
                                                   MPI_Comm comm) {
  std::vector<BoundaryNode> boundary = part_boundary(part, settings, footprints);
  // (held as on one process: the fixed boundary's nodes, or the matched layer's outer surface)
  std::vector<char> fixed = held_nodes(part.nodes(), boundary, settings);
  std::optional<CsrMatrix> K;
  Eigen::VectorXd mass;
  on_every_rank(comm, [&] {  // (a degenerate tetrahedron throws on its rank alone)
    K.emplace(assemble_stiffness(part.mesh, settings));
    mass = lumped_mass(part.mesh, settings);
  });
  complete_shared_entries(part, *K, comm);
  complete_mass(part, mass);
  return std::make_unique<DistributedOperator>(
      std::move(*K), ElementStiffness(part.mesh, settings), std::move(mass), std::move(boundary),
      settings.boundary.springs(), std::move(fixed), threads, precision, part, comm);
}

}  // namespace rumble::fem
