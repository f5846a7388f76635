// SPDX-License-Identifier: MIT
// rumble/coupling.hpp: building blocks for coupling schemes (couplers), the same ones the
// in-tree gauss_seidel and jacobi use. Stable from SDK 1.1: names and behaviour change only with
// a new major version. Header-only, C++17, standard library only.
//
//   macro_step_count/start/length  equal macro steps computed from the step index (no drift)
//   OutputHistory    a participant's outputs at the ends of its last final steps, with times,
//                    and the polynomial waveforms extrapolated (order 0..2) or interpolated
//                    from them; steps may vary in length (extrapolation uses the sample times)
//   Link             which output channel of one participant feeds which input channel of
//                    another, by channel group name ("footprint_force", ...), so a scheme never
//                    assumes a layout
//   GroupResiduals   the interface residual per output group: absolute, and relative to the
//                    largest magnitude the group has had in the run so far (not at this instant);
//                    measure_trial() for an iterate that may not be final
#ifndef RUMBLE_COUPLING_HPP
#define RUMBLE_COUPLING_HPP

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <rumble/plugin.hpp>
#include <string>
#include <vector>

namespace rumble::coupling {

// ------------------------------------------------------------------ macro steps

/// Number of macro steps of at most H [s] covering [t0, t_end]; a final partial step ends
/// exactly at t_end.
inline std::size_t macro_step_count(double t0, double t_end, double H) {
  return static_cast<std::size_t>(std::ceil((t_end - t0) / H - 1e-9));
}
/// Start of step k: t0 + k H, computed from k (no accumulated round-off).
inline double macro_step_start(double t0, double H, std::size_t k) {
  return t0 + static_cast<double>(k) * H;
}
/// Length of step k: H, or less for the final one.
inline double macro_step_length(double t0, double t_end, double H, std::size_t k) {
  return std::fmin(H, t_end - macro_step_start(t0, H, k));
}

/// Stops the run because participant `who` refused the step [t, t + h] (DISCARD) and the scheme
/// cannot retry it (why). Throws CosimHost::Stop with a message that says what to change.
[[noreturn]] inline void refused_step(const CosimHost& host, double t, double h, std::uint32_t who,
                                      const std::string& why) {
  throw CosimHost::Stop(RUMBLE_ERROR,
                        "participant '" + host.participant_name(who) +
                            "' refused the step starting at t = " + std::to_string(t) + " s of " +
                            std::to_string(h) + " s (DISCARD) and it cannot be retried: " + why +
                            "; reduce time.macro_step or raise the participant's "
                            "own step limit");
}

// ------------------------------------------------------------------ history and waveforms

/// Highest polynomial orders OutputHistory implements: extrapolate() and interpolate().
inline constexpr std::uint32_t kMaxExtrapolationOrder = 2;
inline constexpr std::uint32_t kMaxInterpolationOrder = 1;

/// JSON schema of a coupler's "extrapolation" property (an order in [0, kMaxExtrapolationOrder],
/// default `order`); `role` says what is extrapolated in this coupler, as the description's
/// first words. Declared here once, so that the range follows what OutputHistory implements.
inline std::string extrapolation_schema(std::uint32_t order, const std::string& role) {
  return R"("extrapolation": {"type": "integer", "minimum": 0, "maximum": )" +
         std::to_string(kMaxExtrapolationOrder) + R"(, "default": )" + std::to_string(order) +
         R"(, "description": ")" + role + R"( (0 = held constant); [0, )" +
         std::to_string(kMaxExtrapolationOrder) + R"(]: the orders implemented"})";
}

/// JSON schema of a coupler's "order" property: which participant advances first in a macro
/// step ("track_first", the seed paper's, or "soil_first"); `role` is its description.
inline std::string order_schema(const std::string& role) {
  return R"("order": {"enum": ["track_first", "soil_first"], "default": "track_first", )"
         R"("description": ")" +
         role + R"("})";
}

/// JSON schema of a coupler's "interpolation" property (an order in
/// [0, kMaxInterpolationOrder], default `order`), as extrapolation_schema().
inline std::string interpolation_schema(std::uint32_t order, const std::string& role) {
  return R"("interpolation": {"type": "integer", "minimum": 0, "maximum": )" +
         std::to_string(kMaxInterpolationOrder) + R"(, "default": )" + std::to_string(order) +
         R"(, "description": ")" + role + R"(; [0, )" + std::to_string(kMaxInterpolationOrder) +
         R"(]: the orders implemented"})";
}

/// The last three final outputs of one participant, with their times.
class OutputHistory {
 public:
  static constexpr std::size_t kDepth = kMaxExtrapolationOrder + 1;

  OutputHistory(const CosimHost& host, std::uint32_t participant)
      : host_(host), participant_(participant), scratch_(host.output_size(participant)) {
    for (auto& v : values_) v.assign(scratch_.size(), 0.0);
  }
  std::size_t size() const { return scratch_.size(); }
  std::size_t samples() const { return count_; }
  std::uint32_t participant() const { return participant_; }

  /// Reads the participant's outputs now, at time t [s], as the newest sample.
  void sample(double t) {
    host_.get_output(participant_, scratch_);
    push(t, scratch_);
  }
  /// Adds outputs read elsewhere (e.g. before the step was known to be final).
  void push(double t, const std::vector<double>& y) {
    head_ = (head_ + 1) % kDepth;
    times_[head_] = t;
    std::copy(y.begin(), y.end(), values_[head_].begin());
    count_ = std::min(count_ + 1, kDepth);
  }
  /// Sample k steps back (0: newest).
  const std::vector<double>& latest(std::size_t k = 0) const {
    return values_[(head_ + kDepth - k) % kDepth];
  }
  double time(std::size_t k = 0) const { return times_[(head_ + kDepth - k) % kDepth]; }

  /// Waveform over [t, t + h] extrapolated from the newest samples by a polynomial of the given
  /// order (0..2; lower while fewer samples exist), as coefficients in tau = (s - t) / h:
  /// coeff[k n + i], k = 0..order used. Returns the order used.
  std::uint32_t extrapolate(std::uint32_t order, double t, double h,
                            std::vector<double>& coeff) const {
    const std::size_t n = size();
    const std::uint32_t used =
        std::min<std::uint32_t>(order, static_cast<std::uint32_t>(count_ > 0 ? count_ - 1 : 0));
    coeff.assign((used + 1) * n, 0.0);
    const std::vector<double>& y2 = latest(0);
    if (used == 0) {
      std::copy(y2.begin(), y2.end(), coeff.begin());
      return used;
    }
    // Newton form through (t2, y2), (t1, y1)[, (t0, y0)], evaluated at s = t + tau h.
    const double t2 = time(0), t1 = time(1);
    const double a = t - t2, b = t - t1;
    const std::vector<double>& y1 = latest(1);
    for (std::size_t i = 0; i < n; ++i) {
      const double d1 = (y2[i] - y1[i]) / (t2 - t1);
      double d2 = 0.0;
      if (used == 2) {
        const double t0 = time(2);
        const double d1_prev = (y1[i] - latest(2)[i]) / (t1 - t0);
        d2 = (d1 - d1_prev) / (t2 - t0);
      }
      coeff[i] = y2[i] + d1 * a + d2 * a * b;
      coeff[n + i] = d1 * h + d2 * (a + b) * h;
      if (used == 2) coeff[2 * n + i] = d2 * h * h;
    }
    return used;
  }

  /// Waveform over the step that ends with `newest` (outputs just produced, not yet a sample):
  /// order 0 holds newest; order 1 is linear from the newest sample to newest. Returns the order.
  std::uint32_t interpolate(std::uint32_t order, const std::vector<double>& newest,
                            std::vector<double>& coeff) const {
    const std::size_t n = size();
    const std::uint32_t used = count_ == 0 ? 0 : std::min<std::uint32_t>(order, 1);
    coeff.assign((used + 1) * n, 0.0);
    for (std::size_t i = 0; i < n; ++i) {
      if (used == 0) {
        coeff[i] = newest[i];
      } else {
        coeff[i] = latest()[i];
        coeff[n + i] = newest[i] - latest()[i];
      }
    }
    return used;
  }

 private:
  const CosimHost& host_;
  std::uint32_t participant_;
  std::array<std::vector<double>, kDepth> values_;
  std::array<double, kDepth> times_{};
  std::size_t head_ = kDepth - 1, count_ = 0;
  std::vector<double> scratch_;
};

// ------------------------------------------------------------------ links

/// Output channels of `from` feeding the input channels of `to`, matched by group name.
class Link {
 public:
  Link(const CosimHost& host, std::uint32_t from, std::uint32_t to)
      : n_out_(host.output_size(from)) {
    const std::vector<ChannelGroup> outs = host.groups(from, RUMBLE_SIDE_OUTPUT);
    for (const ChannelGroup& in : host.groups(to, RUMBLE_SIDE_INPUT)) {
      const auto match = std::find_if(outs.begin(), outs.end(),
                                      [&](const ChannelGroup& o) { return o.name == in.name; });
      if (match == outs.end() || match->count != in.count || match->unit != in.unit) {
        throw CosimHost::Stop(
            RUMBLE_ERROR, "participant '" + host.participant_name(to) + "' needs input group '" +
                              in.name + "' [" + in.unit + "] x " + std::to_string(in.count) +
                              ", which '" + host.participant_name(from) + "' does not output");
      }
      if (source_.size() < in.offset + in.count) source_.resize(in.offset + in.count, 0);
      for (std::size_t i = 0; i < in.count; ++i) source_[in.offset + i] = match->offset + i;
    }
  }
  /// Input waveform of `to` (order, coefficients) from a waveform over `from`'s outputs.
  void map(const std::vector<double>& from_coeff, std::uint32_t order,
           std::vector<double>& to_coeff) const {
    const std::size_t n_in = source_.size();
    to_coeff.resize((order + 1) * n_in);
    for (std::uint32_t k = 0; k <= order; ++k)
      for (std::size_t i = 0; i < n_in; ++i)
        to_coeff[k * n_in + i] = from_coeff[k * n_out_ + source_[i]];
  }

 private:
  std::size_t n_out_;
  std::vector<std::size_t> source_;  // input channel -> output channel
};

// ------------------------------------------------------------------ residuals

/// Interface residual per output group of one participant: the value another participant used
/// at the end of the step (a waveform over these outputs, evaluated at tau = 1) against the value
/// produced. relative = absolute / scale, scale = the largest |value| of the group so far in the
/// run (the initial static values included), so a residual at a zero crossing is not inflated.
class GroupResiduals {
 public:
  GroupResiduals(const CosimHost& host, std::uint32_t participant)
      : groups_(host.groups(participant, RUMBLE_SIDE_OUTPUT)), scale_(groups_.size(), 0.0) {}

  /// Grows each group's scale with these outputs (call with every final sample).
  void observe(const std::vector<double>& y) {
    for (std::size_t g = 0; g < groups_.size(); ++g)
      for (std::size_t i = 0; i < groups_[g].count; ++i)
        scale_[g] = std::max(scale_[g], std::abs(y[groups_[g].offset + i]));
  }
  std::size_t groups() const { return groups_.size(); }
  /// Writes one GroupResidual per group to out[0 .. groups() - 1] (assigned in place, so a
  /// report reused from step to step allocates nothing).
  void measure(const std::vector<double>& used_coeff, std::uint32_t order,
               const std::vector<double>& produced, GroupResidual* out) {
    observe(produced);
    const std::size_t n = produced.size();
    for (std::size_t g = 0; g < groups_.size(); ++g) {
      double worst = 0.0;
      for (std::size_t i = groups_[g].offset; i < groups_[g].offset + groups_[g].count; ++i) {
        double used = 0.0;
        for (std::uint32_t k = 0; k <= order; ++k) used += used_coeff[k * n + i];
        worst = std::max(worst, std::abs(used - produced[i]));
      }
      out[g].group = groups_[g].name;
      out[g].absolute = worst;
      out[g].relative = scale_[g] > 0.0 ? worst / scale_[g] : worst;
      out[g].scale = scale_[g];
    }
  }
  /// As measure(), for outputs that may not be final (an iterate of an iterating scheme): the
  /// scale is the run's so far grown by `produced` for this call only, so measure() on the same
  /// values once they are final gives the same numbers; nothing is observed. (SDK 1.1, appended.)
  void measure_trial(const std::vector<double>& used_coeff, std::uint32_t order,
                     const std::vector<double>& produced, GroupResidual* out) const {
    const std::size_t n = produced.size();
    for (std::size_t g = 0; g < groups_.size(); ++g) {
      double worst = 0.0, scale = scale_[g];
      for (std::size_t i = groups_[g].offset; i < groups_[g].offset + groups_[g].count; ++i) {
        double used = 0.0;
        for (std::uint32_t k = 0; k <= order; ++k) used += used_coeff[k * n + i];
        worst = std::max(worst, std::abs(used - produced[i]));
        scale = std::max(scale, std::abs(produced[i]));
      }
      out[g].group = groups_[g].name;
      out[g].absolute = worst;
      out[g].relative = scale > 0.0 ? worst / scale : worst;
      out[g].scale = scale;
    }
  }

 private:
  std::vector<ChannelGroup> groups_;
  std::vector<double> scale_;
};

}  // namespace rumble::coupling

#endif  // RUMBLE_COUPLING_HPP
