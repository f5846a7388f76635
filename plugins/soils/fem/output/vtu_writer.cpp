#include "output/vtu_writer.hpp"

#include <cstdint>
#include <fstream>
#include <stdexcept>
#include <vector>

namespace rumble::fem {

namespace {

/// One data array of the appended section: its header and its bytes.
struct Block {
  std::string header;
  std::vector<char> bytes;
};

template <class T>
Block block(const std::string& type, const std::string& name, int components,
            const std::vector<T>& data) {
  Block b;
  b.header = "<DataArray type=\"" + type + "\" Name=\"" + name + "\" NumberOfComponents=\"" +
             std::to_string(components) + "\" format=\"appended\"";
  const auto* p = reinterpret_cast<const char*>(data.data());
  b.bytes.assign(p, p + data.size() * sizeof(T));
  return b;
}

std::vector<double> as_vector(const Eigen::VectorXd& x) {
  return {x.data(), x.data() + x.size()};
}

}  // namespace

void write_vtu(const std::string& path, double t, const TetMesh& mesh,
               const Eigen::VectorXd& displacement, const Eigen::VectorXd& velocity,
               const std::vector<std::uint8_t>* ghosts) {
  const std::size_t n_cells = mesh.tets.size();
  std::vector<double> points(mesh.nodes.data(), mesh.nodes.data() + mesh.nodes.size());
  std::vector<std::int64_t> connectivity, offsets(n_cells);
  connectivity.reserve(4 * n_cells);
  for (std::size_t e = 0; e < n_cells; ++e) {
    for (std::int32_t v : mesh.tets[e]) connectivity.push_back(v);
    offsets[e] = static_cast<std::int64_t>(4 * (e + 1));
  }
  const std::vector<std::uint8_t> types(n_cells, 10);  // VTK_TETRA
  std::vector<Block> point_data = {block("Float64", "displacement", 3, as_vector(displacement)),
                                   block("Float64", "velocity", 3, as_vector(velocity))};
  if (ghosts != nullptr) point_data.push_back(block("UInt8", "vtkGhostType", 1, *ghosts));
  const Block point_block = block("Float64", "Points", 3, points);
  const std::vector<Block> cell_blocks = {block("Int64", "connectivity", 1, connectivity),
                                          block("Int64", "offsets", 1, offsets),
                                          block("UInt8", "types", 1, types)};
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  std::uint64_t offset = 0;
  const auto header = [&](const Block& b) {
    out << b.header << " offset=\"" << offset << "\"/>\n";
    offset += sizeof(std::uint64_t) + b.bytes.size();
  };
  out << "<?xml version=\"1.0\"?>\n<VTKFile type=\"UnstructuredGrid\" version=\"1.0\" "
         "byte_order=\"LittleEndian\" header_type=\"UInt64\">\n<UnstructuredGrid>\n"
      << "<FieldData><DataArray type=\"Float64\" Name=\"TimeValue\" NumberOfTuples=\"1\" "
         "format=\"ascii\">"
      << t << "</DataArray></FieldData>\n"
      << "<Piece NumberOfPoints=\"" << mesh.node_count() << "\" NumberOfCells=\"" << n_cells
      << "\">\n<PointData Vectors=\"velocity\">\n";
  for (const Block& b : point_data) header(b);
  out << "</PointData>\n<Points>\n";
  header(point_block);
  out << "</Points>\n<Cells>\n";
  for (const Block& b : cell_blocks) header(b);
  out << "</Cells>\n</Piece>\n</UnstructuredGrid>\n<AppendedData encoding=\"raw\">\n_";
  const auto bytes = [&](const Block& b) {
    const std::uint64_t size = b.bytes.size();
    out.write(reinterpret_cast<const char*>(&size), sizeof size);
    out.write(b.bytes.data(), static_cast<std::streamsize>(b.bytes.size()));
  };
  for (const Block& b : point_data) bytes(b);
  bytes(point_block);
  for (const Block& b : cell_blocks) bytes(b);
  out << "\n</AppendedData>\n</VTKFile>\n";
  if (!out) throw std::runtime_error("fem: cannot write the field snapshot " + path);
}

}  // namespace rumble::fem
