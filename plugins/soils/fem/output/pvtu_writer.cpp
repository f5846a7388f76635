#include "output/pvtu_writer.hpp"

#include <filesystem>
#include <fstream>
#include <stdexcept>

namespace rumble::fem {

namespace {

constexpr const char kParallelSuffix[] = ".pvtu";

}  // namespace

bool is_parallel_snapshot(const std::string& path) {
  const std::string suffix = kParallelSuffix;
  return path.size() > suffix.size() &&
         path.compare(path.size() - suffix.size(), suffix.size(), suffix) == 0;
}

std::string piece_path(const std::string& pvtu, int rank) {
  const std::string suffix = kParallelSuffix;
  if (!is_parallel_snapshot(pvtu))
    throw std::invalid_argument("fem: a snapshot in pieces needs a path ending in .pvtu, got " +
                                pvtu);
  return pvtu.substr(0, pvtu.size() - suffix.size()) + "_" + std::to_string(rank) + ".vtu";
}

void write_pvtu(const std::string& pvtu, int pieces) {
  std::ofstream out(pvtu, std::ios::trunc);
  // The arrays as vtu_writer.cpp writes them in each piece (their order there).
  out << "<?xml version=\"1.0\"?>\n<VTKFile type=\"PUnstructuredGrid\" version=\"1.0\" "
         "byte_order=\"LittleEndian\" header_type=\"UInt64\">\n"
      << "<PUnstructuredGrid GhostLevel=\"0\">\n<PPointData Vectors=\"velocity\">\n"
      << "<PDataArray type=\"Float64\" Name=\"displacement\" NumberOfComponents=\"3\"/>\n"
      << "<PDataArray type=\"Float64\" Name=\"velocity\" NumberOfComponents=\"3\"/>\n"
      << "<PDataArray type=\"UInt8\" Name=\"vtkGhostType\" NumberOfComponents=\"1\"/>\n"
      << "</PPointData>\n<PPoints>\n"
      << "<PDataArray type=\"Float64\" Name=\"Points\" NumberOfComponents=\"3\"/>\n</PPoints>\n";
  for (int r = 0; r < pieces; ++r)
    out << "<Piece Source=\"" << std::filesystem::path(piece_path(pvtu, r)).filename().string()
        << "\"/>\n";
  out << "</PUnstructuredGrid>\n</VTKFile>\n";
  if (!out) throw std::runtime_error("fem: cannot write the field snapshot's index " + pvtu);
}

}  // namespace rumble::fem
