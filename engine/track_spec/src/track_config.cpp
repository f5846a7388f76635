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
  c.elements_per_bay = rail.at("elements_per_bay").get<int>();
  c.overhang_bays = rail.at("overhang_bays").get<int>();
  c.pad_k = track.at("railpad").at("k").get<double>();
  c.pad_c = track.at("railpad").at("c").get<double>();
  c.ballast_k = track.at("ballast").at("k").get<double>();
  c.ballast_c = track.at("ballast").at("c").get<double>();
  const auto& damping = track.at("damping");
  c.rayleigh_alpha = damping.at("rayleigh_alpha").get<double>();
  c.rayleigh_beta = damping.at("rayleigh_beta").get<double>();
  const auto& ct = track.at("contact");
  if (ct.contains("hertz_constant")) c.hertz_constant = ct.at("hertz_constant").get<double>();
  c.rail_radius = ct.at("rail_radius").get<double>();
  c.contact_E = ct.at("E").get<double>();
  c.contact_nu = ct.at("nu").get<double>();
  const auto& in = track.at("integrator");
  if (in.contains("micro_step")) c.micro_step = in.at("micro_step").get<double>();
  c.newmark_gamma = in.at("gamma").get<double>();
  c.unevenness = UnevennessSpec::from_json(track.at("unevenness"));
  return c;
}

}  // namespace rumble
