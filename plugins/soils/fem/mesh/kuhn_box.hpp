// A structured mesh for the FEM soil's operator tests and benchmarks: an n x n x n box of cubes
// of edge h [m], each cut into the 6 Kuhn tetrahedra around its main diagonal (docs/numerics.md
// §4.1: the stable step of this mesh with lumped mass is 0.671 h / c_p whatever n). Ground at depth
// 0 (the top faces), truncation on the other five sides. Deterministic, no gmsh.
#pragma once

#include <array>
#include <utility>

#include "mesh/tet_mesh.hpp"

namespace rumble::fem {

/// nx x ny x nz cubes of edge h [m] from `origin` (its ground corner of least x, y).
inline TetMesh kuhn_box(int nx, int ny, int nz, double h, double x0 = 0.0, double y0 = 0.0) {
  TetMesh m;
  const int px = nx + 1, py = ny + 1, pz = nz + 1;
  const auto id = [px, py](int i, int j, int k) {
    return static_cast<std::int32_t>((k * py + j) * px + i);
  };
  m.nodes.resize(3, px * py * pz);
  for (int k = 0; k < pz; ++k)
    for (int j = 0; j < py; ++j)
      for (int i = 0; i < px; ++i) m.nodes.col(id(i, j, k)) << x0 + i * h, y0 + j * h, k * h;
  constexpr std::array<std::array<int, 3>, 6> kAxes = {
      {{0, 1, 2}, {0, 2, 1}, {1, 0, 2}, {1, 2, 0}, {2, 0, 1}, {2, 1, 0}}};
  for (int k = 0; k < nz; ++k)
    for (int j = 0; j < ny; ++j)
      for (int i = 0; i < nx; ++i)
        for (const auto& axes : kAxes) {
          std::array<int, 3> c{i, j, k};
          Tetrahedron t{};
          t[0] = id(c[0], c[1], c[2]);
          for (int s = 0; s < 3; ++s) {
            ++c[axes[s]];
            t[s + 1] = id(c[0], c[1], c[2]);
          }
          if (tet_volume(m, t) < 0.0) std::swap(t[2], t[3]);
          m.tets.push_back(t);
          m.layer.push_back(0);
        }
  // Boundary faces: two triangles per square of each side.
  const auto square = [&](std::int32_t a, std::int32_t b, std::int32_t c, std::int32_t d,
                          bool ground) {
    auto& faces = ground ? m.ground : m.truncation;
    faces.push_back({a, b, c});
    faces.push_back({a, c, d});
  };
  for (int a = 0; a < nx; ++a)
    for (int b = 0; b < ny; ++b) {
      square(id(a, b, 0), id(a + 1, b, 0), id(a + 1, b + 1, 0), id(a, b + 1, 0), true);
      square(id(a, b, nz), id(a + 1, b, nz), id(a + 1, b + 1, nz), id(a, b + 1, nz), false);
    }
  for (int a = 0; a < ny; ++a)
    for (int b = 0; b < nz; ++b) {
      square(id(0, a, b), id(0, a + 1, b), id(0, a + 1, b + 1), id(0, a, b + 1), false);
      square(id(nx, a, b), id(nx, a + 1, b), id(nx, a + 1, b + 1), id(nx, a, b + 1), false);
    }
  for (int a = 0; a < nx; ++a)
    for (int b = 0; b < nz; ++b) {
      square(id(a, 0, b), id(a + 1, 0, b), id(a + 1, 0, b + 1), id(a, 0, b + 1), false);
      square(id(a, ny, b), id(a + 1, ny, b), id(a + 1, ny, b + 1), id(a, ny, b + 1), false);
    }
  return m;
}

/// An n x n x n box of cubes of edge h [m] from the origin.
inline TetMesh kuhn_box(int n, double h) {
  return kuhn_box(n, n, n, h);
}

}  // namespace rumble::fem
