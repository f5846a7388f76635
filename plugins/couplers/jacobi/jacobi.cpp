// jacobi: the parallel explicit co-simulation scheme. Per macro step [t, t+H] both participants
// advance at once, on two threads, each from the other's outputs at t (order 0: held constant;
// extrapolation 1: linear from the last two macro steps). Cheaper in wall time than
// Gauss-Seidel, usually less stable for stiff interfaces.
#include <exception>
#include <rumble/params.hpp>
#include <rumble/plugin.hpp>
#include <thread>

#include "common/interface_history.hpp"
#include "common/macro_steps.hpp"

namespace {

using rumble::CosimHost;
using rumble::couplers::InterfaceHistory;

class Jacobi final : public rumble::Coupler {
 public:
  static constexpr const char* kTypeName = "jacobi";
  static constexpr const char* kSummary =
      "parallel explicit coupling: both participants advance at once from the previous outputs";
  static const char* params_schema() {
    return R"schema({
  "type": "object",
  "additionalProperties": false,
  "properties": {
    "extrapolation": {"type": "integer", "minimum": 0, "maximum": 1, "default": 0,
                      "description": "polynomial order of each participant's input over the step, extrapolated from past macro steps (0 = held constant)"},
    "threads": {"type": "integer", "minimum": 1, "maximum": 2, "default": 2,
                "description": "2: the two participants advance on two threads; 1: one after the other (same results)"}
  }
})schema";
  }

  Jacobi(const std::string& params_json, const rumble::Host& /*host*/) {
    const rumble::Params p(params_json);
    extrapolation_ = p.get_or<std::uint32_t>("extrapolation", 0);
    threads_ = p.get_or<int>("threads", 2);
  }

  void run(const CosimHost& host, double t0, double t_end, double H) override {
    InterfaceHistory track(host, CosimHost::kTrack), soil(host, CosimHost::kSoil);
    track.sample();
    soil.sample();
    std::vector<double> in_track, in_soil;
    std::uint32_t order_track = 0, order_soil = 0;
    const std::size_t steps = rumble::couplers::macro_step_count(t0, t_end, H);
    for (std::size_t k = 0; k < steps; ++k) {
      const double t = rumble::couplers::macro_step_start(t0, H, k);
      const double h = rumble::couplers::macro_step_length(t0, t_end, H, k);
      soil.extrapolated(extrapolation_, in_track, order_track);
      track.extrapolated(extrapolation_, in_soil, order_soil);
      host.set_input(CosimHost::kTrack, order_track, in_track);
      host.set_input(CosimHost::kSoil, order_soil, in_soil);
      if (threads_ == 2) {
        std::exception_ptr soil_error;
        std::thread soil_thread([&] {
          try {
            host.advance(CosimHost::kSoil, t, h);
          } catch (...) {
            soil_error = std::current_exception();
          }
        });
        std::exception_ptr track_error;
        try {
          host.advance(CosimHost::kTrack, t, h);
        } catch (...) {
          track_error = std::current_exception();
        }
        soil_thread.join();
        if (track_error) std::rethrow_exception(track_error);
        if (soil_error) std::rethrow_exception(soil_error);
      } else {
        host.advance(CosimHost::kTrack, t, h);
        host.advance(CosimHost::kSoil, t, h);
      }
      track.sample();
      soil.sample();
      host.step_done(t, h, soil.relative_mismatch(in_track, order_track, soil.size() / 2));
    }
  }

 private:
  std::uint32_t extrapolation_ = 0;
  int threads_ = 2;
};

}  // namespace

RUMBLE_PLUGIN("jacobi", "0.1.0", Jacobi)
