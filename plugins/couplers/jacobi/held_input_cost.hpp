// What jacobi's held input costs the outputs of the participant that receives it, for the
// adaptive macro step (docs/couplers.md, adaptive macro steps: "jacobi: the error of the
// soil's held force").
//
// Under jacobi both participants start a step from the other's outputs at its start, extrapolated
// (order 0: held). The input a participant took then differs from what the other produced over
// the step by about a ramp that reaches the predictor residual r of that input group at the
// step's end, and the receiving participant's outputs at the step's end are wrong by its response
// to that ramp. The predictor residual alone measures r in the input's own unit against the
// input's own scale: on the paper's medium soil as Winkler footprints, a footprint force error of
// 1 % of the force's scale (some 33 kN before the dip) moves the footprint velocity by 1 mm/s
// (dF / c, Lysmer's dashpot c = 3.4e5 N s/m), 2.2 % of the dip's peak velocity.
// So the error is counted where it lands: in the receiver's outputs,
//   e = max over output groups g, channels j of  sum over input groups i of R_ij(h) r_i /
//   allowed_g,
// allowed_g = max(tolerance x the group's scale, its absolute tolerance) as for the residuals
// (rumble/macro_steps.hpp, step_error), R_ij(h) [output unit / input unit] the response of output
// channel j at the end of a step of h to a ramp from 0 to 1 over the step on every channel of
// input group i. R is probed on the receiver itself, once per step length (the steps are whole
// numbers of min_step, so there are few): before the step, the receiver advances over it with the
// ramp added and is put back (one extra advance per length; the step itself then runs as ever,
// so a soil's own state beyond its checkpoint, such as the step-mean velocity it reports, is the
// step's), and R(h) is the difference of the two ends. The probe assumes a response linear in
// the input, as every lumped and FEM soil's is; the ramp on every channel at once counts a
// coupled soil's neighbours as loaded too, so it over-estimates a localised error there.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <map>
#include <rumble/coupling.hpp>
#include <rumble/macro_steps.hpp>
#include <rumble/plugin.hpp>
#include <string>
#include <utility>
#include <vector>

namespace rumble_jacobi {

class HeldInputCost {
 public:
  /// For `receiver`'s inputs under the adaptive step `a`; inactive (error() 0) unless `active`
  /// (the receiver can checkpoint: each probe saves it and puts it back).
  HeldInputCost(const rumble::CosimHost& host, std::uint32_t receiver,
                const rumble::coupling::AdaptiveStep& a, bool active)
      : host_(host),
        receiver_(receiver),
        a_(a),
        active_(active && a.enabled()),
        inputs_(host.groups(receiver, RUMBLE_SIDE_INPUT)),
        outputs_(host.groups(receiver, RUMBLE_SIDE_OUTPUT)) {}

  /// Before a step of h whose length is new: advances the receiver over [t, t + h] from its
  /// state now with the input waveform (order, coeff) and a ramp added to each input group in
  /// turn, reads its outputs, and puts it back (saved in checkpoint `slot`, restored, given
  /// (order, coeff) again): one extra advance per input group. finish() completes R(h) from the
  /// step's own outputs.
  void probe(double t, double h, std::uint32_t order, const std::vector<double>& coeff,
             std::uint32_t slot) {
    pending_.clear();
    if (!active_ || responses_.count(key(h)) > 0) return;
    const std::size_t n = coeff.size() / (order + 1u);
    const std::uint32_t ramped = std::max<std::uint32_t>(order, 1);
    std::vector<double> ramp;
    host_.save(receiver_, slot);
    for (const rumble::ChannelGroup& in : inputs_) {
      // A ramp of the group's own size (its largest held value, at least 1 unit): the response
      // is linear, so only round-off depends on it.
      double size = 1.0;
      for (std::size_t i = in.offset; i < in.offset + in.count; ++i)
        size = std::max(size, std::abs(coeff[i]));
      ramp.assign((ramped + 1u) * n, 0.0);
      std::copy(coeff.begin(), coeff.end(), ramp.begin());
      for (std::size_t i = in.offset; i < in.offset + in.count; ++i) ramp[n + i] += size;
      host_.set_input(receiver_, ramped, ramp);
      if (host_.advance(receiver_, t, h) == RUMBLE_DISCARD) {  // refused: no response this time
        pending_.clear();
        break;
      }
      auto& [ramp_size, outputs] = pending_.emplace_back(size, std::vector<double>());
      outputs.resize(host_.output_size(receiver_));
      host_.get_output(receiver_, outputs);
      host_.restore(receiver_, slot);
      ++probes_;
    }
    host_.set_input(receiver_, order, coeff);
  }

  /// After the step of h probe() prepared, with the receiver's outputs `produced`: R(h).
  void finish(double h, const std::vector<double>& produced) {
    if (pending_.empty()) return;
    std::vector<std::vector<double>> response;
    for (const auto& [size, y] : pending_) {
      std::vector<double>& r = response.emplace_back(produced.size());
      for (std::size_t j = 0; j < y.size(); ++j) r[j] = std::abs(y[j] - produced[j]) / size;
      step_mean_velocity(h, r);
    }
    responses_.emplace(key(h), std::move(response));
    pending_.clear();
  }

  /// The error [-] (1: on the tolerance) the receiver's outputs make through its inputs' errors
  /// over a step of h: `input_residuals` (n_in) are the predictor residuals of the groups that
  /// fed it (matched by name), `output_residuals` (n_out) its own outputs' (for their scales).
  double error(double h, const rumble::GroupResidual* input_residuals, std::size_t n_in,
               const rumble::GroupResidual* output_residuals, std::size_t n_out) const {
    const auto found = responses_.find(key(h));
    if (!active_ || found == responses_.end()) return 0.0;
    std::vector<double> error_in(inputs_.size(), 0.0);  // r_i [input unit]
    for (std::size_t i = 0; i < inputs_.size(); ++i)
      for (std::size_t k = 0; k < n_in; ++k)
        if (input_residuals[k].group == inputs_[i].name) error_in[i] = input_residuals[k].absolute;
    double e = 0.0;
    for (std::size_t g = 0; g < outputs_.size(); ++g) {
      double scale = 0.0;
      for (std::size_t k = 0; k < n_out; ++k)
        if (output_residuals[k].group == outputs_[g].name) scale = output_residuals[k].scale;
      const auto floor = a_.absolute.find(outputs_[g].name);
      const double allowed =
          std::max(a_.tolerance * scale, floor != a_.absolute.end() ? floor->second : 0.0);
      if (!(allowed > 0.0)) continue;
      for (std::size_t j = outputs_[g].offset; j < outputs_[g].offset + outputs_[g].count; ++j) {
        double out = 0.0;  // [output unit]
        for (std::size_t i = 0; i < inputs_.size(); ++i) out += found->second[i][j] * error_in[i];
        e = std::max(e, out / allowed);
      }
    }
    return e;
  }

  /// Extra advances of the receiver the probes took.
  std::size_t advances() const { return probes_; }

 private:
  const rumble::CosimHost& host_;
  std::uint32_t receiver_;
  rumble::coupling::AdaptiveStep a_;
  bool active_;
  std::vector<rumble::ChannelGroup> inputs_, outputs_;
  std::map<long long, std::vector<std::vector<double>>> responses_;  // h [ns] -> R[input][output]
  std::size_t probes_ = 0;
  std::vector<std::pair<double, std::vector<double>>> pending_;  // ramp size, outputs (probe())

  static long long key(double h) { return std::llround(h * 1e9); }

  /// The footprint velocity's response as the results record it after a step under a held
  /// force: the mean over the step, the displacement's response / h (docs/couplers.md, "The
  /// footprint velocity"), the one the PPV reads. Its end-of-step response is about twice
  /// that on a massless soil (the velocity follows the ramp at once), and counted so it put
  /// the paper's medium soil at min_step through the dip at either tolerance.
  void step_mean_velocity(double h, std::vector<double>& r) const {
    const rumble::ChannelGroup *u = nullptr, *v = nullptr;
    for (const rumble::ChannelGroup& g : outputs_) {
      if (g.name == "footprint_displacement") u = &g;
      if (g.name == "footprint_velocity") v = &g;
    }
    if (u == nullptr || v == nullptr || u->count != v->count) return;
    for (std::size_t i = 0; i < v->count; ++i) r[v->offset + i] = r[u->offset + i] / h;
  }
};

}  // namespace rumble_jacobi
