// DIN 4150-2 (1999), "Erschütterungen im Bauwesen - Teil 2: Einwirkungen auf Menschen in
// Gebäuden": the KB frequency weighting of a velocity signal and the running RMS with the
// exponential time weighting "Fast", KB_F(t) and its maximum KB_F,max; plus the plain running
// RMS and the effective (RMS) velocity of unweighted signals. All velocities in m/s (DIN tables
// quote KB in mm/s: multiply by 1000).
//
// KB weighting: a first-order high-pass on velocity with corner f0 = 5.6 Hz,
//   H_KB(s) = s / (s + 2 pi f0),   |H_KB(f)| = 1 / sqrt(1 + (f0 / f)^2)
// (gains 0.336 at 2 Hz, 0.707 at 5.6 Hz, 0.944 at 16 Hz; docs/physics.md §9).
// It is discretised by the bilinear transform with the corner pre-warped,
//   s -> K (1 - z^-1) / (1 + z^-1),  K = 2 pi f0 / tan(pi f0 dt),
//   y_n = b (x_n - x_{n-1}) - a y_{n-1},  b = K / (K + 2 pi f0),  a = (2 pi f0 - K) / (K + 2 pi
//   f0),
// which is stable for every dt and exact at f0 and at DC (zero); at other frequencies the
// digital gain is the analogue one at f0 tan(pi f dt) / tan(pi f0 dt), 0.8 % above f at f = fs/20,
// where |H_KB| is nearly flat (a gain error of 1e-4 at 50 Hz with fs = 1 kHz). The record starts
// from rest (x_{-1} = y_{-1} = 0), as a simulation does.
//
// Running RMS with exponential time weighting (DIN 4150-2 eq. for KB_F; IEC 61672 "Fast"):
//   r(t) = sqrt( (1/tau) int_0^t exp(-(t - xi) / tau) x(xi)^2 dxi ),   tau = 0.125 s for Fast,
// integrated exactly for x^2 varying linearly between samples:
//   q_n = a q_{n-1} + u_n - a u_{n-1} - (u_n - u_{n-1}) (tau/dt) (1 - a),  a = exp(-dt/tau),
//   u = x^2, q_0 = 0, r_n = sqrt(q_n).
// For a steady sine A sin(2 pi f t) the squared output ripples at 2f around A^2/2:
//   max r = (A / sqrt 2) sqrt(1 + 1 / sqrt(1 + (4 pi f tau)^2))
// (a ripple of 2.0 % at 16 Hz with Fast), so KB_F,max of a long steady sine is
// (A / sqrt 2) |H_KB(f)| to within that ripple.
#pragma once

#include <cstddef>
#include <span>
#include <vector>

#include "post/time_series.hpp"

namespace rumble::post {

constexpr double kKbCornerHz = 5.6;  // f0 of the KB weighting [Hz]
constexpr double kFastTau = 0.125;   // s, time constant of the "Fast" exponential weighting

/// |H_KB(f)| = 1 / sqrt(1 + (f0/f)^2) for f > 0 [Hz]; 0 at f = 0.
double kb_gain(double f);

/// The KB-weighted signal (same grid as v) [m/s].
TimeSeries kb_weight(const TimeSeries& v);

/// Running RMS with exponential time weighting of time constant tau [s] (same grid as x).
TimeSeries running_rms(const TimeSeries& x, double tau);

/// The RMS over the whole record, sqrt(mean x^2) [signal unit]: the effective value.
double effective_value(std::span<const double> x);

/// DIN 4150-2's KB_F(t) and its maximum for one velocity component.
struct KbResult {
  TimeSeries kb_f;        // KB_F(t) [m/s]
  double kb_f_max = 0.0;  // m/s
  double t_max = 0.0;     // s, time of the maximum
};
KbResult kb_f(const TimeSeries& v, double tau = kFastTau);

/// The maximum of the running RMS (Fast by default) of the unweighted velocity, v_eff,F,max
/// [m/s]: what a vibration meter with Fast time weighting and no frequency weighting shows.
double effective_velocity_max(const TimeSeries& v, double tau = kFastTau);

}  // namespace rumble::post
