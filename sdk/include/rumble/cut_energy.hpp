// SPDX-License-Identifier: MIT
// rumble/cut_energy.hpp: the energy residual of a macro step at the track/soil cut, the error
// measure of an adaptive macro step (rumble/macro_steps.hpp). Header-only, C++17, standard
// library only. SDK 1.2.
//
// The cut is a power bond (ECCO, Sadjina et al. 2017): the force side (the track) puts out
// footprint forces F [N] and takes footprint velocities [m/s]; the motion side (the soil) takes
// the forces and puts out the velocities v. At a step's end each side has its own view of the
// power through the cut: the track its forces on the velocities it was given (its input at the
// step's end), the soil the forces it was given times its velocities. Their difference dP [W] is
// the power the coupling creates; over a step of length h the energy residual is the trapezoid
//   dE = h / 2 (dP at the step's start + dP at its end)   [J]
// and the work through the cut W = h / 2 |P_start + P_end| (the larger side's).
// Velocities, not displacement increments: with held inputs the track's displacement increment
// over a step is the soil's over the previous one, which differs from this step's by the change
// of step length, so it would count every change of step as an error. (The engine's energies in
// interface.csv use displacement increments, which add up right over a run.)
#ifndef RUMBLE_CUT_ENERGY_HPP
#define RUMBLE_CUT_ENERGY_HPP

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <rumble/plugin.hpp>
#include <string>
#include <vector>

namespace rumble::coupling {

class CutEnergy {
 public:
  /// Finds the groups `force` (output of force_side, input of motion_side) and `velocity`
  /// (output of motion_side, input of force_side); throws CosimHost::Stop when one is missing.
  CutEnergy(const CosimHost& host, std::uint32_t force_side, std::uint32_t motion_side,
            const std::string& force = "footprint_force",
            const std::string& velocity = "footprint_velocity")
      : force_out_(find(host, force_side, RUMBLE_SIDE_OUTPUT, force)),
        force_in_(find(host, motion_side, RUMBLE_SIDE_INPUT, force)),
        velocity_out_(find(host, motion_side, RUMBLE_SIDE_OUTPUT, velocity)),
        velocity_in_(find(host, force_side, RUMBLE_SIDE_INPUT, velocity)),
        n_in_force_side_(input_width(host, force_side)),
        n_in_motion_side_(input_width(host, motion_side)) {
    if (force_out_.count != velocity_out_.count || force_in_.count != force_out_.count ||
        velocity_in_.count != velocity_out_.count) {
      throw CosimHost::Stop(RUMBLE_ERROR, "the groups '" + force + "' and '" + velocity +
                                              "' of the cut do not have the same size");
    }
  }

  /// The state at the run's start: the motion side's outputs are the velocities both sides see,
  /// the force side's the forces.
  void start(const std::vector<double>& force_side_out,
             const std::vector<double>& motion_side_out) {
    double p = 0.0;
    for (std::size_t i = 0; i < force_out_.count; ++i)
      p += force_side_out[force_out_.offset + i] * motion_side_out[velocity_out_.offset + i];
    last_ = {p, p};
  }

  /// A step of h [s] just taken: each side's input waveform (coefficients coeff[k n_in + i],
  /// k = 0..order, in tau = (s - t) / h; its value at the step's end is their sum) and its new
  /// outputs. Returns the step's energy residual [J], the force side's minus the motion side's.
  double step(double h, const std::vector<double>& force_side_in, std::uint32_t force_side_order,
              const std::vector<double>& force_side_out, const std::vector<double>& motion_side_in,
              std::uint32_t motion_side_order, const std::vector<double>& motion_side_out) {
    Power now;
    for (std::size_t i = 0; i < force_out_.count; ++i) {
      now.track +=
          force_side_out[force_out_.offset + i] *
          at_end(force_side_in, force_side_order, n_in_force_side_, velocity_in_.offset + i);
      now.soil +=
          at_end(motion_side_in, motion_side_order, n_in_motion_side_, force_in_.offset + i) *
          motion_side_out[velocity_out_.offset + i];
    }
    before_ = last_;
    work_before_ = work_;
    work_ = 0.5 * h * std::max(std::abs(last_.track + now.track), std::abs(last_.soil + now.soil));
    const double residual = 0.5 * h * ((last_.track - last_.soil) + (now.track - now.soil));
    last_ = now;
    return residual;
  }

  /// The work through the cut over the last step [J] (the larger side's).
  double work() const { return work_; }

  /// Forgets the last step (a scheme that takes it again).
  void undo() {
    last_ = before_;
    work_ = work_before_;
  }

 private:
  struct Power {
    double track = 0.0, soil = 0.0;  // W, each side's view
  };
  static ChannelGroup find(const CosimHost& host, std::uint32_t participant, std::uint32_t side,
                           const std::string& name) {
    for (const ChannelGroup& g : host.groups(participant, side))
      if (g.name == name) return g;
    throw CosimHost::Stop(RUMBLE_ERROR,
                          "the energy at the cut needs the " +
                              std::string(side == RUMBLE_SIDE_OUTPUT ? "output" : "input") +
                              " group '" + name + "' of participant '" +
                              host.participant_name(participant) + "', which it does not have");
  }
  static std::size_t input_width(const CosimHost& host, std::uint32_t participant) {
    std::size_t n = 0;
    for (const ChannelGroup& g : host.groups(participant, RUMBLE_SIDE_INPUT))
      n = std::max(n, g.offset + g.count);
    return n;
  }
  static double at_end(const std::vector<double>& coeff, std::uint32_t order, std::size_t n,
                       std::size_t i) {
    double sum = 0.0;
    for (std::uint32_t k = 0; k <= order; ++k) sum += coeff[k * n + i];
    return sum;
  }

  ChannelGroup force_out_, force_in_, velocity_out_, velocity_in_;
  std::size_t n_in_force_side_, n_in_motion_side_;
  Power last_, before_;                    // at the last step's end, and before it
  double work_ = 0.0, work_before_ = 0.0;  // J
};

}  // namespace rumble::coupling

#endif  // RUMBLE_CUT_ENERGY_HPP
