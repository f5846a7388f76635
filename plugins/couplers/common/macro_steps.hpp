// Macro-step bookkeeping shared by the couplers: step k covers [t0 + k H, min(t0 + (k+1) H,
// t_end)], computed from k (no accumulated round-off); a final partial step ends exactly at t_end.
#pragma once

#include <cmath>
#include <cstddef>

namespace rumble::couplers {

inline std::size_t macro_step_count(double t0, double t_end, double H) {
  return static_cast<std::size_t>(std::ceil((t_end - t0) / H - 1e-9));
}

inline double macro_step_start(double t0, double H, std::size_t k) {
  return t0 + static_cast<double>(k) * H;
}

inline double macro_step_length(double t0, double t_end, double H, std::size_t k) {
  const double start = macro_step_start(t0, H, k);
  return std::fmin(H, t_end - start);
}

}  // namespace rumble::couplers
