#include "track_spec/track_config.hpp"

namespace rumble {

TrackConfig TrackConfig::from_json(const nlohmann::json& track) {
  TrackConfig c;
  const auto& sl = track.at("sleepers");
  c.sleeper_count = sl.at("count").get<int>();
  c.sleeper_spacing = sl.at("spacing").get<double>();
  c.sleeper_mass = sl.at("mass").get<double>();
  c.footprint_length = sl.at("footprint").at("length").get<double>();
  c.footprint_width = sl.at("footprint").at("width").get<double>();
  const auto& rail = track.at("rail");
  c.rail_E = rail.at("E").get<double>();
  c.rail_I = rail.at("I").get<double>();
  c.rail_mass_per_length = rail.at("mass_per_length").get<double>();
  c.elements_per_bay = rail.value("elements_per_bay", 4);
  c.overhang_bays = rail.value("overhang_bays", 1);
  c.pad_k = track.at("railpad").at("k").get<double>();
  c.pad_c = track.at("railpad").at("c").get<double>();
  c.ballast_k = track.at("ballast").at("k").get<double>();
  c.ballast_c = track.at("ballast").at("c").get<double>();
  if (track.contains("damping")) {
    c.rayleigh_alpha = track["damping"].value("rayleigh_alpha", 0.0);
    c.rayleigh_beta = track["damping"].value("rayleigh_beta", 0.0);
  }
  if (track.contains("contact")) {
    const auto& ct = track["contact"];
    if (ct.contains("hertz_constant")) c.hertz_constant = ct["hertz_constant"].get<double>();
    c.rail_radius = ct.value("rail_radius", 0.3);
    c.contact_E = ct.value("E", 2.1e11);
    c.contact_nu = ct.value("nu", 0.3);
  }
  if (track.contains("integrator")) {
    const auto& in = track["integrator"];
    if (in.contains("micro_step")) c.micro_step = in["micro_step"].get<double>();
    c.newmark_gamma = in.value("gamma", 0.5);
  }
  if (track.contains("unevenness")) c.unevenness = track["unevenness"];
  return c;
}

}  // namespace rumble
