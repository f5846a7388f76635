// template_coupler: the copy-me example of a Rumble coupler plugin (see README.md next to this
// file). Start your own with `rumble new-plugin coupler <name>`.
//
// Scheme: plain Gauss-Seidel (staggered, explicit, order 0). Per macro step [t, t + h]:
//   1. the track advances with the soil's last footprint motion (u then v) held constant;
//   2. the soil advances with the footprint forces the track just produced, held constant;
//   3. the step is reported done, with the relative change of the footprint displacement over
//      the step as the interface residual (what the track used versus what the soil now says).
// Not iterated: the interface error is O(h). It uses only the CosimHost calls interface_size,
// output_size, get_output, set_input, advance and step_done.
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <rumble/plugin.hpp>
#include <stdexcept>
#include <string>
#include <vector>

namespace {

class TemplateCoupler final : public rumble::Coupler {
 public:
  static constexpr const char* kTypeName = "template_coupler";
  static constexpr const char* kSummary =
      "Gauss-Seidel, order 0: track then soil, each with the other's last outputs held";
  static const char* params_schema() {
    return R"({"type": "object", "additionalProperties": false, "properties": {}})";
  }

  // No params (the schema allows none), so no rumble/params.hpp and no nlohmann_json.
  TemplateCoupler(const std::string& /*params_json*/, const rumble::Host& /*host*/) {}

  void run(const rumble::CosimHost& host, double t0, double t_end, double H) override {
    const std::uint32_t track = rumble::CosimHost::kTrack, soil = rumble::CosimHost::kSoil;
    const std::size_t n = host.interface_size();         // footprints
    std::vector<double> force(host.output_size(track));  // F_i, n values
    std::vector<double> motion(host.output_size(soil));  // u_i then v_i, 2n values
    host.get_output(track, force);
    host.get_output(soil, motion);
    // Step k starts at t0 + k H (no accumulated round-off); the last one ends exactly at t_end.
    const auto steps = static_cast<std::size_t>(std::ceil((t_end - t0) / H - 1e-9));
    for (std::size_t k = 0; k < steps; ++k) {
      const double t = t0 + static_cast<double>(k) * H;
      const double h = std::min(H, t_end - t);
      const std::vector<double> used = motion;
      host.set_input(track, 0, used);
      refuse_discard(host.advance(track, t, h), "track", t);
      host.get_output(track, force);
      host.set_input(soil, 0, force);
      refuse_discard(host.advance(soil, t, h), "soil", t);
      host.get_output(soil, motion);
      host.step_done(t, h, relative_change(used, motion, n));
    }
  }

 private:
  /// A participant may refuse a step (DISCARD) and expect a retry with a smaller one; this
  /// scheme has no step control, so it stops with a message that says what to change.
  static void refuse_discard(rumble_status status, const char* participant, double t) {
    if (status == RUMBLE_DISCARD) {
      throw std::runtime_error(std::string("template_coupler: the ") + participant +
                               " refused the macro step at t = " + std::to_string(t) +
                               " s; this coupler cannot retry: use a smaller time.macro_step");
    }
  }

  /// max_i |after_i - before_i| / max_i |after_i| over the n displacements.
  static double relative_change(const std::vector<double>& before, const std::vector<double>& after,
                                std::size_t n) {
    double change = 0.0, scale = 0.0;
    for (std::size_t i = 0; i < n; ++i) {
      change = std::max(change, std::abs(after[i] - before[i]));
      scale = std::max(scale, std::abs(after[i]));
    }
    return scale > 0.0 ? change / scale : change;
  }
};

}  // namespace

RUMBLE_PLUGIN("template_coupler", "0.1.0", TemplateCoupler)
