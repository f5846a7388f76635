#include "mesh_cache.hpp"

#include <gmsh.h>
#include <unistd.h>

#include <cstdint>
#include <cstdlib>
#include <fstream>
#include <sstream>

namespace rumble::fem {

namespace {

constexpr char kMagic[8] = {'R', 'M', 'B', 'M', 'E', 'S', 'H', '1'};

/// FNV-1a, 64 bit: enough to tell meshes apart and to detect a damaged file.
std::uint64_t fnv1a(const void* data, std::size_t bytes, std::uint64_t h = 1469598103934665603ull) {
  const auto* p = static_cast<const unsigned char*>(data);
  for (std::size_t i = 0; i < bytes; ++i) h = (h ^ p[i]) * 1099511628211ull;
  return h;
}

template <class T>
void put(std::ostream& out, std::uint64_t& sum, const T* data, std::size_t n) {
  out.write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(n * sizeof(T)));
  sum = fnv1a(data, n * sizeof(T), sum);
}

template <class T>
bool get(std::istream& in, std::uint64_t& sum, T* data, std::size_t n) {
  in.read(reinterpret_cast<char*>(data), static_cast<std::streamsize>(n * sizeof(T)));
  sum = fnv1a(data, n * sizeof(T), sum);
  return static_cast<bool>(in);
}

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
  char magic[8];
  std::uint64_t counts[4], sum = 0, stored = 0;
  if (!in.read(magic, 8) || std::string(magic, 8) != std::string(kMagic, 8)) return std::nullopt;
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
      !get(in, sum, m.truncation.data(), truncation) ||
      !in.read(reinterpret_cast<char*>(&stored), 8) || stored != sum)
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
  std::error_code ec;
  std::filesystem::create_directories(path.parent_path(), ec);
  const std::filesystem::path partial =
      path.string() + ".partial." + std::to_string(static_cast<long>(::getpid()));
  {
    std::ofstream out(partial, std::ios::binary | std::ios::trunc);
    if (!out) return false;
    out.write(kMagic, 8);
    std::uint64_t sum = 0;
    const std::uint64_t counts[4] = {static_cast<std::uint64_t>(m.node_count()), m.tets.size(),
                                     m.ground.size(), m.truncation.size()};
    put(out, sum, counts, 4);
    put(out, sum, m.nodes.data(), static_cast<std::size_t>(m.nodes.size()));
    put(out, sum, m.tets.data(), m.tets.size());
    put(out, sum, m.layer.data(), m.layer.size());
    put(out, sum, m.ground.data(), m.ground.size());
    put(out, sum, m.truncation.data(), m.truncation.size());
    out.write(reinterpret_cast<const char*>(&sum), 8);
    if (!out) {
      out.close();
      std::filesystem::remove(partial, ec);
      return false;
    }
  }
  std::filesystem::rename(partial, path, ec);
  if (ec) std::filesystem::remove(partial, ec);
  return !ec;
}

}  // namespace rumble::fem
