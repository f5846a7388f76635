// The linear track: rail beam elements, railpads, sleepers and ballast, with DOFs numbered along
// the rail (w_i, theta_i, then the sleeper under node i, if any) so that M, C and K are banded.
// The ballast's lower end is the footprint: it does not appear as a DOF; its motion (u, v from
// the soil) enters as the force k_b u + c_b v on the sleeper.
#pragma once

#include <array>
#include <cstddef>
#include <vector>

#include "track/banded_matrix.hpp"
#include "track_spec/track_config.hpp"

namespace rumble {

class TrackStructure {
 public:
  explicit TrackStructure(const TrackConfig& config);

  const TrackConfig& config() const { return config_; }
  std::size_t dof_count() const { return n_dof_; }
  std::size_t node_count() const { return rail_w_dof_.size(); }
  std::size_t sleeper_count() const { return sleeper_dof_.size(); }
  std::size_t rail_w_dof(std::size_t node) const { return rail_w_dof_[node]; }
  std::size_t sleeper_dof(std::size_t sleeper) const { return sleeper_dof_[sleeper]; }
  std::size_t sleeper_node(std::size_t sleeper) const { return sleeper_node_[sleeper]; }

  const BandedSymmetric& mass() const { return mass_; }
  const BandedSymmetric& damping() const { return damping_; }
  const BandedSymmetric& stiffness() const { return stiffness_; }

  /// The rail at x [m]: the 4 DOFs of the element containing x and their shape values.
  struct RailPoint {
    std::array<std::size_t, 4> dof;
    std::array<double, 4> shape;
  };
  /// Throws std::out_of_range when x is not on the rail.
  RailPoint rail_point(double x) const;
  bool on_rail(double x) const { return x >= config_.rail_start() && x <= config_.rail_end(); }

 private:
  TrackConfig config_;
  std::size_t n_dof_ = 0;
  std::vector<std::size_t> rail_w_dof_;    // per rail node; theta is rail_w_dof + 1
  std::vector<std::size_t> sleeper_dof_;   // per sleeper
  std::vector<std::size_t> sleeper_node_;  // rail node above each sleeper
  BandedSymmetric mass_, damping_, stiffness_;
};

}  // namespace rumble
