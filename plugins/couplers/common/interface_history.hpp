// Shared by the explicit couplers: the last two samples of each participant's outputs and the
// waveforms built from them (order 0: hold the last value; order 1: linear extrapolation from
// the last two, or linear interpolation between the last and the newest).
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <rumble/plugin.hpp>
#include <vector>

namespace rumble::couplers {

class InterfaceHistory {
 public:
  InterfaceHistory(const CosimHost& host, std::uint32_t participant)
      : host_(host),
        participant_(participant),
        current_(host.output_size(participant)),
        previous_(current_.size()) {}

  std::size_t size() const { return current_.size(); }
  /// Reads the participant's outputs now; the former ones become the previous sample.
  void sample() {
    previous_.swap(current_);
    host_.get_output(participant_, current_);
    if (samples_ == 0) previous_ = current_;
    have_previous_ = ++samples_ >= 2;
  }
  const std::vector<double>& current() const { return current_; }

  /// Waveform over the coming step from the samples at t - H and t (order 0 or 1).
  void extrapolated(std::uint32_t order, std::vector<double>& coeff,
                    std::uint32_t& out_order) const {
    const std::size_t n = current_.size();
    out_order = have_previous_ ? order : 0;
    coeff.assign((out_order + 1) * n, 0.0);
    for (std::size_t i = 0; i < n; ++i) {
      coeff[i] = current_[i];
      if (out_order == 1) coeff[n + i] = current_[i] - previous_[i];
    }
  }
  /// Waveform over the step just taken by the other participant: from previous() to current().
  void interpolated(std::uint32_t order, std::vector<double>& coeff,
                    std::uint32_t& out_order) const {
    const std::size_t n = current_.size();
    out_order = order;
    coeff.assign((order + 1) * n, 0.0);
    for (std::size_t i = 0; i < n; ++i) {
      if (order == 0) {
        coeff[i] = current_[i];
      } else {
        coeff[i] = previous_[i];
        coeff[n + i] = current_[i] - previous_[i];
      }
    }
  }
  /// Relative interface residual over the first `channels` outputs: the largest difference
  /// between the value another participant used at the end of the step (coeff, order) and the
  /// value produced, over the largest produced magnitude (0 when everything is zero).
  double relative_mismatch(const std::vector<double>& coeff, std::uint32_t order,
                           std::size_t channels) const {
    const std::size_t n = current_.size();
    double diff = 0.0, scale = 0.0;
    for (std::size_t i = 0; i < channels; ++i) {
      double used = 0.0;
      for (std::uint32_t k = 0; k <= order; ++k) used += coeff[k * n + i];
      diff = std::max(diff, std::abs(used - current_[i]));
      scale = std::max(scale, std::abs(current_[i]));
    }
    return scale > 0.0 ? diff / scale : diff;
  }

 private:
  const CosimHost& host_;
  std::uint32_t participant_;
  std::vector<double> current_, previous_;
  bool have_previous_ = false;
  int samples_ = 0;
};

}  // namespace rumble::couplers
