// SPDX-License-Identifier: MIT
// rumble/plugin/soil.hpp (part of rumble/plugin.hpp): the Soil base class, the probes and their
// samples, and what a soil exports (matrices, waveforms).
#ifndef RUMBLE_PLUGIN_SOIL_HPP
#define RUMBLE_PLUGIN_SOIL_HPP

#include <rumble/abi.h>

#include <algorithm>
#include <complex>
#include <cstddef>
#include <cstdint>
#include <rumble/plugin/component.hpp>
#include <string>
#include <vector>

namespace rumble {

using Footprint = rumble_footprint;
using Receiver = rumble_receiver;

/// A receiver point (ABI 1.1): name, position [m], depth below the surface [m] (>= 0).
struct Probe {
  std::string name;
  double x = 0.0, y = 0.0, depth = 0.0;
};

/// Samples of every probe's motion, recorded by a soil inside advance() and taken by the host
/// after it: per sample a time [s] and n_probes x RUMBLE_PROBE_VALUES values (vx, vy, vz [m/s],
/// ux, uy, uz [m], z down +). Capacity is kept between steps: no allocation in steady state.
class ProbeSamples {
 public:
  void reset(std::size_t n_probes) {
    n_probes_ = n_probes;
    times_.clear();
    values_.clear();
  }
  std::size_t probes() const { return n_probes_; }
  std::size_t pending() const { return times_.size(); }
  /// Forgets the samples not yet taken (the boundary calls it on restore: they belong to a step
  /// that is being taken again).
  void drop_pending() {
    times_.clear();
    values_.clear();
  }
  /// values: n_probes x RUMBLE_PROBE_VALUES.
  void push(double t, const double* values) {
    times_.push_back(t);
    values_.insert(values_.end(), values, values + n_probes_ * RUMBLE_PROBE_VALUES);
  }
  /// Moves up to capacity samples out, oldest first; returns how many.
  std::size_t take(double* times, double* values, std::size_t capacity) {
    const std::size_t n = capacity < times_.size() ? capacity : times_.size();
    const std::size_t width = n_probes_ * RUMBLE_PROBE_VALUES;
    for (std::size_t i = 0; i < n; ++i) times[i] = times_[i];
    for (std::size_t i = 0; i < n * width; ++i) values[i] = values_[i];
    times_.erase(times_.begin(), times_.begin() + static_cast<std::ptrdiff_t>(n));
    values_.erase(values_.begin(), values_.begin() + static_cast<std::ptrdiff_t>(n * width));
    return n;
  }

 private:
  std::size_t n_probes_ = 0;
  std::vector<double> times_, values_;
};

/// A compressed-sparse-column matrix (ABI 1.1 rumble_csc), 0-based, rows sorted per column.
struct CscMatrix {
  std::uint64_t rows = 0, cols = 0;
  std::vector<std::int64_t> col_ptr;  // cols + 1
  std::vector<std::int64_t> row_index;
  std::vector<double> values;
};

/// A force waveform over one macro step (see rumble_waveform).
class Waveform {
 public:
  explicit Waveform(const rumble_waveform& w) : w_(w) {}
  std::size_t channels() const { return static_cast<std::size_t>(w_.n); }
  /// Value of channel i at tau = (t - t_step) / H in [0, 1].
  double at(std::size_t i, double tau) const {
    double value = 0.0;
    for (int k = static_cast<int>(w_.order); k >= 0; --k)
      value = value * tau + w_.coeff[static_cast<std::size_t>(k) * w_.n + i];
    return value;
  }

 private:
  rumble_waveform w_;
};

/// Soil participant: see rumble_soil_api in abi.h.
class Soil : public Component {
 public:
  static constexpr rumble_kind kKind = RUMBLE_KIND_SOIL;
  virtual void accept_layout(const std::vector<Footprint>& footprints) = 0;
  virtual void initialize(double t0, const double* static_force, double* static_u) = 0;
  virtual void advance(double t, double H, const Waveform& force) = 0;
  virtual void motion(double* u, double* v) const = 0;
  /// Return false when not offered; else fill receptance [m/N], n x n column-major.
  virtual bool frequency_response(double /*f_hz*/, std::complex<double>* /*receptance*/) {
    return false;
  }
  /// ABI 1.0 surface receivers (vertical velocity only); prefer set_probes. Return false when
  /// not offered.
  virtual bool set_receivers(const std::vector<Receiver>& /*receivers*/) { return false; }
  virtual void receiver_velocity(double* /*v*/) const {}
  /// Receivers (ABI 1.1): record these points' motion into samples() from now on, at every
  /// internal step (sample_interval 0) or every sample_interval [s]. Throw for a point outside.
  virtual void set_probes(const std::vector<Probe>& /*probes*/, double /*sample_interval*/) {
    throw std::logic_error("receivers not offered");
  }
  /// Write the fields at time t [s] to path (.vtu).
  virtual void write_fields(double /*t*/, const std::string& /*path*/) {
    throw std::logic_error("field output not offered");
  }
  /// Slowest shear and Rayleigh wave speeds [m/s] of any layer.
  virtual void wave_speeds(double& /*c_s_min*/, double& /*c_r_min*/) const {
    throw std::logic_error("wave speeds not offered");
  }
  /// One matrix of M x'' + C x' + K x = B F (u = B^T x), after accept_layout().
  virtual void linear_matrix(rumble_matrix /*which*/, CscMatrix& /*out*/) {
    throw std::logic_error("linear matrices not offered");
  }
  /// ABI 1.3, after set_probes(): the highest frequency [Hz] this soil carries from the
  /// footprints to each probe (one per probe; 0 where it cannot say), with how it is found in
  /// `rule`. Empty (the default): the soil does not say.
  virtual std::vector<double> probe_resolution(std::string& /*rule*/) const { return {}; }
  /// ABI 1.5, after accept_layout(): the soil's degrees of freedom and its estimate of a run's
  /// peak resident memory [bytes] (0: it cannot say), for the host's account of memory.
  struct Size {
    std::uint64_t dofs = 0;
    double peak_bytes = 0.0;
  };
  virtual Size size() const { return {}; }
  /// ABI 1.5: the host's static iteration is over; free what only the statics needed (a later
  /// initialize() may still come). Nothing by default.
  virtual void statics_done() {}
  /// Where advance() records probe samples (sized by the boundary at set_probes()).
  ProbeSamples& samples() { return samples_; }

 private:
  ProbeSamples samples_;
};

}  // namespace rumble

#endif  // RUMBLE_PLUGIN_SOIL_HPP
