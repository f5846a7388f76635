#include "run/growth_watch.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

namespace rumble {

std::optional<Growth> GrowthWatch::add(double t, double H, double speed, double alternating) {
  if (open_.steps == 0) open_.t_start = t - H;
  open_.peak = std::max(open_.peak, std::isfinite(speed) ? speed : 0.0);
  open_.alternating = std::max(open_.alternating, std::isfinite(alternating) ? alternating : 0.0);
  ++open_.steps;
  open_.t_end = t;
  if (open_.steps < kStepsPerWindow || t - open_.t_start < kWindowSeconds * (1.0 - 1e-9))
    return std::nullopt;
  peak_upto_.push_back(std::max(open_.peak, peak_upto_.empty() ? 0.0 : peak_upto_.back()));
  windows_.push_back(open_);
  open_ = Window{};
  for (std::size_t span : std::array<std::size_t, 5>{3, 6, 12, 24, 48})
    if (auto g = growing_span(span)) return g;
  return std::nullopt;
}

bool GrowthWatch::keeps_rising_beyond(double before) const {
  const std::size_t n = windows_.size();
  std::size_t rising = 0;  // windows in a row, newest first
  while (rising + 1 < n) {
    const Window& w = windows_[n - 1 - rising];
    if (!(w.peak > kFloor) || w.peak < kMinGrowth * before ||
        !(w.peak > windows_[n - 2 - rising].peak))
      break;
    ++rising;
  }
  const Window& newest = windows_.back();
  if (rising >= kAlternatingWindows && newest.alternating >= kAlternating * newest.peak)
    return true;
  const double seconds = rising == 0 ? 0.0 : newest.t_end - windows_[n - rising].t_start;
  return rising >= kBeyondWindows && seconds >= kBeyondSeconds * (1.0 - 1e-9);
}

bool GrowthWatch::rises_steadily(std::size_t first) const {
  const std::size_t n = windows_.size(), mid = first + (n - first) / 2;
  const Window &older = windows_[first], &middle = windows_[mid], &newest = windows_.back();
  if (!(older.peak > 0.0)) return false;  // from rest: a load's start, not a mode's growth
  const double early = std::log(middle.peak / older.peak) / (middle.t_mid() - older.t_mid());
  const double late = std::log(newest.peak / middle.peak) / (newest.t_mid() - middle.t_mid());
  return late >= kSteadyRate * early;  // 1/s
}

GrowthWatch::Fit GrowthWatch::fit_exponential(std::size_t first) const {
  // The peaks are the train's motion B plus the growing mode A e^{r t}: a line through log(peak)
  // mixes B in and reads a slower rate (0.018 per step where the mode grew 0.04, seen on the
  // massless CLM of docs/couplers.md). For each r on a log grid, B >= 0 and A > 0 follow by
  // linear least squares weighted by 1 / peak (a relative misfit); the r of the least misfit is
  // the rate. The grid spans 1/2 to 200 times the mean rate of the span.
  const std::size_t n = windows_.size();
  const double t_last = windows_.back().t_mid();
  const double mean_rate =
      std::log(windows_.back().peak / windows_[first].peak) / (t_last - windows_[first].t_mid());
  double total = 0.0, mean = 0.0;  // the relative spread of the peaks about their mean
  for (std::size_t i = first; i < n; ++i) mean += windows_[i].peak / static_cast<double>(n - first);
  for (std::size_t i = first; i < n; ++i) total += std::pow(1.0 - mean / windows_[i].peak, 2);
  Fit best;
  double best_misfit = std::numeric_limits<double>::infinity();
  for (int k = 0; k <= 300; ++k) {
    const double r = mean_rate * 0.5 * std::pow(400.0, k / 300.0);
    double s11 = 0.0, s12 = 0.0, s22 = 0.0, b1 = 0.0, b2 = 0.0;
    for (std::size_t i = first; i < n; ++i) {
      const double w2 = 1.0 / (windows_[i].peak * windows_[i].peak);
      const double e = std::exp(r * (windows_[i].t_mid() - t_last));
      s11 += w2;
      s12 += w2 * e;
      s22 += w2 * e * e;
      b1 += w2 * windows_[i].peak;
      b2 += w2 * e * windows_[i].peak;
    }
    const double det = s11 * s22 - s12 * s12;
    if (!(det > 0.0)) continue;
    const double B = (b1 * s22 - b2 * s12) / det, A = (s11 * b2 - s12 * b1) / det;
    if (B < 0.0 || A <= 0.0) continue;
    double misfit = 0.0;
    for (std::size_t i = first; i < n; ++i) {
      const double e = std::exp(r * (windows_[i].t_mid() - t_last));
      misfit += std::pow(1.0 - (B + A * e) / windows_[i].peak, 2);
    }
    if (misfit < best_misfit) {
      best_misfit = misfit;
      best = {r, total > 0.0 ? 1.0 - misfit / total : 0.0};
    }
  }
  return best;
}

std::optional<Growth> GrowthWatch::growing_span(std::size_t span) const {
  // Spans start after the first window: a run starts from rest, and its first window rises
  // from nothing.
  const std::size_t n = windows_.size();
  if (n < span + 1) return std::nullopt;
  const std::size_t first = n - span;
  const double before = peak_upto_[first - 1];
  if (!keeps_rising_beyond(before) || windows_.back().peak < kMinGrowth * windows_[first].peak ||
      !rises_steadily(first))
    return std::nullopt;
  const Fit fit = fit_exponential(first);
  if (!(fit.rate > 0.0) || fit.quality < kMinFit) return std::nullopt;
  std::size_t steps = 0;
  for (std::size_t i = first; i < n; ++i) steps += windows_[i].steps;
  const double mean_step = (windows_.back().t_end - windows_[first].t_start) / steps;  // s
  Growth g;
  g.per_step = std::exp(fit.rate * mean_step);
  g.doubling_s = std::log(2.0) / fit.rate;
  g.since_s = windows_[first].t_start;
  g.peak = windows_.back().peak;
  g.peak_before = before;
  return g;
}

}  // namespace rumble
