// A structured mesh for the FEM soil's operator tests and benchmarks: an n x n x n box of cubes
// of edge h [m], each cut into the 6 Kuhn tetrahedra around its main diagonal (numerics.md §3.1:
// the stable step of this mesh with lumped mass is 0.671 h / c_p whatever n). Ground at depth 0
// (the top faces), truncation on the other five sides. Deterministic, no gmsh.
#pragma once

#include <array>
#include <utility>

#include "tet_mesh.hpp"

namespace rumble::fem {

inline TetMesh kuhn_box(int n, double h) {
  TetMesh m;
  const int p = n + 1;
  const auto id = [p](int i, int j, int k) {
    return static_cast<std::int32_t>((k * p + j) * p + i);
  };
  m.nodes.resize(3, p * p * p);
  for (int k = 0; k < p; ++k)
    for (int j = 0; j < p; ++j)
      for (int i = 0; i < p; ++i) m.nodes.col(id(i, j, k)) << i * h, j * h, k * h;
  constexpr std::array<std::array<int, 3>, 6> kAxes = {
      {{0, 1, 2}, {0, 2, 1}, {1, 0, 2}, {1, 2, 0}, {2, 0, 1}, {2, 1, 0}}};
  for (int k = 0; k < n; ++k)
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i)
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
  for (int a = 0; a < n; ++a)
    for (int b = 0; b < n; ++b) {
      square(id(a, b, 0), id(a + 1, b, 0), id(a + 1, b + 1, 0), id(a, b + 1, 0), true);
      square(id(a, b, n), id(a + 1, b, n), id(a + 1, b + 1, n), id(a, b + 1, n), false);
      square(id(0, a, b), id(0, a + 1, b), id(0, a + 1, b + 1), id(0, a, b + 1), false);
      square(id(n, a, b), id(n, a + 1, b), id(n, a + 1, b + 1), id(n, a, b + 1), false);
      square(id(a, 0, b), id(a + 1, 0, b), id(a + 1, 0, b + 1), id(a, 0, b + 1), false);
      square(id(a, n, b), id(a + 1, n, b), id(a + 1, n, b + 1), id(a, n, b + 1), false);
    }
  return m;
}

}  // namespace rumble::fem
