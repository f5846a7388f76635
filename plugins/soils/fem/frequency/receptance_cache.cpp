#include "frequency/receptance_cache.hpp"

#include <fstream>
#include <sstream>

#include "mesh/cache_file.hpp"

namespace rumble::fem {

namespace {

constexpr char kReceptanceMagic[8] = {'R', 'M', 'B', 'F', 'R', 'F', '0', '1'};

template <class T>
std::uint64_t hash_all(const std::vector<T>& v, std::uint64_t h) {
  return cache::fnv1a(v.data(), v.size() * sizeof(T), h);
}

}  // namespace

std::uint64_t receptance_soil_key(const TetMesh& mesh, const std::string& params_json,
                                  const FootprintWeights& weights) {
  // (2: the boundary springs fitted to the half-space; 3: the far field following the forces,
  // docs/fem-soil.md section 3.2)
  const std::string version = "rumble-fem-receptance-3";
  std::uint64_t h = cache::fnv1a(version.data(), version.size());
  h = cache::fnv1a(mesh.nodes.data(), static_cast<std::size_t>(mesh.nodes.size()) * 8, h);
  h = hash_all(mesh.tets, h);
  h = hash_all(mesh.layer, h);
  h = hash_all(mesh.ground, h);
  h = hash_all(mesh.truncation, h);
  h = cache::fnv1a(params_json.data(), params_json.size(), h);
  for (const auto& footprint : weights) {  // (field by field: a NodalWeight has padding)
    const std::uint64_t count = footprint.size();
    h = cache::fnv1a(&count, 8, h);
    for (const NodalWeight& w : footprint) {
      h = cache::fnv1a(&w.node, sizeof w.node, h);
      h = cache::fnv1a(&w.weight, sizeof w.weight, h);
    }
  }
  return h;
}

std::string receptance_cache_name(std::uint64_t soil_key, double f_hz) {
  std::ostringstream name;
  name << std::hex << cache::fnv1a(&f_hz, sizeof f_hz, soil_key) << ".frf";
  return name.str();
}

bool read_cached_receptance(const std::filesystem::path& path, double f_hz, std::size_t n,
                            std::complex<double>* H) {
  std::ifstream in(path, std::ios::binary);
  if (!in || !cache::read_magic(in, kReceptanceMagic)) return false;
  std::uint64_t sum = 0, count = 0;
  double f = 0.0;
  if (!cache::get(in, sum, &count, 1) || count != n || !cache::get(in, sum, &f, 1) || f != f_hz)
    return false;
  return cache::get(in, sum, H, n * n) && cache::read_checksum(in, sum);
}

bool write_cached_receptance(const std::filesystem::path& path, double f_hz, std::size_t n,
                             const std::complex<double>* H) {
  return cache::write_whole(path, kReceptanceMagic, [&](std::ostream& out, std::uint64_t& sum) {
    const std::uint64_t count = n;
    cache::put(out, sum, &count, 1);
    cache::put(out, sum, &f_hz, 1);
    cache::put(out, sum, H, n * n);
  });
}

}  // namespace rumble::fem
