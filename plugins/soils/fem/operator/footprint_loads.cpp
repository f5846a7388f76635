#include "operator/footprint_loads.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <sstream>
#include <stdexcept>

namespace rumble::fem {

FootprintWeights footprint_weights(const TetMesh& mesh, const std::vector<Footprint>& footprints) {
  FootprintWeights weights(footprints.size());
  std::vector<double> meshed_area(footprints.size(), 0.0);
  std::vector<std::map<std::int32_t, double>> integral(footprints.size());
  for (const Triangle& f : mesh.ground) {
    const double area = triangle_area(mesh, f, nullptr);
    const double x = (mesh.nodes(0, f[0]) + mesh.nodes(0, f[1]) + mesh.nodes(0, f[2])) / 3.0;
    const double y = (mesh.nodes(1, f[0]) + mesh.nodes(1, f[1]) + mesh.nodes(1, f[2])) / 3.0;
    for (std::size_t j = 0; j < footprints.size(); ++j) {
      const Footprint& p = footprints[j];
      if (std::abs(x - p.x) > 0.5 * p.width || std::abs(y - p.y) > 0.5 * p.length) continue;
      meshed_area[j] += area;
      for (std::int32_t v : f) integral[j][v] += area / 3.0;  // integral of N_v on the face
      break;
    }
  }
  for (std::size_t j = 0; j < footprints.size(); ++j) {
    const double area = footprints[j].length * footprints[j].width;
    if (!(std::abs(meshed_area[j] - area) <= 0.01 * area)) {
      std::ostringstream m;
      m << "fem: footprint " << j << " (x " << footprints[j].x << " m, y " << footprints[j].y
        << " m, " << footprints[j].length << " m x " << footprints[j].width << " m = " << area
        << " m^2) covers " << meshed_area[j] << " m^2 of the meshed ground; "
        << (meshed_area[j] == 0.0 ? "it lies outside the mesh: enlarge mesh.radius"
                                  : "the mesh does not follow its edges (overlapping footprints?)");
      throw std::invalid_argument(m.str());
    }
    for (const auto& [node, value] : integral[j])
      weights[j].push_back({node, value / meshed_area[j]});
  }
  return weights;
}

std::vector<std::int32_t> loaded_nodes(const FootprintWeights& weights) {
  std::vector<std::int32_t> nodes;
  for (const std::vector<NodalWeight>& footprint : weights)
    for (const NodalWeight& w : footprint) nodes.push_back(w.node);
  std::sort(nodes.begin(), nodes.end());
  nodes.erase(std::unique(nodes.begin(), nodes.end()), nodes.end());
  return nodes;
}

}  // namespace rumble::fem
