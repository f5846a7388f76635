// The FEM soil in the frequency domain: the footprints' receptance, solved per frequency or
// from impulse responses, and cached on disk. Its solvers are built lazily and live beside the
// time stepping's without touching its state, so they read best on their own.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <complex>
#include <cstddef>
#include <filesystem>
#include <memory>
#include <string>

#include "fem_soil.hpp"
#include "frequency/impulse_receptance.hpp"
#include "frequency/receptance.hpp"
#include "frequency/receptance_cache.hpp"
#include "mesh/mesh_cache.hpp"

namespace rumble::fem {

bool FemSoil::frequency_response(double f_hz, std::complex<double>* receptance) {
  require_layout("frequency_response");
  if (distributed_)
    refuse_whole_operator("frequency_response (the receptance: rumble soil-frf, calibrate)");
  using namespace rumble::fem;
  const auto dir = mesh_cache_directory();
  std::filesystem::path cached;
  if (dir) {
    if (!receptance_key_) receptance_key_ = receptance_soil_key(mesh_, params_, weights_);
    cached = *dir / receptance_cache_name(*receptance_key_, f_hz);
    if (read_cached_receptance(cached, f_hz, footprints_.size(), receptance)) {
      host_.log(RUMBLE_LOG_DEBUG,
                "fem: receptance at " + format(f_hz) + " Hz from the cache " + cached.string());
      return true;
    }
  }
  if (settings_.receptance.impulse) {
    op_->set_threads(host_.threads());
    if (!impulse_) impulse_ = impulse_responses();
    impulse_->at(f_hz, receptance);
  } else {
    if (!receptance_) {
      receptance_ =
          std::make_unique<Receptance>(*op_, weights_, settings_.damping.mass_coefficient(),
                                       settings_.damping.stiffness_coefficient());
      if (settings_.boundary.far_field_follows) receptance_->set_far_field(far_field(), &far_lag_);
    }
    receptance_->at(f_hz, receptance);
  }
  if (dir && !write_cached_receptance(cached, f_hz, footprints_.size(), receptance) &&
      !receptance_cache_warned_) {
    host_.warn("fem: could not keep the receptance in " + cached.string() +
               " (set RUMBLE_MESH_CACHE to a writable directory, or to off)");
    receptance_cache_warned_ = true;
  }
  return true;
}

std::unique_ptr<rumble::fem::ImpulseReceptance> FemSoil::impulse_responses() {
  const rumble::fem::StaticFarField* far =
      settings_.boundary.far_field_follows ? far_field() : nullptr;
  const double dt = settings_.courant * op_->stable_step();
  const double duration = settings_.receptance.duration;
  const std::size_t n = footprints_.size();
  host_.info("fem: receptance from " + std::to_string(n) + " impulse responses of " +
             format(duration) + " s (" + format(std::ceil(duration / dt)) + " steps of " +
             format(dt) + " s each, " + std::to_string(op_->threads()) + " thread(s))");
  const auto start = std::chrono::steady_clock::now();
  auto last_check = start;
  auto responses = std::make_unique<rumble::fem::ImpulseReceptance>(
      *op_, weights_, dt, duration, settings_.mesh.f_max,
      [&](std::size_t j, std::size_t k) {
        const auto now = std::chrono::steady_clock::now();
        if (now - last_check > std::chrono::milliseconds(100)) {  // Ctrl-C, as in advance()
          host_.check_stop(static_cast<double>(j) / n);
          last_check = now;
        }
        if (k != 0 || j == 0 || j % std::max<std::size_t>(1, n / 10) != 0) return;  // ~10 %
        const double elapsed = seconds_since(start);
        host_.info("fem: impulse response " + std::to_string(j + 1) + " of " + std::to_string(n) +
                   ", about " + format(elapsed / j * static_cast<double>(n - j), 2) + " s left");
      },
      far, far_lag_.tau);
  host_.info("fem: impulse responses done in " + format(seconds_since(start), 3) +
             " s; the motion in the records' last tenth is " + format(responses->decay_ratio(), 2) +
             " of its peak");
  constexpr double kCutOff = 0.01;  // beyond, the low frequencies carry the truncation
  if (responses->decay_ratio() > kCutOff)
    host_.warn("fem: params/receptance/duration " + format(duration) +
               " s: the footprints still move at " + format(responses->decay_ratio(), 2) +
               " of their peak when the records end; the low frequencies are cut off: raise it");
  return responses;
}

}  // namespace rumble::fem
