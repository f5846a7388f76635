// What the FEM soil hands out besides the footprints' motion: receivers' records, VTU fields,
// the exported mesh and the linear matrices. None of them changes the soil's motion, so they sit
// apart from the code that does.
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <sstream>
#include <stdexcept>
#include <string>
#include <system_error>
#include <vector>

#include "boundary/static_far_field.hpp"
#include "fem_soil.hpp"
#include "frequency/resolved_band.hpp"
#include "mesh/gmsh_model.hpp"
#include "mesh/track_region.hpp"
#include "operator/linear_matrices.hpp"
#include "output/probe_locator.hpp"
#include "output/vtu_writer.hpp"
#include "results_file.hpp"

namespace rumble::fem {

void FemSoil::set_probes(const std::vector<rumble::Probe>& probes, double sample_interval) {
  require_layout("set_probes");
  if (distributed_) return set_probes_distributed(probes, sample_interval);
  set_probes_here(probes, sample_interval);
}

void FemSoil::set_probes_here(const std::vector<rumble::Probe>& probes, double sample_interval) {
  probes_.clear();
  for (const rumble::Probe& p : probes) {
    if (op_->pml() && !pml_profile().inside_physical_box({p.x, p.y, p.depth})) {
      std::ostringstream m;
      m << "fem: probe \"" << p.name << "\" at (" << p.x << ", " << p.y << ", " << p.depth
        << ") m lies in the perfectly matched layer, whose motion is not physical; move it into "
           "the box (within params/mesh/radius = "
        << plan_.radius << " m of the footprints, depth at most " << plan_.radius
        << " m) or raise mesh.radius";
      throw std::invalid_argument(m.str());
    }
    probes_.push_back(rumble::fem::locate_probe(mesh_, p.x, p.y, p.depth, p.name));
  }
  std::vector<Eigen::Vector3d> points;
  for (const rumble::Probe& p : probes) points.emplace_back(p.x, p.y, p.depth);
  probe_resolution_ = rumble::fem::path_resolved_frequency(
      mesh_, rumble::fem::TrackRegion::of(footprints_), points, rayleigh_speed(),
      settings_.mesh.elements_per_wavelength);
  row_.assign(probes.size() * RUMBLE_PROBE_VALUES, 0.0);
  sample_interval_ = sample_interval;
  next_sample_ = -1.0;
}

std::vector<double> FemSoil::probe_resolution(std::string& rule) const {
  rule = "f = c_R / (n h): n = " + format(settings_.mesh.elements_per_wavelength) +
         " linear elements per Rayleigh wavelength (mesh.elements_per_wavelength), c_R = " +
         format(rayleigh_speed()) +
         " m/s (the slowest layer's), h the mean edge of the largest tetrahedron on the "
         "straight path from the nearest footprint to the receiver (docs/fem-soil.md 2.2)";
  return probe_resolution_;
}

void FemSoil::record_probes(double t) {
  if (probes_.empty()) return;
  if (sample_interval_ > 0.0) {
    if (next_sample_ < 0.0) next_sample_ = t;
    if (t < next_sample_ - 1e-9 * sample_interval_) return;
    next_sample_ +=
        sample_interval_ * std::max(1.0, std::floor((t - next_sample_) / sample_interval_) + 1.0);
  }
  if (distributed_) {  // (each receiver sampled on a rank that holds it, gathered on rank 0)
    distributed_->sample_probes(row_.data());
    if (distributed_->root()) samples().push(t, row_.data());
    return;
  }
  for (std::size_t p = 0; p < probes_.size(); ++p) {
    double* out = row_.data() + p * RUMBLE_PROBE_VALUES;
    for (int c = 0; c < 6; ++c) out[c] = 0.0;
    for (int a = 0; a < 4; ++a) {
      const std::int64_t node = probes_[p].nodes[a];
      const double w = probes_[p].weights[a];
      for (int c = 0; c < 3; ++c) {
        out[c] += w * state_.v[3 * node + c];
        out[3 + c] += w * (u_static_[3 * node + c] + state_.w[3 * node + c]);
      }
    }
  }
  samples().push(t, row_.data());
}

void FemSoil::write_fields(double t, const std::string& path) {
  require_layout("write_fields");
  if (distributed_) return write_fields_distributed(t, path);
  export_if_due();  // `rumble mesh` gives a directory, then asks for the fields only
  rumble::fem::write_vtu(path, t, mesh_, u_static_ + state_.w, state_.v);
}

void FemSoil::export_if_due() {
  if (!export_due_ || host_.results_dir().empty()) return;
  export_due_ = false;
  const std::string where =
      "fem: params/mesh/export: " + nlohmann::json(settings_.mesh.export_file).dump();
  const std::filesystem::path path = rumble::fem::new_results_file(
      host_.results_dir(), settings_.mesh.export_file, where);  // made empty, never replaced
  std::string why;
  try {
    rumble::fem::write_mesh_file(mesh_, settings_, footprints_, path.string());
  } catch (const std::exception& e) {
    why = std::string(" (") + e.what() + ")";
  }
  std::error_code error;
  if (!why.empty() || std::filesystem::file_size(path, error) == 0) {
    std::filesystem::remove(path, error);  // the file made above, not left empty
    throw std::runtime_error(where + ": could not write the mesh to " + path.string() + why +
                             "; check that its folder can be written, or give another path");
  }
  host_.info("fem: mesh written to " + path.string() + " (mesh.file reads it back)");
}

void FemSoil::linear_matrix(rumble_matrix which, rumble::CscMatrix& out) {
  require_layout("linear_matrix");
  if (distributed_)
    refuse_whole_operator("linear_matrix (the monolithic coupler, rumble stability)");
  refuse_with_pml("its matrices (the monolithic coupler, rumble stability)");
  if (settings_.damping.maxwell)
    throw std::invalid_argument(
        "fem: params/damping/model: the Maxwell mechanisms' memory has no place in M, C and K "
        "(the monolithic coupler, rumble stability); use damping.model \"rayleigh\" for them, "
        "got \"maxwell\"");
  rumble::fem::linear_matrix(op_->soil(), weights_, settings_.damping.mass_coefficient(),
                             settings_.damping.stiffness_coefficient(), which, out);
  if (which == RUMBLE_MATRIX_STIFFNESS && settings_.boundary.far_field_follows &&
      rumble::fem::static_far_field_applies(settings_))
    host_.info(
        "fem: the linear matrices hold the far field's traction at the statics' (a load "
        "change settles through the springs alone); the soil's own steps follow the forces: "
        "set params/boundary/far_field \"static\" for the same motion both ways "
        "(docs/fem-soil.md section 3.2)");
}

void FemSoil::refuse_with_pml(const std::string& what) const {
  if (op_->pml())
    throw std::invalid_argument(
        "fem: params/boundary/type: the perfectly matched layer has no form for " + what +
        " yet; use boundary.type \"viscous_spring\" for it");
}

}  // namespace rumble::fem
