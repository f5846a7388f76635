#include "statics/coarse_level.hpp"

#include <utility>

#include "boundary/absorbing_boundary.hpp"
#include "operator/csr_operator.hpp"
#include "operator/effective_matrix.hpp"
#include "operator/elasticity.hpp"
#include "statics/nested_interpolation.hpp"

namespace rumble::fem {

CoarseLevel coarse_level(const TetMesh& coarse, const TetMesh& fine, int levels,
                         const FemSettings& settings, const std::vector<Footprint>& footprints,
                         const std::vector<char>& fine_held) {
  CoarseLevel level;
  std::vector<BoundaryNode> boundary = absorbing_boundary(coarse, settings, footprints);
  std::vector<char> held = held_nodes(coarse.node_count(), boundary, settings);
  level.interpolation = nested_interpolation(coarse, fine, levels);
  // (RowSparse is compressed: each row's entries lie in [outer[r], outer[r + 1]))
  RowSparse& p = level.interpolation;
  for (Eigen::Index r = 0; r < p.rows(); ++r)
    for (int k = p.outerIndexPtr()[r]; k < p.outerIndexPtr()[r + 1]; ++k)
      if (fine_held[static_cast<std::size_t>(r)] ||
          held[static_cast<std::size_t>(p.innerIndexPtr()[k])])
        p.valuePtr()[k] = 0.0;
  {  // (the coarse operator only for its combination: 1/8 of the fine mesh's K per level)
    const CsrOperator op(assemble_stiffness(coarse, settings), lumped_mass(coarse, settings),
                         std::move(boundary), true, std::move(held), 1, StepPrecision::kDouble);
    level.matrix = full_combination(op, {.stiffness = 1.0, .springs = true});
  }
  level.matrix.makeCompressed();
  level.nodes = coarse.nodes;
  return level;
}

}  // namespace rumble::fem
