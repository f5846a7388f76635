#include "track/track_structure.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "track/rail_beam.hpp"

namespace rumble {
namespace {
// w_i, theta_i, sleeper_i, w_{i+1}, theta_{i+1}: the farthest coupling is 4 positions away.
constexpr std::size_t kHalfBandwidth = 4;
}  // namespace

TrackStructure::TrackStructure(const TrackConfig& c) : config_(c) {
  const int n_el = c.element_count();
  const std::size_t n_nodes = static_cast<std::size_t>(n_el) + 1;
  rail_w_dof_.resize(n_nodes);
  sleeper_dof_.resize(static_cast<std::size_t>(c.sleeper_count));
  sleeper_node_.resize(sleeper_dof_.size());
  std::size_t next = 0;
  for (std::size_t node = 0; node < n_nodes; ++node) {
    rail_w_dof_[node] = next;
    next += 2;
    const long rel =
        static_cast<long>(node) - static_cast<long>(c.overhang_bays) * c.elements_per_bay;
    if (rel >= 0 && rel % c.elements_per_bay == 0 && rel / c.elements_per_bay < c.sleeper_count) {
      const auto s = static_cast<std::size_t>(rel / c.elements_per_bay);
      sleeper_dof_[s] = next++;
      sleeper_node_[s] = node;
    }
  }
  n_dof_ = next;
  mass_ = BandedSymmetric(n_dof_, kHalfBandwidth);
  damping_ = BandedSymmetric(n_dof_, kHalfBandwidth);
  stiffness_ = BandedSymmetric(n_dof_, kHalfBandwidth);

  const double L = c.element_length();
  const auto ke = rail_beam::stiffness(c.rail_E * c.rail_I, L);
  const auto me = rail_beam::mass(c.rail_mass_per_length, L);
  for (int e = 0; e < n_el; ++e) {
    const std::size_t a = rail_w_dof_[static_cast<std::size_t>(e)];
    const std::size_t b = rail_w_dof_[static_cast<std::size_t>(e) + 1];
    const std::array<std::size_t, 4> dof{a, a + 1, b, b + 1};
    for (std::size_t i = 0; i < 4; ++i) {
      for (std::size_t j = 0; j <= i; ++j) {
        // Symmetric storage: each (i, j) pair is added once.
        stiffness_.add(dof[i], dof[j], ke[i][j]);
        mass_.add(dof[i], dof[j], me[i][j]);
        damping_.add(dof[i], dof[j], c.rayleigh_alpha * me[i][j] + c.rayleigh_beta * ke[i][j]);
      }
    }
  }
  for (std::size_t s = 0; s < sleeper_dof_.size(); ++s) {
    const std::size_t w = rail_w_dof_[sleeper_node_[s]], d = sleeper_dof_[s];
    // railpad between rail and sleeper
    stiffness_.add(w, w, c.pad_k);
    stiffness_.add(d, d, c.pad_k);
    stiffness_.add(w, d, -c.pad_k);
    damping_.add(w, w, c.pad_c);
    damping_.add(d, d, c.pad_c);
    damping_.add(w, d, -c.pad_c);
    // ballast between sleeper and footprint (footprint motion enters as a force)
    stiffness_.add(d, d, c.ballast_k);
    damping_.add(d, d, c.ballast_c);
    mass_.add(d, d, c.sleeper_mass);
  }
}

TrackStructure::RailPoint TrackStructure::rail_point(double x) const {
  const double L = config_.element_length();
  const double s = (x - config_.rail_start()) / L;
  const int n_el = config_.element_count();
  if (!(s >= 0.0) || s > n_el) {
    throw std::out_of_range("x = " + std::to_string(x) + " m is off the rail [" +
                            std::to_string(config_.rail_start()) + ", " +
                            std::to_string(config_.rail_end()) + "] m");
  }
  const int e = std::min(static_cast<int>(std::floor(s)), n_el - 1);
  const double xi = s - e;
  const std::size_t a = rail_w_dof_[static_cast<std::size_t>(e)];
  const std::size_t b = rail_w_dof_[static_cast<std::size_t>(e) + 1];
  return RailPoint{{a, a + 1, b, b + 1}, rail_beam::shape(xi, L)};
}

}  // namespace rumble
