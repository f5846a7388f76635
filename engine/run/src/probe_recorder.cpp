#include "run/probe_recorder.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <rumble/host_resources.hpp>
#include <sstream>

#include "core/errors.hpp"
#include "core/logging.hpp"
#include "core/number_text.hpp"
#include "plugin/instance.hpp"
#include "results/results_directory.hpp"
#include "scenario/run_size.hpp"

namespace rumble {

ProbeRecorder::ProbeRecorder(ResultsDirectory& results, SoilInstance& soil,
                             const std::vector<scenario::ReceiverSpec>& points, double t_end,
                             bool size_confirmed)
    : soil_(soil),
      points_(points),
      t_end_(t_end),
      size_confirmed_(size_confirmed),
      ppv_z_(points.size(), 0.0),
      ppv_3c_(points.size(), 0.0) {
  std::vector<std::string> cols{"t [s]"};
  for (const scenario::ReceiverSpec& p : points_) {
    for (const char* c : {"vx [m/s]", "vy [m/s]", "vz [m/s]", "ux [m]", "uy [m]", "uz [m]"})
      cols.push_back(p.name + " " + c);
  }
  csv_ = std::make_unique<CsvFile>(results.file("receivers.csv"), cols);
  resolution_ = soil_.probe_resolution();
  if (resolution_) log_resolution();
}

void ProbeRecorder::log_resolution() const {
  std::string line;
  for (std::size_t p = 0; p < points_.size(); ++p) {
    const double f = resolution_->f_hz[p];
    line += (p == 0 ? "" : ", ") + points_[p].name + " " +
            (f > 0.0 ? number_text(f, 3) + " Hz" : std::string("unknown"));
  }
  logger("engine")->info(
      "receivers resolved to: {} ({}); what a receiver records above its frequency is the "
      "discretisation's, not the ground's: post/ gives each receiver's share of energy above it "
      "and its indicators below it",
      line, resolution_->rule);
}

void ProbeRecorder::check_projected_size(double t) const {
  const double columns = 1.0 + static_cast<double>(points_.size() * RUMBLE_PROBE_VALUES);
  const double bytes = samples_ * (t_end_ / t) * columns * scenario::kBytesPerValue;
  // What is still to come must fit the disk, --yes or not (a full disk ends the run anyway).
  const double to_come = bytes * (1.0 - t / t_end_);
  const std::string dir = csv_->path().parent_path().string();
  const double free = free_disk_bytes(dir);
  logger("engine")->info(
      "receivers.csv: about {} bytes projected ({} samples a second over {} s; {} bytes free "
      "there)",
      number_text(bytes, 3), number_text(samples_ / t, 3), number_text(t_end_, 3),
      number_text(free, 3));
  std::ostringstream m;
  m.precision(3);
  m << "/outputs/receiver_interval: receivers.csv would take about " << bytes / (1u << 30)
    << " GiB (the soil samples its receivers " << samples_ / t << " times a second, " << columns
    << " values a row, " << t_end_ << " s), ";
  if (to_come > free) {
    m << "and the " << to_come / (1u << 30) << " GiB still to come are more than the "
      << free / (1u << 30) << " GiB free under " << dir
      << " (--yes does not waive this); set outputs.receiver_interval (a sample every 1e-4 s "
         "resolves 5 kHz), list fewer receivers, or free space there";
    throw RunError(m.str());
  }
  if (bytes <= scenario::kMaxBytesWritten || size_confirmed_) return;
  m << "more than the " << scenario::kMaxBytesWritten / (1u << 30)
    << " GiB limit on time histories; set outputs.receiver_interval (a sample every 1e-4 s "
       "resolves 5 kHz), list fewer receivers, or confirm the size with --yes";
  throw RunError(m.str());
}

void ProbeRecorder::take() {
  times_.clear();
  values_.clear();
  soil_.take_probe_samples(times_, values_);
  samples_ += static_cast<double>(times_.size());
  if (!projected_ && !times_.empty() && times_.back() > 0.0) {
    projected_ = true;
    check_projected_size(times_.back());
  }
  const std::size_t width = points_.size() * RUMBLE_PROBE_VALUES;
  for (std::size_t s = 0; s < times_.size(); ++s) {
    const double* row = values_.data() + s * width;
    for (std::size_t p = 0; p < points_.size(); ++p) {
      const double* v = row + p * RUMBLE_PROBE_VALUES;  // vx vy vz ux uy uz
      ppv_z_[p] = std::max(ppv_z_[p], std::abs(v[2]));
      ppv_3c_[p] = std::max(ppv_3c_[p], std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]));
    }
    csv_->row(times_[s], row, width);
  }
}

nlohmann::json ProbeRecorder::peaks() const {
  nlohmann::json out = nlohmann::json::array();
  for (std::size_t p = 0; p < points_.size(); ++p) {
    out.push_back({{"name", points_[p].name},
                   {"x_m", points_[p].x},
                   {"distance_m", points_[p].y},
                   {"depth_m", points_[p].depth},
                   {"ppv_m_s", ppv_z_[p]},
                   {"ppv_3c_m_s", ppv_3c_[p]},
                   {"resolved_f_hz", resolution_ && resolution_->f_hz[p] > 0.0
                                         ? nlohmann::json(resolution_->f_hz[p])
                                         : nlohmann::json()}});
  }
  return out;
}

}  // namespace rumble
