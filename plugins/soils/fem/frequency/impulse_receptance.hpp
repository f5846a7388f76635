// The footprint receptance H(f) from impulse responses: footprint j is loaded by a Hann pulse
// of length 1 / f_top and the soil stepped explicitly (the same central differences, lumped mass
// and boundary as a run) for `duration` seconds from rest; the area-averaged vertical motion of
// every footprint is recorded at every step, and
//   H_ij(f) = sum_k u_i(t_k) e^{-i w t_k} / sum_k F(t_k) e^{-i w t_k}
// (e^{+i w t}: u = H F, as receptance.hpp). One run per footprint gives its column at every
// frequency, where receptance.hpp factors the whole complex matrix once per frequency (13
// minutes per frequency at 1.6e5 DOFs, docs/fem-soil.md section 5): on large meshes, for the
// dozen or more frequencies a calibration asks for, the runs cost far less. The record must
// outlast the response (the pulse's motion has left through the boundary or been damped):
// what is cut off is the error at low frequency; see decay_ratio().
#pragma once

#include <complex>
#include <functional>
#include <vector>

#include "boundary/static_far_field.hpp"
#include "operator/footprint_loads.hpp"
#include "time/explicit_solver.hpp"

namespace rumble::fem {

class ImpulseReceptance {
 public:
  /// Runs the n impulse responses at once (n = weights.size()) with steps of dt [s] over
  /// duration [s]; the pulse (0.5 / f_top long) carries energy to 4 f_top, half its peak at
  /// 2 f_top [Hz]. progress(j, k) is called before step k of footprint j's run, every 64 steps (and
  /// may throw to stop).
  /// far (nullptr: none): the far field's traction follows each run's pulse through a lag of
  /// tau [s] (FarFieldLag, docs/fem-soil.md §3.2), as in the soil's own steps.
  ImpulseReceptance(const ExplicitSolver& op, const FootprintWeights& weights, double dt,
                    double duration, double f_top,
                    const std::function<void(std::size_t, std::size_t)>& progress,
                    const StaticFarField* far = nullptr, double tau = 0.0);

  /// H(f), n x n column-major [m/N]. Throws std::invalid_argument beyond the pulse's band.
  void at(double f_hz, std::complex<double>* H) const;
  /// The largest footprint displacement in the record's last tenth over the largest in the whole
  /// record, over all runs [-]: what the record cut off, roughly (small: the response had died).
  double decay_ratio() const { return decay_ratio_; }
  std::size_t samples() const { return force_.size(); }

 private:
  std::size_t n_;
  double dt_;
  double f_top_;  // Hz: where the pulse's spectrum is about a sixth of its peak (the refusal)
  std::vector<double> force_;   // F(t_k) [N], k = 1..N
  std::vector<double> motion_;  // u_i(t_k) of run j at [(j n + i) N + k] [m]
  double decay_ratio_ = 0.0;
};

}  // namespace rumble::fem
