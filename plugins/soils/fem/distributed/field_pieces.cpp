#include "distributed/field_pieces.hpp"

#include <cstdint>
#include <vector>

#include "distributed/rank_agreement.hpp"
#include "output/pvtu_writer.hpp"
#include "output/vtu_writer.hpp"

namespace rumble::fem {

void write_field_pieces(const DistributedSoil& soil, double t, const std::string& pvtu) {
  const MeshPartition& part = soil.partition();
  on_every_rank(soil.comm(), [&] {
    std::vector<std::uint8_t> ghosts(part.owner.size());
    for (std::size_t k = 0; k < ghosts.size(); ++k)
      ghosts[k] = part.owner[k] == soil.rank() ? 0 : 1;  // (VTK's DUPLICATEPOINT)
    write_vtu(piece_path(pvtu, soil.rank()), t, part.mesh, soil.static_state() + soil.state().w,
              soil.state().v, &ghosts);
    if (soil.root()) write_pvtu(pvtu, soil.ranks());
  });
}

}  // namespace rumble::fem
