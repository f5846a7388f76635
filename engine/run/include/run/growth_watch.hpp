// Sustained exponential growth of a soil's interface motion: the mark of an unstable coupling,
// seen long before the motion is large (docs/couplers.md, "Divergence"). An unstable explicit
// coupling multiplies its error by the spectral radius rho > 1 at every macro step, from the
// first step on; a passing train's motion rises and falls with the load, the dip and the waves,
// but does not keep growing at one rate past anything it did before.
//
// The measure fed in is the largest footprint speed of one final macro step. Macro steps are
// gathered into windows (at least kStepsPerWindow steps and kWindowSeconds), each keeping its
// peak; at each window's end, spans of the last 3, 6, 12, 24 and 48 windows are tried. A span grows
// when a constant (the train's own motion) plus an exponential fits its peaks (R^2 >= kMinFit),
// it rises by at least kMinGrowth, and its last windows keep rising beyond kMinGrowth times every
// peak before the span for kBeyondSeconds (3 windows when what grows flips sign every step) and
// beyond kFloor (rounding noise of a soil at rest): a start from rest or a dip's blow rise once
// and ring down. And the span rises at a steady rate: a load that rises from rest (a prescribed
// load's ramp or pulse, docs/couplers.md) rises at a falling one, as a power of the time since
// it began, and can rise for longer than kBeyondSeconds. The rate reported is the exponential's.
#pragma once

#include <cstddef>
#include <optional>
#include <vector>

namespace rumble {

/// What a growing span measured.
struct Growth {
  double per_step = 1.0;     // [-] factor per macro step (the spectral radius it shows)
  double doubling_s = 0.0;   // [s] time to double
  double since_s = 0.0;      // [s] start of the span
  double peak = 0.0;         // [m/s] newest window's peak
  double peak_before = 0.0;  // [m/s] largest peak before the span (0: none)
};

class GrowthWatch {
 public:
  static constexpr std::size_t kStepsPerWindow = 10;
  static constexpr double kWindowSeconds = 5e-3;  // s
  static constexpr double kMinFit = 0.9;          // R^2 of the fit to the peaks
  static constexpr double kMinGrowth = 2.0;       // over the span, and over what came before
  static constexpr double kFloor = 1e-6;          // m/s
  // How long the motion must keep rising beyond kMinGrowth x before, window after window: longer
  // than the blow of a dip or a wheel flat rises (the paper's 0.6 m dip at 25 m/s: 24 ms; the
  // quarter car's 0.5 m dip at 20 m/s rose 33x in 30 ms over a smooth track, then fell) ...
  static constexpr double kBeyondSeconds = 0.06;    // s
  static constexpr std::size_t kBeyondWindows = 6;  // and at least these windows
  // ... unless what grows alternates with the macro step (in the newest window the step-to-step
  // part is at least kAlternating of the speed; a smooth motion at f has about pi f H of it):
  // nothing physical moves at 1 / (2 H), so three windows tell.
  static constexpr std::size_t kAlternatingWindows = 3;
  static constexpr double kAlternating = 0.5;
  // The newer half of a growing span rises at least this fraction of the older half's rate (per
  // second, of the log of the peaks): an unstable mode rises at one rate, or faster as it
  // emerges from the train's motion; the speed under a load rising from rest slows its rate (as
  // p / t for t^p). Measured (growth_watch_test.cpp): the speed under a 1 - cos ramp of the load
  // over up to 1 s, or a Hann pulse, stays under it; a t^3 rise of the speed kept up for 0.3 s
  // and more does not, and is taken for growth.
  static constexpr double kSteadyRate = 0.7;

  /// One final macro step of length H [s] ending at t [s]: `speed` [m/s], the largest footprint
  /// speed; `alternating` [m/s], the largest half change of a footprint's mean velocity from the
  /// step before (the speed itself for a motion whose sign flips every step, about
  /// omega H / 2 of it for a smooth one). Returns the growth when a window ends in a growing span.
  std::optional<Growth> add(double t, double H, double speed, double alternating);

 private:
  struct Window {
    double t_start = 0.0, t_end = 0.0;     // s
    double peak = 0.0, alternating = 0.0;  // m/s, largest speed and alternating part
    std::size_t steps = 0;
    double t_mid() const { return 0.5 * (t_start + t_end); }
  };
  /// Whether the last windows rise beyond kMinGrowth x `before` long enough to be growth.
  bool keeps_rising_beyond(double before) const;
  /// Whether the windows from `first` on rise at a steady rate (kSteadyRate); never from rest.
  bool rises_steadily(std::size_t first) const;
  std::optional<Growth> growing_span(std::size_t span) const;
  /// The windows from `first` on as a constant plus an exponential: its rate [1/s] and how much
  /// of the peaks' relative spread it explains (R^2).
  struct Fit {
    double rate = 0.0, quality = 0.0;
  };
  Fit fit_exponential(std::size_t first) const;

  std::vector<Window> windows_;    // closed, oldest first
  std::vector<double> peak_upto_;  // peak_upto_[i]: largest peak of windows 0..i
  Window open_;
};

}  // namespace rumble
