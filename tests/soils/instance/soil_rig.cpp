#include "soil_rig.hpp"

#include <numbers>

#include "plugin/built_soils.hpp"
#include "scenario/schema_check.hpp"

namespace rumble::soiltest {

std::unique_ptr<SoilInstance> make_soil(const std::string& type, const nlohmann::json& params,
                                        const std::vector<rumble_footprint>& layout) {
  // The params as the host hands them over: with the type's schema defaults filled in (as
  // scenario validation does; the FEM soil reads every defaulted key as given).
  nlohmann::json filled = params;
  scenario::SchemaChecker(soil_type(type).params_schema).fill_defaults(filled);
  return lay_soil(soil_type(type), "/soil", filled, ".", layout);
}

nlohmann::json soil_properties(double E, double nu, double rho) {
  return {{"E", E}, {"nu", nu}, {"rho", rho}};
}

Lumped lumped_parameters(SoilInstance& soil, Index n, double f_probe_hz) {
  const double w = 2.0 * std::numbers::pi * f_probe_hz;
  const MatrixXcd d0 = receptance(soil, 0.0, n).inverse();
  const MatrixXcd dw = receptance(soil, f_probe_hz, n).inverse();
  const Index i = n >= 3 ? 1 : 0;  // an interior footprint where there is one
  const double neighbours = (i > 0 ? 1.0 : 0.0) + (i + 1 < n ? 1.0 : 0.0);
  Lumped p;
  if (n >= 2) {
    p.k_c = -d0(0, 1).real();
    p.c_c = -dw(0, 1).imag() / w;
  }
  p.k_f = d0(i, i).real() - neighbours * p.k_c;
  p.c_f = dw(i, i).imag() / w - neighbours * p.c_c;
  p.m_f = (d0(i, i).real() - dw(i, i).real()) / (w * w);
  return p;
}

nlohmann::json clm_params(const Lumped& p) {
  return {{"m_f", p.m_f}, {"k_f", p.k_f}, {"c_f", p.c_f}, {"k_c", p.k_c}, {"c_c", p.c_c}};
}

}  // namespace rumble::soiltest
