#include "soil_harness.hpp"

#include <spdlog/sinks/base_sink.h>

#include <complex>
#include <filesystem>
#include <map>
#include <memory>
#include <mutex>
#include <nlohmann/json.hpp>
#include <stdexcept>

#include "core/errors.hpp"
#include "core/logging.hpp"
#include "scenario/schema_check.hpp"

namespace rumble {

/// The plugin's handle of an instance (Instance's friend): TestSoil::self() for the tests that
/// call the plugin's own C table.
struct PluginHandle {
  static rumble_instance* of(const Instance& instance) { return instance.handle(); }
};

}  // namespace rumble

namespace rumble::test {
namespace {

/// The params as the host hands them to the plugin: with every default of the type's schema
/// filled in (the engine's own SchemaChecker). Not validated: the tests of the plugins' own
/// refusals hand them what the schema would refuse; the schema's refusals are tested against the
/// schema.
nlohmann::json with_defaults(const ComponentType& type, const std::string& params_json) {
  nlohmann::json params = nlohmann::json::parse(params_json);
  if (!params.is_object() || type.params_schema.empty()) return params;
  static std::map<std::string, std::unique_ptr<scenario::SchemaChecker>> checkers;
  auto& checker = checkers[type.type_name];
  if (!checker) checker = std::make_unique<scenario::SchemaChecker>(type.params_schema);
  checker->fill_defaults(params);
  return params;
}

/// A SoilInstance of `type` from `params_json`, as the host creates it; throws the engine's
/// ParamsRefused when the plugin refuses them.
std::unique_ptr<SoilInstance> create(const std::string& type, const std::string& params_json) {
  const nlohmann::json params = with_defaults(soil_type(type), params_json);
  return std::make_unique<SoilInstance>(soil_type(type), "/soil", params, ".");
}

/// The plugin's message `plugin` when the engine's exception `e` quotes it (the plugin refused),
/// else the engine's own message (the engine refused before the plugin was called).
std::string plugin_message(const std::exception& e, const std::string& plugin) {
  const std::string what = e.what();
  return !plugin.empty() && what.find(plugin) != std::string::npos ? plugin : what;
}

}  // namespace

const ComponentType& soil_type(const std::string& type) {
  static PluginRegistry registry;
  // Copies: the registry's list of types moves as libraries are added.
  static std::map<std::string, ComponentType> found;
  if (auto it = found.find(type); it != found.end()) return it->second;
  const std::filesystem::path file = std::filesystem::path(RUMBLE_TEST_PLUGIN_DIR) / (type + ".so");
  registry.load_library(file);
  const ComponentType* loaded = registry.find(RUMBLE_KIND_SOIL, type);
  if (loaded == nullptr)
    throw std::runtime_error("no soil type '" + type + "' in " + file.string());
  return found.emplace(type, *loaded).first->second;
}

const rumble_factory& soil_factory(const std::string& type) {
  return soil_type(type).factory();
}

std::string creation_error(const std::string& type, const std::string& params_json) {
  try {
    create(type, params_json);
  } catch (const ParamsRefused& e) {
    return e.plugin_message();
  } catch (const ConfigError& e) {
    return e.what();  // the engine refused before the plugin was called
  }
  return "";
}

std::vector<rumble_footprint> sleeper_row(std::size_t n, double spacing, double length,
                                          double width) {
  std::vector<rumble_footprint> row(n);
  for (std::size_t i = 0; i < n; ++i)
    row[i] = {static_cast<double>(i) * spacing, 0.0, length, width};
  return row;
}

VectorXd static_displacement(SoilInstance& soil, const VectorXd& F) {
  const std::vector<double> f(F.data(), F.data() + F.size());
  std::vector<double> u;
  soil.initialize(0.0, f, u);
  return Eigen::Map<const VectorXd>(u.data(), static_cast<Eigen::Index>(u.size()));
}

void advance_waveform(SoilInstance& soil, double t, double H, unsigned order,
                      const VectorXd& coeff) {
  const auto n = static_cast<std::uint64_t>(coeff.size() / (order + 1));
  const rumble_waveform w{order, n, coeff.data()};
  soil.advance(t, H, w);
}

void advance_linear(SoilInstance& soil, double t, double H, const VectorXd& f0,
                    const VectorXd& f1) {
  VectorXd coeff(2 * f0.size());
  coeff << f0, f1 - f0;
  advance_waveform(soil, t, H, 1, coeff);
}

void advance_held(SoilInstance& soil, double t, double H, const VectorXd& f) {
  advance_waveform(soil, t, H, 0, f);
}

Motion motion(const SoilInstance& soil, Eigen::Index n) {
  Motion m{VectorXd(n), VectorXd(n)};
  soil.motion(m.u.data(), m.v.data(), static_cast<std::size_t>(n));
  return m;
}

MatrixXcd receptance(SoilInstance& soil, double f_hz, Eigen::Index n) {
  std::vector<std::complex<double>> h;
  if (!soil.frequency_response(f_hz, static_cast<std::size_t>(n), h))
    throw std::runtime_error("soil '" + soil.type_name() + "' offers no frequency response");
  return Eigen::Map<const MatrixXcd>(h.data(), n, n);  // column-major, as the ABI writes it
}

// ---------------------------------------------------------------- TestSoil

/// Every message a logger hands it, in order.
class TestSoil::LogCapture final : public spdlog::sinks::base_sink<std::mutex> {
 public:
  const std::vector<std::string>& lines() const { return lines_; }

 protected:
  void sink_it_(const spdlog::details::log_msg& msg) override {
    lines_.emplace_back(msg.payload.data(), msg.payload.size());
  }
  void flush_() override {}

 private:
  std::vector<std::string> lines_;
};

TestSoil::TestSoil(const std::string& type, const std::string& params_json)
    // The logger the engine gives every soil of this type (Instance: "<kind>/<type>").
    : logger_(logger(std::string(kind_name(RUMBLE_KIND_SOIL)) + "/" + type)),
      logs_(std::make_shared<LogCapture>()) {
  logger_->sinks().push_back(logs_);
  try {
    soil_ = create(type, params_json);
    self_ = PluginHandle::of(*soil_);
  } catch (...) {
    stop_listening();
    throw;
  }
  api_ = static_cast<const rumble_soil_api*>(soil_factory(type).api);
}

TestSoil::~TestSoil() {
  soil_.reset();
  stop_listening();
}

void TestSoil::stop_listening() {
  std::erase(logger_->sinks(), static_cast<spdlog::sink_ptr>(logs_));
}

rumble_status TestSoil::refusal(const std::exception& e, const char* call,
                                std::string* message) const {
  if (message != nullptr) {
    const char* said = api_->common.last_message(self_);
    *message = plugin_message(e, said != nullptr ? said : "");
  }
  // The status the engine turned into `e` (Instance::check: "<call> refused: " for DISCARD,
  // "<call> failed fatally: " for FATAL); accept_layout's arrives as a ConfigError.
  const std::string what = e.what();
  if (dynamic_cast<const Discarded*>(&e) != nullptr ||
      what.find(std::string(call) + " refused: ") != std::string::npos)
    return RUMBLE_DISCARD;
  if (what.find(std::string(call) + " failed fatally: ") != std::string::npos) return RUMBLE_FATAL;
  return RUMBLE_ERROR;
}

rumble_status TestSoil::try_accept_layout(const std::vector<rumble_footprint>& footprints,
                                          std::string* message) {
  try {
    soil_->accept_layout(footprints);
  } catch (const std::runtime_error& e) {
    return refusal(e, "accept_layout", message);
  }
  n_ = static_cast<Eigen::Index>(footprints.size());
  return RUMBLE_OK;
}

void TestSoil::accept_layout(const std::vector<rumble_footprint>& footprints) {
  soil_->accept_layout(footprints);
  n_ = static_cast<Eigen::Index>(footprints.size());
}

VectorXd TestSoil::initialize(const VectorXd& static_force) {
  return static_displacement(*soil_, static_force);
}

void TestSoil::advance(double t, double H, unsigned order, const VectorXd& coeff) {
  const rumble_waveform w{order, static_cast<std::uint64_t>(n_), coeff.data()};
  soil_->advance(t, H, w);
}

rumble_status TestSoil::try_advance(double t, double H, unsigned order, const VectorXd& coeff,
                                    std::string* message) {
  try {
    advance(t, H, order, coeff);
  } catch (const std::runtime_error& e) {
    return refusal(e, "advance", message);
  }
  return RUMBLE_OK;
}

void TestSoil::advance_linear(double t, double H, const VectorXd& f0, const VectorXd& f1) {
  test::advance_linear(*soil_, t, H, f0, f1);
}

void TestSoil::drive_probes(const std::function<double(double)>& force, double H, double t_end,
                            std::size_t probes,
                            const std::function<void(double, std::size_t, const double*)>& sample) {
  if (n_ != 1) throw std::runtime_error("drive_probes: a soil of one footprint");
  std::vector<double> times(4096), values(times.size() * probes * RUMBLE_PROBE_VALUES);
  VectorXd f0(1), f1(1);
  for (int k = 0; k * H < t_end - 0.5 * H; ++k) {
    const double t = k * H;
    f0 << force(t);
    f1 << force(t + H);
    advance_linear(t, H, f0, f1);
    std::uint64_t n = 0;
    if (api_->probe_samples(self_, times.data(), values.data(), times.size(), &n) != RUMBLE_OK)
      throw std::runtime_error("probe_samples: " + std::string(api_->common.last_message(self_)));
    for (std::uint64_t s = 0; s < n; ++s)
      for (std::size_t p = 0; p < probes; ++p)
        sample(times[s], p, &values[(s * probes + p) * RUMBLE_PROBE_VALUES]);
  }
}

VectorXd TestSoil::displacement() {
  return motion(*soil_, n_).u;
}

VectorXd TestSoil::velocity() {
  return motion(*soil_, n_).v;
}

MatrixXcd TestSoil::receptance(double f_hz) {
  return test::receptance(*soil_, f_hz, n_);
}

std::vector<double> TestSoil::save() {
  std::uint64_t size = 0;
  std::vector<double> state;
  if (api_->common.state_size(self_, &size) == RUMBLE_OK) {
    state.resize(size);
    if (api_->common.save_state(self_, state.data(), size) == RUMBLE_OK) return state;
  }
  throw std::runtime_error("save: " + std::string(api_->common.last_message(self_)));
}

void TestSoil::restore(const std::vector<double>& state) {
  if (api_->common.restore_state(self_, state.data(), state.size()) != RUMBLE_OK)
    throw std::runtime_error("restore: " + std::string(api_->common.last_message(self_)));
}

const std::vector<std::string>& TestSoil::logs() const {
  return logs_->lines();
}

std::string TestSoil::last_log(const std::string& text) const {
  const std::vector<std::string>& lines = logs();
  for (auto line = lines.rbegin(); line != lines.rend(); ++line)
    if (line->find(text) != std::string::npos) return *line;
  return "";
}

void TestSoil::set_results_dir(const std::string& dir) {
  soil_->set_results_dir(dir);
}

}  // namespace rumble::test
