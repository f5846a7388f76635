// What the track participant's statics (track_statics.cpp) and dynamics (track_dynamics.cpp)
// share: the Newton iteration's limits, so that both stop by the same rule, and the rail's
// deflection under a contact point, which both evaluate in their inner loops (inline, so that
// the files being apart costs those loops nothing). Private to the track room: the interface is
// track/track_participant.hpp.
#pragma once

#include <Eigen/Dense>
#include <cstddef>

#include "track/track_structure.hpp"

namespace rumble {

constexpr int kMaxNewtonIterations = 30;
// Newton (dynamics: residual forces; statics: updates) stops below this fraction of its scale:
// far below any physical effect, far above round-off (~1e-16 relative).
constexpr double kRelativeTolerance = 1e-10;

inline double max_abs(const Eigen::VectorXd& v) {
  return v.size() == 0 ? 0.0 : v.cwiseAbs().maxCoeff();
}

// Ref, not const VectorXd&: a column of z_t_ binds without a temporary copy (an allocation).
inline double dot_rail(const TrackStructure::RailPoint& p,
                       const Eigen::Ref<const Eigen::VectorXd>& x) {
  double w = 0.0;
  for (std::size_t k = 0; k < 4; ++k) w += p.shape[k] * x[static_cast<Eigen::Index>(p.dof[k])];
  return w;
}

}  // namespace rumble
