// Surface receivers' peak particle velocity on the FEM soil through its C table, for the
// mesh-refinement checks (ppv_convergence_test.cpp in the default suite, validation_test.cpp with
// finer meshes): the same loading on meshes that differ only by their element size.
#pragma once

#include <gtest/gtest.h>
#include <rumble/abi.h>

#include <algorithm>
#include <cmath>
#include <nlohmann/json.hpp>
#include <vector>

#include "soil_harness.hpp"

namespace rumble::test {

/// The peak vertical velocity of four surface receivers at the same distance from the centre of
/// a square footprint, on its two axes both ways (by symmetry the same PPV in the continuum; on
/// an unstructured mesh each sees its own neighbourhood: their spread measures the mesh's
/// irregular part of the error).
struct RingPpv {
  std::vector<double> ppv;  // m/s: largest |v_z| of each receiver
  double mean() const {
    double s = 0.0;
    for (double p : ppv) s += p;
    return s / static_cast<double>(ppv.size());
  }
  double spread() const {  // largest - smallest
    const auto [lo, hi] = std::minmax_element(ppv.begin(), ppv.end());
    return *hi - *lo;
  }
};

/// Stiff soil (E 750 MPa, nu 0.3, rho 1800: c_p 749, c_s 400, c_R 371 m/s, default 2 % damping)
/// in a hemisphere of `radius` [m]; element size h_near within 5 m of the footprint and up to
/// 2 h_near beyond (every size scales with h_near); a 0.6 x 0.6 m footprint at the centre loaded
/// by a force rising to 10 kN over `rise` [s] as a half cosine, then held (piecewise linear over
/// 1 ms macro steps: the same loading on every mesh); receivers on the surface at `distance` [m]
/// on the x and y axes, recorded at every sub-step until t_end [s].
inline RingPpv ring_ppv(double h_near, double distance, double radius, double rise, double t_end) {
  const nlohmann::json params = {
      {"E", 750e6},
      {"nu", 0.3},
      {"rho", 1800.0},
      {"mesh",
       {{"radius", radius}, {"h_near", h_near}, {"h_max", 2.0 * h_near}, {"near_distance", 5.0}}}};
  TestSoil soil("fem", params.dump());
  soil.accept_layout({{0.0, 0.0, 0.6, 0.6}});
  const std::vector<rumble_probe> probes = {{"+x", distance, 0.0, 0.0},
                                            {"-x", -distance, 0.0, 0.0},
                                            {"+y", 0.0, distance, 0.0},
                                            {"-y", 0.0, -distance, 0.0}};
  EXPECT_EQ(soil.api().set_probes(soil.self(), probes.data(), probes.size(), 0.0), RUMBLE_OK);
  soil.initialize(VectorXd::Zero(1));
  const double H = 1e-3;
  const auto force = [rise](double t) {
    return t < rise ? 0.5e4 * (1.0 - std::cos(M_PI * t / rise)) : 1e4;
  };
  RingPpv ring;
  ring.ppv.assign(probes.size(), 0.0);
  soil.drive_probes(force, H, t_end, probes.size(), [&](double, std::size_t p, const double* v) {
    ring.ppv[p] = std::max(ring.ppv[p], std::abs(v[2]));
  });
  return ring;
}

/// Observed order of convergence from three solutions on sizes h, h / r, h / r^2:
/// log(|p1 - p2| / |p2 - p3|) / log(r).
inline double observed_order(double p1, double p2, double p3, double r) {
  return std::log(std::abs(p1 - p2) / std::abs(p2 - p3)) / std::log(r);
}

/// Least-squares fit of p(h) = p_inf + c h^order to solutions on several sizes, the order
/// scanned over [0.5, 5] in steps of 0.01 (p_inf and c linear for each order).
struct OrderFit {
  double order = 0.0, p_inf = 0.0, c = 0.0, rms = 0.0;  // rms of the residuals
};
inline OrderFit fit_order(const std::vector<double>& h, const std::vector<double>& p) {
  OrderFit best;
  best.rms = INFINITY;
  const double n = static_cast<double>(h.size());
  for (int k = 50; k <= 500; ++k) {
    const double order = 0.01 * k;
    double sx = 0.0, sy = 0.0, sxx = 0.0, sxy = 0.0;
    for (std::size_t i = 0; i < h.size(); ++i) {
      const double x = std::pow(h[i], order);
      sx += x;
      sy += p[i];
      sxx += x * x;
      sxy += x * p[i];
    }
    OrderFit f;
    f.order = order;
    f.c = (n * sxy - sx * sy) / (n * sxx - sx * sx);
    f.p_inf = (sy - f.c * sx) / n;
    double r2 = 0.0;
    for (std::size_t i = 0; i < h.size(); ++i)
      r2 += std::pow(p[i] - f.p_inf - f.c * std::pow(h[i], order), 2);
    f.rms = std::sqrt(r2 / n);
    if (f.rms < best.rms) best = f;
  }
  return best;
}

}  // namespace rumble::test
