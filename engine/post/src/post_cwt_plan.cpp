// Which receivers get a scalogram, and with which options. The user's choice meets the record's
// sampling here (f_max below Nyquist, f_min within the zero padding allowed), so that the
// transform (post/cwt.hpp) is asked only what the record can answer; each change is a warning.
#include <algorithm>
#include <cmath>
#include <optional>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "core/number_text.hpp"
#include "post_run_steps.hpp"

namespace rumble::post::detail {
namespace {

// For each wanted distance, the nearest receiver not yet chosen (surface before depth).
std::vector<std::size_t> default_cwt_receivers(const std::vector<Receiver>& receivers,
                                               const std::vector<double>& distances) {
  std::vector<std::size_t> chosen;
  for (double target : distances) {
    std::optional<std::size_t> best;
    for (std::size_t r = 0; r < receivers.size(); ++r) {
      if (std::find(chosen.begin(), chosen.end(), r) != chosen.end()) continue;
      auto key = [&](std::size_t i) {
        return std::make_pair(std::abs(receivers[i].distance - target), receivers[i].depth);
      };
      if (!best || key(r) < key(*best)) best = r;
    }
    if (best) chosen.push_back(*best);
  }
  return chosen;
}

}  // namespace

std::vector<std::size_t> choose_cwt_receivers(const std::vector<ReceiverResult>& results,
                                              const PostOptions& options,
                                              const fs::path& results_dir) {
  std::vector<std::size_t> cwt_of;
  if (options.cwt_receivers.empty()) {
    std::vector<Receiver> ordered;
    for (const ReceiverResult& rr : results) ordered.push_back(*rr.rx);
    return default_cwt_receivers(ordered, options.cwt_distances);
  }
  for (const std::string& name : options.cwt_receivers) {
    const auto it = std::find_if(results.begin(), results.end(),
                                 [&](const ReceiverResult& rr) { return rr.rx->name == name; });
    if (it == results.end()) {
      std::vector<std::string> names;
      for (const ReceiverResult& rr : results) names.push_back(rr.rx->name);
      throw std::runtime_error("CWT receiver '" + name + "' is not in receivers.csv in " +
                               quoted(results_dir) + "; its receivers are " + list_names(names) +
                               ". Name one of them");
    }
    cwt_of.push_back(static_cast<std::size_t>(it - results.begin()));
  }
  return cwt_of;
}

CwtOptions cwt_options_for(const PostOptions& options, const UniformGrid& grid,
                           std::vector<std::size_t>& cwt_of, std::vector<std::string>& warnings) {
  const std::size_t n = grid.count;
  CwtOptions cwt_options;
  cwt_options.omega0 = options.cwt_omega0;
  cwt_options.f_min = options.cwt_f_min;
  cwt_options.f_max = std::min(options.cwt_f_max, 0.4 / grid.dt);
  cwt_options.n_freq = options.cwt_n_freq;
  cwt_options.time_stride = std::max<std::size_t>(
      1, (n + options.cwt_max_times - 1) / std::max<std::size_t>(1, options.cwt_max_times));
  if (cwt_options.f_max < options.cwt_f_max)
    warnings.push_back("CWT: f_max lowered from " + number_text(options.cwt_f_max, 9) + " Hz to " +
                       number_text(cwt_options.f_max, 9) + " Hz (0.4 of the sampling rate)");
  // The zero padding for f_min's wavelet is 6 scales, 5.8 s at 1 Hz whatever the record's
  // length: a step of 1e-300 s asked for 1e300 samples (found by the post fuzz target,
  // docs/fuzzing.md). Beyond 64 records (and 65536 samples: 1 Hz at steps of 89 us or more) the
  // wavelet at f_min outlasts the record tenfold and its |W| is all cone of influence: f_min rises
  // to the lowest frequency within that padding (it falls as 1 / f).
  const double padding_allowed =
      std::min(kMaxCwtPadding, std::max(64.0 * static_cast<double>(n), 65536.0));
  if (const double padding = cwt_padding(grid.dt, cwt_options);
      !cwt_of.empty() && padding > padding_allowed) {
    const double raised = cwt_options.f_min * padding / padding_allowed;
    warnings.push_back("CWT: f_min raised from " + number_text(cwt_options.f_min, 9) + " Hz to " +
                       number_text(raised, 9) + " Hz: at the record's step of " +
                       number_text(grid.dt, 9) + " s its wavelet needs " + number_text(padding, 9) +
                       " samples of zero padding, more than " + number_text(padding_allowed, 9) +
                       " (64 times the record's samples, at least 65536)");
    cwt_options.f_min = raised;
  }
  if (!cwt_of.empty() && !(cwt_options.f_min < cwt_options.f_max)) {
    warnings.push_back("CWT skipped: f_min = " + number_text(cwt_options.f_min, 9) +
                       " Hz is not below f_max = " + number_text(cwt_options.f_max, 9) + " Hz");
    cwt_of.clear();
  }
  return cwt_options;
}

}  // namespace rumble::post::detail
