#include "mesh/mesh_cache.hpp"

#include <gmsh.h>

#include <cstdint>
#include <cstdlib>
#include <fstream>
#include <sstream>

#include "mesh/cache_file.hpp"

namespace rumble::fem {

namespace {

using cache::fnv1a;
using cache::get;
using cache::put;

constexpr char kMagic[8] = {'R', 'M', 'B', 'M', 'E', 'S', 'H', '1'};

}  // namespace

std::optional<std::filesystem::path> mesh_cache_directory() {
  if (const char* dir = std::getenv("RUMBLE_MESH_CACHE")) {
    const std::string d = dir;
    if (d.empty() || d == "off") return std::nullopt;
    return std::filesystem::path(d);
  }
  if (const char* xdg = std::getenv("XDG_CACHE_HOME"); xdg != nullptr && *xdg != '\0')
    return std::filesystem::path(xdg) / "rumble" / "meshes";
  if (const char* home = std::getenv("HOME"); home != nullptr && *home != '\0')
    return std::filesystem::path(home) / ".cache" / "rumble" / "meshes";
  return std::nullopt;
}

std::string mesh_cache_name(const FemSettings& s, const std::vector<Footprint>& footprints,
                            const MeshPlan& p) {
  std::ostringstream key;
  key.precision(17);
  // -2: generated meshes have their nodes in Morton order (node_order.hpp) since 2026-12-02.
  key << "rumble-fem-mesh-2 gmsh " << GMSH_API_VERSION << " algorithm "
      << (s.mesh.fast_algorithm ? "hxt" : "delaunay") << " threads " << s.mesh_threads << " shape "
      << static_cast<int>(p.shape) << " radius " << p.radius << " h " << p.h_near << ' ' << p.h_max
      << ' ' << p.near_distance;
  if (s.mesh.quality_threshold != 0.3)  // (gmsh's default: the keys of older meshes still hold)
    key << " quality " << s.mesh.quality_threshold;
  if (p.pml > 0.0) key << " pml " << p.pml << ' ' << p.h_pml;  // (absent: older keys still hold)
  if (p.refine > 0) key << " coarse for refine " << p.refine;  // (the mesh gmsh made, unrefined)
  key << " layers";
  for (const soils::SoilLayer& l : s.layers) key << ' ' << l.thickness;
  key << " footprints";
  for (const Footprint& f : footprints)
    key << ' ' << f.x << ' ' << f.y << ' ' << f.length << ' ' << f.width;
  const std::string text = key.str();
  std::ostringstream name;
  name << std::hex << fnv1a(text.data(), text.size()) << ".mesh";
  return name.str();
}

std::optional<TetMesh> read_cached_mesh(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) return std::nullopt;
  std::uint64_t counts[4], sum = 0;
  if (!cache::read_magic(in, kMagic)) return std::nullopt;
  if (!get(in, sum, counts, 4)) return std::nullopt;
  const auto [nodes, tets, ground, truncation] = counts;
  if (nodes == 0 || tets == 0 || nodes > (1ull << 31) || tets > (1ull << 33)) return std::nullopt;
  TetMesh m;
  m.nodes.resize(3, static_cast<Eigen::Index>(nodes));
  m.tets.resize(tets);
  m.layer.resize(tets);
  m.ground.resize(ground);
  m.truncation.resize(truncation);
  if (!get(in, sum, m.nodes.data(), 3 * nodes) || !get(in, sum, m.tets.data(), tets) ||
      !get(in, sum, m.layer.data(), tets) || !get(in, sum, m.ground.data(), ground) ||
      !get(in, sum, m.truncation.data(), truncation) || !cache::read_checksum(in, sum))
    return std::nullopt;
  // (a copy: Clang 14 cannot capture a structured binding)
  const auto valid = [node_count = nodes](const auto& elements) {
    for (const auto& e : elements)
      for (std::int32_t v : e)
        if (v < 0 || static_cast<std::uint64_t>(v) >= node_count) return false;
    return true;
  };
  if (!valid(m.tets) || !valid(m.ground) || !valid(m.truncation)) return std::nullopt;
  return m;
}

bool write_cached_mesh(const std::filesystem::path& path, const TetMesh& m) {
  return cache::write_whole(path, kMagic, [&m](std::ostream& out, std::uint64_t& sum) {
    const std::uint64_t counts[4] = {static_cast<std::uint64_t>(m.node_count()), m.tets.size(),
                                     m.ground.size(), m.truncation.size()};
    put(out, sum, counts, 4);
    put(out, sum, m.nodes.data(), static_cast<std::size_t>(m.nodes.size()));
    put(out, sum, m.tets.data(), m.tets.size());
    put(out, sum, m.layer.data(), m.layer.size());
    put(out, sum, m.ground.data(), m.ground.size());
    put(out, sum, m.truncation.data(), m.truncation.size());
  });
}

}  // namespace rumble::fem
