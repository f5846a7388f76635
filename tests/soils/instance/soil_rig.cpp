#include "soil_rig.hpp"

#include <numbers>
#include <stdexcept>

#include "scenario/schema_check.hpp"

namespace rumble::soiltest {

const PluginRegistry& registry() {
  static const PluginRegistry r = [] {
    PluginRegistry loaded;
    loaded.load_directory(RUMBLE_TEST_PLUGIN_DIR);
    return loaded;
  }();
  return r;
}

const ComponentType& soil_type(const std::string& name) {
  const ComponentType* type = registry().find(RUMBLE_KIND_SOIL, name);
  if (type == nullptr) {
    throw std::runtime_error("soil type '" + name + "' not found in " + RUMBLE_TEST_PLUGIN_DIR);
  }
  return *type;
}

std::vector<rumble_footprint> sleeper_row(std::size_t n, double spacing, double length,
                                          double width) {
  std::vector<rumble_footprint> row(n);
  for (std::size_t i = 0; i < n; ++i)
    row[i] = {static_cast<double>(i) * spacing, 0.0, length, width};
  return row;
}

std::unique_ptr<SoilInstance> make_soil(const std::string& type, const nlohmann::json& params,
                                        const std::vector<rumble_footprint>& layout) {
  // The params as the host hands them over: with the type's schema defaults filled in (as
  // scenario validation does; the FEM soil reads every defaulted key as given).
  nlohmann::json filled = params;
  scenario::SchemaChecker(soil_type(type).params_schema).fill_defaults(filled);
  auto soil = std::make_unique<SoilInstance>(soil_type(type), "/soil", filled, ".");
  soil->accept_layout(layout);
  return soil;
}

nlohmann::json soil_properties(double E, double nu, double rho) {
  return {{"E", E}, {"nu", nu}, {"rho", rho}};
}

VectorXd static_displacement(SoilInstance& soil, const VectorXd& F) {
  const std::vector<double> f(F.data(), F.data() + F.size());
  std::vector<double> u;
  soil.initialize(0.0, f, u);
  return Eigen::Map<const VectorXd>(u.data(), static_cast<Index>(u.size()));
}

void advance_linear(SoilInstance& soil, double t, double H, const VectorXd& f0,
                    const VectorXd& f1) {
  const Index n = f0.size();
  std::vector<double> coeff(static_cast<std::size_t>(2 * n));
  Eigen::Map<VectorXd>(coeff.data(), n) = f0;
  Eigen::Map<VectorXd>(coeff.data() + n, n) = f1 - f0;
  const rumble_waveform w{1, static_cast<std::uint64_t>(n), coeff.data()};
  soil.advance(t, H, w);
}

void advance_held(SoilInstance& soil, double t, double H, const VectorXd& f) {
  const rumble_waveform w{0, static_cast<std::uint64_t>(f.size()), f.data()};
  soil.advance(t, H, w);
}

Motion motion(const SoilInstance& soil, Index n) {
  Motion m{VectorXd(n), VectorXd(n)};
  soil.motion(m.u.data(), m.v.data(), static_cast<std::size_t>(n));
  return m;
}

MatrixXcd receptance(SoilInstance& soil, double f_hz, Index n) {
  std::vector<std::complex<double>> h;
  if (!soil.frequency_response(f_hz, static_cast<std::size_t>(n), h)) {
    throw std::runtime_error("soil '" + soil.type_name() + "' offers no frequency response");
  }
  return Eigen::Map<const MatrixXcd>(h.data(), n, n);  // column-major, as the ABI writes it
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
