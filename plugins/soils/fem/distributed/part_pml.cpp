#include "distributed/part_pml.hpp"

#include <algorithm>
#include <array>
#include <cstdint>
#include <vector>

namespace rumble::fem {

PmlProfile from_root(const PmlProfile& profile, MPI_Comm comm) {
  static_assert(sizeof(PmlProfile) == 9 * sizeof(double), "a field of PmlProfile is not sent");
  std::array<double, 9> box{profile.low[0],    profile.low[1],     profile.low[2],
                            profile.high[0],   profile.high[1],    profile.high[2],
                            profile.thickness, profile.reflection, profile.shift};
  MPI_Bcast(box.data(), static_cast<int>(box.size()), MPI_DOUBLE, 0, comm);
  PmlProfile p;
  p.low = {box[0], box[1], box[2]};
  p.high = {box[3], box[4], box[5]};
  p.thickness = box[6];
  p.reflection = box[7];
  p.shift = box[8];
  return p;
}

PmlLayer part_pml(const MeshPartition& part, const FemSettings& settings, const PmlProfile& profile,
                  MPI_Comm comm) {
  PmlLayer layer(part.mesh, settings, profile);
  const std::int32_t shared = part.shared;
  // A shared node is a layer node here where it is one on any rank.
  std::vector<double> in_layer(static_cast<std::size_t>(shared), 0.0);
  for (std::int32_t i = 0; i < shared; ++i) in_layer[i] = layer.layer_node(i) >= 0 ? 1.0 : 0.0;
  part.halo->sum_to_roots(in_layer.data(), in_layer.data(), 1);
  part.halo->to_leaves(in_layer.data(), in_layer.data(), 1);
  std::vector<std::int32_t> added;
  for (std::int32_t i = 0; i < shared; ++i)
    if (in_layer[i] > 0.0 && layer.layer_node(i) < 0) added.push_back(i);
  layer.add_nodes(added);
  // Their mass side summed over the ranks' tetrahedra (the owner's sum copied to each ghost).
  constexpr int kTerms = PmlLayer::kMassTerms;
  std::vector<double> terms(static_cast<std::size_t>(kTerms) * shared, 0.0);
  for (std::int32_t i = 0; i < shared; ++i)
    if (const std::int32_t p = layer.layer_node(i); p >= 0)
      std::copy_n(layer.mass_terms(p).data(), kTerms, terms.data() + kTerms * i);
  part.halo->sum_to_roots(terms.data(), terms.data(), kTerms);
  part.halo->to_leaves(terms.data(), terms.data(), kTerms);
  for (std::int32_t i = 0; i < shared; ++i)
    if (const std::int32_t p = layer.layer_node(i); p >= 0)
      std::copy_n(terms.data() + kTerms * i, kTerms, layer.mass_terms(p).data());
  double mine = layer.max_damping(), most = 0.0;
  MPI_Allreduce(&mine, &most, 1, MPI_DOUBLE, MPI_MAX, comm);
  layer.set_max_damping(most);
  return layer;
}

}  // namespace rumble::fem
