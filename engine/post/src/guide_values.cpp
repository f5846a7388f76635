#include "post/guide_values.hpp"

#include <array>
#include <cmath>
#include <numbers>
#include <stdexcept>
#include <utility>

namespace rumble::post {
namespace {

constexpr double kMmPerS = 1e-3;  // m/s per mm/s

using Point = std::pair<double, double>;  // (Hz, mm/s)

// DIN 4150-3 Table 1, foundation, at the band edges 1, 10, 50, 100 Hz.
constexpr std::array<std::array<Point, 4>, 3> kDin = {{
    {{{1.0, 20.0}, {10.0, 20.0}, {50.0, 40.0}, {100.0, 50.0}}},
    {{{1.0, 5.0}, {10.0, 5.0}, {50.0, 15.0}, {100.0, 20.0}}},
    {{{1.0, 3.0}, {10.0, 3.0}, {50.0, 8.0}, {100.0, 10.0}}},
}};

// BS 7385-2 Table 1, line 2, from 4 Hz.
constexpr std::array<Point, 3> kBsLine2 = {{{4.0, 15.0}, {15.0, 20.0}, {40.0, 50.0}}};
constexpr double kBsLine1 = 50.0;                // mm/s
constexpr double kBsDisplacementLimit = 0.6e-3;  // m, zero to peak, line 2 below 4 Hz

void check_frequency(double f, const char* what) {
  if (!(f > 0.0) || !std::isfinite(f))
    throw std::invalid_argument(std::string(what) + ": frequency " + std::to_string(f) +
                                " Hz is not a positive number; the guide values are read at "
                                "the dominant frequency of the vibration");
}

template <std::size_t N>
double interpolate(const std::array<Point, N>& table, double f) {
  if (f <= table.front().first) return table.front().second;
  for (std::size_t i = 1; i < N; ++i) {
    if (f <= table[i].first) {
      const auto [f0, v0] = table[i - 1];
      const auto [f1, v1] = table[i];
      return v0 + (v1 - v0) * (f - f0) / (f1 - f0);
    }
  }
  return table.back().second;
}

}  // namespace

double din4150_3_guide(Din4150Line line, double f) {
  check_frequency(f, "DIN 4150-3");
  const int i = static_cast<int>(line) - 1;
  if (i < 0 || i > 2) throw std::invalid_argument("DIN 4150-3: no line " + std::to_string(i + 1));
  return interpolate(kDin[static_cast<std::size_t>(i)], f) * kMmPerS;
}

double bs7385_2_guide(Bs7385Line line, double f) {
  check_frequency(f, "BS 7385-2");
  switch (line) {
    case Bs7385Line::kReinforced:
      return kBsLine1 * kMmPerS;
    case Bs7385Line::kUnreinforced:
      if (f < kBsLine2.front().first) return 2.0 * std::numbers::pi * f * kBsDisplacementLimit;
      return interpolate(kBsLine2, f) * kMmPerS;
  }
  throw std::invalid_argument("BS 7385-2: no line " + std::to_string(static_cast<int>(line)));
}

GuideCheck check_din4150_3(Din4150Line line, double ppv, double f) {
  const double g = din4150_3_guide(line, f);
  return {g, ppv / g};
}

GuideCheck check_bs7385_2(Bs7385Line line, double ppv, double f) {
  const double g = bs7385_2_guide(line, f);
  return {g, ppv / g};
}

std::string name(Din4150Line line) {
  return "DIN 4150-3 line " + std::to_string(static_cast<int>(line));
}

std::string name(Bs7385Line line) {
  return "BS 7385-2 line " + std::to_string(static_cast<int>(line));
}

}  // namespace rumble::post
