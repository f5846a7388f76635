#include "msh_check.hpp"

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <filesystem>
#include <map>
#include <nlohmann/json.hpp>
#include <set>
#include <sstream>
#include <stdexcept>
#include <vector>

#include "fuzz_support.hpp"
#include "mesh/gmsh_model.hpp"

namespace rumble::fuzz {
namespace {

namespace fs = std::filesystem;

bool starts_with(const std::string& text, const std::string& head) {
  return text.rfind(head, 0) == 0;
}

/// Nodes per element of the gmsh types a soil's mesh may hold (MSH 2.2 numbering): point, line,
/// triangle, quadrangle, tetrahedron, hexahedron, prism, pyramid, second-order tetrahedron.
const std::map<long, std::size_t> kNodesOfType = {{15, 1}, {1, 2}, {2, 3}, {3, 4},  {4, 4},
                                                  {5, 8},  {6, 6}, {7, 5}, {11, 10}};
constexpr long kMaxTag = 1000000;  // gmsh keeps some tables by tag: 1e18 would be its memory

long tag_of(const std::string& token) {
  char* end = nullptr;
  const long v = std::strtol(token.c_str(), &end, 10);
  return *end == '\0' && v >= 1 && v <= kMaxTag ? v : 0;
}

/// The mesh `text` describes, read leniently from the sections of MSH 2.2 (see the header) and
/// written back as a well-formed MSH 2.2 file.
std::string well_formed_msh(std::string_view text) {
  std::istringstream in{std::string(text)};
  std::string line, section;
  std::vector<std::string> names, elements;
  std::map<long, std::string> nodes;  // tag -> "x y z", coordinates as %.17g
  bool counted = false;               // the section's count line is past
  while (std::getline(in, line)) {
    if (!line.empty() && line.back() == '\r') line.pop_back();
    if (starts_with(line, "$")) {
      section = starts_with(line, "$End") ? "" : line;
      counted = false;
      continue;
    }
    if (!counted && !section.empty()) {
      counted = true;  // recounted below
      continue;
    }
    std::istringstream fields(line);
    std::vector<std::string> t;
    for (std::string f; fields >> f;) t.push_back(f);
    if (section == "$PhysicalNames" && t.size() >= 3) {
      const long dim = std::strtol(t[0].c_str(), nullptr, 10);
      const long tag = tag_of(t[1]);
      std::string name;  // between the quotes, without quotes or control characters
      const auto open = line.find('"');
      for (std::size_t i = open == std::string::npos ? line.size() : open + 1; i < line.size(); ++i)
        if (line[i] != '"' && static_cast<unsigned char>(line[i]) >= 0x20) name += line[i];
      if ((dim == 2 || dim == 3) && tag > 0)
        names.push_back(std::to_string(dim) + " " + std::to_string(tag) + " \"" + name + "\"");
    } else if (section == "$Nodes" && t.size() >= 4 && nodes.size() < 5000) {
      const long tag = tag_of(t[0]);
      std::string xyz;
      for (std::size_t c = 1; c <= 3; ++c) {
        char buf[40];
        std::snprintf(buf, sizeof buf, " %.17g", std::strtod(t[c].c_str(), nullptr));
        xyz += buf;
      }
      if (tag > 0) nodes.try_emplace(tag, xyz);
    } else if (section == "$Elements" && t.size() >= 5 && elements.size() < 20000) {
      const long type = std::strtol(t[1].c_str(), nullptr, 10);
      const long ntags = std::strtol(t[2].c_str(), nullptr, 10);
      const auto count = kNodesOfType.find(type);
      if (count == kNodesOfType.end() || ntags < 2 || ntags > 4) continue;
      const auto first_node = static_cast<std::size_t>(3 + ntags);
      if (t.size() != first_node + count->second) continue;
      const long physical = std::strtol(t[3].c_str(), nullptr, 10);
      const long entity = tag_of(t[4]);
      std::string element = std::to_string(type) + " 2 " +
                            std::to_string(physical >= 0 && physical <= kMaxTag ? physical : 0) +
                            " " + std::to_string(entity > 0 ? entity : 1);
      bool known = true;
      for (std::size_t k = first_node; k < t.size() && known; ++k) {
        const long node = tag_of(t[k]);
        known = nodes.count(node) > 0;  // nodes come before the elements in a mesh file
        element += " " + std::to_string(node);
      }
      if (known) elements.push_back(element);
    }
  }
  std::string out = "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n";
  out += "$PhysicalNames\n" + std::to_string(names.size()) + "\n";
  for (const std::string& n : names) out += n + "\n";
  out += "$EndPhysicalNames\n$Nodes\n" + std::to_string(nodes.size()) + "\n";
  for (const auto& [tag, xyz] : nodes) out += std::to_string(tag) + xyz + "\n";
  out += "$EndNodes\n$Elements\n" + std::to_string(elements.size()) + "\n";
  for (std::size_t e = 0; e < elements.size(); ++e)
    out += std::to_string(e + 1) + " " + elements[e] + "\n";
  return out + "$EndElements\n";
}

std::string check_mesh(const fem::MeshFile& file, const fem::FemSettings& settings) {
  const fem::TetMesh& m = file.mesh;
  if (m.tets.empty()) return "a mesh without tetrahedra";
  if (m.layer.size() != m.tets.size()) return "a layer count unlike the tetrahedra's";
  const auto n = static_cast<std::int32_t>(m.node_count());
  for (Eigen::Index i = 0; i < m.nodes.cols(); ++i)
    if (!m.nodes.col(i).allFinite()) return "node " + std::to_string(i) + " is not finite";
  const auto inside = [&](const auto& cells, const char* what) -> std::string {
    for (const auto& c : cells)
      for (const std::int32_t v : c)
        if (v < 0 || v >= n)
          return std::string(what) + " uses node " + std::to_string(v) + " of " + std::to_string(n);
    return "";
  };
  for (const std::string& bad : {inside(m.tets, "a tetrahedron"), inside(m.ground, "a ground face"),
                                 inside(m.truncation, "a truncation face")})
    if (!bad.empty()) return bad;
  for (std::size_t e = 0; e < m.tets.size(); ++e) {
    // Positively oriented (read_tets turns the mirrored ones); a flat one (volume 0, or NaN
    // when its extent overflows) is the stiffness assembly's to refuse (elasticity.cpp), which
    // this target does not run.
    if (fem::tet_volume(m, m.tets[e]) < 0.0)
      return "tetrahedron " + std::to_string(e) + " has the volume " +
             std::to_string(fem::tet_volume(m, m.tets[e]));
    if (m.layer[e] > settings.layers.size())
      return "tetrahedron " + std::to_string(e) + " in layer " + std::to_string(m.layer[e]);
  }
  for (const fem::Triangle& f : m.ground)
    for (const std::int32_t v : f)
      if (std::abs(m.nodes(2, v)) > 1e-6) return "a ground face off z = 0";
  // The rectangles' extents (what check_mesh_footprints compares); not their area, which nothing
  // reads and which overflows for triangles with coordinates near 1e308.
  for (const fem::MeshFootprint& p : file.footprints)
    if (!std::isfinite(p.x0) || !std::isfinite(p.x1) || !std::isfinite(p.y0) ||
        !std::isfinite(p.y1) || !(p.x0 <= p.x1) || !(p.y0 <= p.y1))
      return "a footprint rectangle [" + std::to_string(p.x0) + ", " + std::to_string(p.x1) +
             "] x [" + std::to_string(p.y0) + ", " + std::to_string(p.y1) + "]";
  return "";
}

}  // namespace

fem::FemSettings msh_default_settings() {
  fem::FemSettings s;
  s.mesh.max_dofs = nlohmann::json::parse(fem::settings_schema())
                        .at("/properties/mesh/properties/max_dofs/default"_json_pointer)
                        .get<double>();
  return s;
}

namespace {

std::string check_msh(std::string_view file_text) {
  const fs::path path = scratch_dir("msh") / "soil.msh";
  write_file(path, file_text);
  const std::string where = "fem: params/mesh/file: '" + path.string() + "'";
  // A mesh that does not fit the track blames the track and names the file.
  const std::string mismatch =
      "fem: the track's footprints do not fit the mesh of params/mesh/file '" + path.string() + "'";
  const fem::FemSettings settings = msh_default_settings();
  const std::vector<Footprint> track = {{0.0, 0.0, 2.6, 0.26}};
  try {
    const fem::MeshFile file = fem::load_mesh_file(settings, path.string());
    if (std::string bad = check_mesh(file, settings); !bad.empty()) return bad;
    fem::check_mesh_footprints(file, track);
  } catch (const std::invalid_argument& e) {
    if (!starts_with(e.what(), where) && !starts_with(e.what(), mismatch))
      return std::string("refused without the file: ") + e.what();
  } catch (const std::runtime_error& e) {  // gmsh's errors, through gmsh_call
    if (!starts_with(e.what(), where) && !starts_with(e.what(), "fem: gmsh failed to "))
      return std::string("refused without the file: ") + e.what();
  }
  return "";
}

}  // namespace

std::string check_msh_text(std::string_view text) {
  try {
    return check_msh(well_formed_msh(text));
  } catch (const std::exception& e) {
    return std::string("exception escaped: ") + e.what();
  }
}

std::string check_raw_msh_text(std::string_view text) {
  try {
    return check_msh(text);
  } catch (const std::exception& e) {
    return std::string("exception escaped: ") + e.what();
  }
}

}  // namespace rumble::fuzz
