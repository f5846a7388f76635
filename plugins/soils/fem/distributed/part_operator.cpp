#include "distributed/part_operator.hpp"

#include <optional>
#include <utility>

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
  std::vector<char> fixed(static_cast<std::size_t>(part.nodes()), 0);
  if (settings.boundary.kind == BoundaryKind::kFixed)  // (the matched layer is refused here)
    for (const BoundaryNode& b : boundary) fixed[b.node] = 1;
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
