// gauss_seidel: the sequential (staggered) explicit co-simulation scheme of the seed paper.
// Per macro step [t, t+H], with order "track_first" (the paper's):
//   1. the vehicle/track advances with the footprint motion extrapolated from the soil's last
//      outputs (order 0: held constant; 1: linear from the last two macro steps);
//   2. the soil advances with the footprint forces the track just produced (interpolation 0:
//      the new end-of-step force held over the step; 1: linear from the previous to the new).
// "soil_first" swaps the roles. Not iterated: the interface error is O(H) (order 0).
#include <rumble/params.hpp>
#include <rumble/plugin.hpp>

#include "common/interface_history.hpp"
#include "common/macro_steps.hpp"

namespace {

using rumble::CosimHost;
using rumble::couplers::InterfaceHistory;

class GaussSeidel final : public rumble::Coupler {
 public:
  static constexpr const char* kTypeName = "gauss_seidel";
  static constexpr const char* kSummary =
      "sequential explicit coupling: one participant advances first, the other follows with its "
      "new outputs";
  static const char* params_schema() {
    return R"schema({
  "type": "object",
  "additionalProperties": false,
  "properties": {
    "order": {"enum": ["track_first", "soil_first"], "default": "track_first",
              "description": "which participant advances first in each macro step"},
    "extrapolation": {"type": "integer", "minimum": 0, "maximum": 1, "default": 0,
                      "description": "polynomial order of the first participant's input over the step, extrapolated from past macro steps (0 = held constant)"},
    "interpolation": {"type": "integer", "minimum": 0, "maximum": 1, "default": 0,
                      "description": "polynomial order of the second participant's input over the step (0 = the first participant's new end-of-step value held; 1 = linear from its previous to its new value)"}
  }
})schema";
  }

  GaussSeidel(const std::string& params_json, const rumble::Host& /*host*/) {
    const rumble::Params p(params_json);
    track_first_ = p.get_or<std::string>("order", "track_first") == "track_first";
    extrapolation_ = p.get_or<std::uint32_t>("extrapolation", 0);
    interpolation_ = p.get_or<std::uint32_t>("interpolation", 0);
  }

  void run(const CosimHost& host, double t0, double t_end, double H) override {
    InterfaceHistory track(host, CosimHost::kTrack), soil(host, CosimHost::kSoil);
    const std::uint32_t first = track_first_ ? CosimHost::kTrack : CosimHost::kSoil;
    const std::uint32_t second = track_first_ ? CosimHost::kSoil : CosimHost::kTrack;
    InterfaceHistory& first_outputs = track_first_ ? track : soil;   // produced by `first`
    InterfaceHistory& second_outputs = track_first_ ? soil : track;  // produced by `second`
    // Residual channels: the displacements u (soil outputs u then v), or the forces.
    const std::size_t residual_channels = track_first_ ? soil.size() / 2 : track.size();
    track.sample();
    soil.sample();
    std::vector<double> in_first, in_second;
    std::uint32_t order_first = 0, order_second = 0;
    const std::size_t steps = rumble::couplers::macro_step_count(t0, t_end, H);
    for (std::size_t k = 0; k < steps; ++k) {
      const double t = rumble::couplers::macro_step_start(t0, H, k);
      const double h = rumble::couplers::macro_step_length(t0, t_end, H, k);
      second_outputs.extrapolated(extrapolation_, in_first, order_first);
      host.set_input(first, order_first, in_first);
      host.advance(first, t, h);
      first_outputs.sample();
      first_outputs.interpolated(interpolation_, in_second, order_second);
      host.set_input(second, order_second, in_second);
      host.advance(second, t, h);
      second_outputs.sample();
      host.step_done(t, h,
                     second_outputs.relative_mismatch(in_first, order_first, residual_channels));
    }
  }

 private:
  bool track_first_ = true;
  std::uint32_t extrapolation_ = 0;
  std::uint32_t interpolation_ = 0;
};

}  // namespace

RUMBLE_PLUGIN("gauss_seidel", "0.1.0", GaussSeidel)
