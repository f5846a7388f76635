#include "track_spec/unevenness_spec.hpp"

#include "core/number_text.hpp"
#include "track_spec/unevenness_psd.hpp"

namespace rumble {

UnevennessSpec UnevennessSpec::from_json(const nlohmann::json& u) {
  UnevennessSpec s;
  const std::string type = u.at("type").get<std::string>();
  if (type == "dip" || type == "bump") {
    s.kind = type == "dip" ? Kind::kDip : Kind::kBump;
    s.position = u.at("position").get<double>();
    s.length = u.at("length").get<double>();
    s.height = u.at(type == "dip" ? "depth" : "height").get<double>();
  } else if (type == "wheel_flat") {
    s.kind = Kind::kWheelFlat;
    s.length = u.at("length").get<double>();
    s.wheel = u.at("wheel").get<std::size_t>();
    if (u.contains("depth")) s.flat_depth = u.at("depth").get<double>();
    if (u.contains("first_impact")) s.first_impact = u.at("first_impact").get<double>();
  } else if (type == "random") {
    s.kind = Kind::kRandom;
    s.spectrum = u.at("class").get<std::string>();
    s.seed = u.at("seed").get<std::uint64_t>();
    s.wavelength_min = u.at("wavelength_min").get<double>();
    s.wavelength_max = u.at("wavelength_max").get<double>();
  }
  return s;
}

std::vector<UnevennessFinding> band_findings(const UnevennessSpec& s) {
  if (s.kind != UnevennessSpec::Kind::kRandom) return {};
  const double lo = s.wavelength_min, hi = s.wavelength_max;
  if (!(hi > lo))
    return {{"wavelength_max",
             "must be > wavelength_min = " + number_text(lo) + " m, got " + number_text(hi) + " m",
             "the profile covers wavelengths from wavelength_min to wavelength_max, e.g. 1 to "
             "30 m for track geometry"}};
  const auto spectrum = RoughnessSpectrum::from_name(s.spectrum);
  const std::string range = "the " + spectrum.name() +
                            " spectrum is defined for wavelengths from " +
                            number_text(spectrum.min_wavelength()) + " m to " +
                            number_text(spectrum.max_wavelength()) + " m";
  const std::string hint = spectrum.name() == "ISO3095"
                               ? "ISO 3095 is rail roughness (short waves); for track geometry "
                                 "(1 to 30 m) use an FRA class"
                               : "choose a band inside the spectrum's range";
  std::vector<UnevennessFinding> out;
  if (!spectrum.above_min(lo))
    out.push_back({"wavelength_min", range + ", got " + number_text(lo) + " m", hint});
  if (!spectrum.below_max(hi))
    out.push_back({"wavelength_max", range + ", got " + number_text(hi) + " m", hint});
  return out;
}

}  // namespace rumble
