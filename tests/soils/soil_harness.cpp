#include "soil_harness.hpp"

#include <dlfcn.h>

#include <map>
#include <memory>
#include <nlohmann/json.hpp>
#include <stdexcept>

#include "scenario/schema_check.hpp"

namespace rumble::test {
namespace {

const rumble_plugin_descriptor& descriptor(const std::string& type) {
  static std::map<std::string, const rumble_plugin_descriptor*> loaded;
  if (auto it = loaded.find(type); it != loaded.end()) return *it->second;
  const std::string path = std::string(RUMBLE_TEST_PLUGIN_DIR) + "/" + type + ".so";
  void* library = dlopen(path.c_str(), RTLD_NOW | RTLD_LOCAL);  // never closed
  if (library == nullptr) throw std::runtime_error("cannot load " + path + ": " + dlerror());
  void* entry = dlsym(library, RUMBLE_PLUGIN_ENTRY_SYMBOL);
  if (entry == nullptr) throw std::runtime_error(path + " exports no entry point");
  const auto* d = reinterpret_cast<rumble_plugin_entry_fn>(entry)();
  loaded[type] = d;
  return *d;
}

rumble_host make_host() {
  rumble_host h{};
  h.struct_size = sizeof(rumble_host);
  h.abi_minor = RUMBLE_ABI_MINOR;
  h.scenario_dir = ".";
  return h;
}

// The params as the host hands them to the plugin: with every default of the type's schema filled
// in (the engine's own SchemaChecker). Not validated: the tests of the plugins' own refusals hand
// them what the schema would refuse; the schema's refusals are tested against the schema.
std::string with_defaults(const rumble_factory& f, const std::string& params_json) {
  nlohmann::json params = nlohmann::json::parse(params_json, nullptr, false);
  if (!params.is_object() || f.params_schema == nullptr) return params_json;
  static std::map<std::string, std::unique_ptr<scenario::SchemaChecker>> checkers;
  auto& checker = checkers[f.type_name];
  if (!checker) checker = std::make_unique<scenario::SchemaChecker>(f.params_schema);
  checker->fill_defaults(params);
  return params.dump();
}

}  // namespace

const rumble_factory& soil_factory(const std::string& type) {
  const rumble_plugin_descriptor& d = descriptor(type);
  for (std::uint64_t i = 0; i < d.n_factories; ++i) {
    const rumble_factory& f = d.factories[i];
    if (f.kind == RUMBLE_KIND_SOIL && type == f.type_name) return f;
  }
  throw std::runtime_error("no soil type " + type + " in its plugin");
}

std::string creation_error(const std::string& type, const std::string& params_json) {
  const rumble_factory& f = soil_factory(type);
  const rumble_host host = make_host();
  rumble_instance* instance = nullptr;
  const char* error = nullptr;
  const std::string params = with_defaults(f, params_json);
  if (f.create(params.c_str(), &host, &instance, &error) == RUMBLE_OK) {
    static_cast<const rumble_soil_api*>(f.api)->common.destroy(instance);
    return "";
  }
  return error != nullptr ? error : "(no message)";
}

std::vector<rumble_footprint> sleeper_row(std::size_t n, double spacing, double length,
                                          double width) {
  std::vector<rumble_footprint> row(n);
  for (std::size_t i = 0; i < n; ++i)
    row[i] = {static_cast<double>(i) * spacing, 0.0, length, width};
  return row;
}

TestSoil::TestSoil(const std::string& type, const std::string& params_json) : host_(make_host()) {
  host_.host_data = &logs_;
  host_.log = [](void* data, int32_t /*level*/, const char* message) {
    static_cast<std::vector<std::string>*>(data)->emplace_back(message);
  };
  const rumble_factory& f = soil_factory(type);
  api_ = static_cast<const rumble_soil_api*>(f.api);
  const char* error = nullptr;
  const std::string params = with_defaults(f, params_json);
  if (f.create(params.c_str(), &host_, &self_, &error) != RUMBLE_OK)
    throw std::runtime_error(std::string("create failed: ") + (error ? error : ""));
}

void TestSoil::set_results_dir(const std::string& dir) {
  results_dir_ = dir;
  host_.results_dir = results_dir_.c_str();
}

std::string TestSoil::last_log(const std::string& text) const {
  for (auto line = logs_.rbegin(); line != logs_.rend(); ++line)
    if (line->find(text) != std::string::npos) return *line;
  return "";
}

TestSoil::~TestSoil() {
  if (self_ != nullptr) api_->common.destroy(self_);
}

void TestSoil::check(rumble_status status, const char* call) const {
  if (status != RUMBLE_OK) {
    throw std::runtime_error(std::string(call) + " returned " + std::to_string(status) + ": " +
                             api_->common.last_message(self_));
  }
}

rumble_status TestSoil::try_accept_layout(const std::vector<rumble_footprint>& footprints,
                                          std::string* message) {
  const rumble_status s = api_->accept_layout(self_, footprints.data(), footprints.size());
  if (s == RUMBLE_OK) {
    n_ = static_cast<Eigen::Index>(footprints.size());
  } else if (message != nullptr) {
    *message = api_->common.last_message(self_);
  }
  return s;
}

void TestSoil::accept_layout(const std::vector<rumble_footprint>& footprints) {
  std::string message;
  if (try_accept_layout(footprints, &message) != RUMBLE_OK)
    throw std::runtime_error("accept_layout: " + message);
}

VectorXd TestSoil::initialize(const VectorXd& static_force) {
  VectorXd u(n_);
  check(api_->initialize(self_, 0.0, static_force.data(), u.data(), n_), "initialize");
  return u;
}

rumble_status TestSoil::try_advance(double t, double H, unsigned order, const VectorXd& coeff,
                                    std::string* message) {
  const rumble_waveform w{order, static_cast<std::uint64_t>(n_), coeff.data()};
  const rumble_status s = api_->advance(self_, t, H, &w);
  if (s != RUMBLE_OK && message != nullptr) *message = api_->common.last_message(self_);
  return s;
}

void TestSoil::advance(double t, double H, unsigned order, const VectorXd& coeff) {
  std::string message;
  if (try_advance(t, H, order, coeff, &message) != RUMBLE_OK)
    throw std::runtime_error("advance: " + message);
}

void TestSoil::advance_linear(double t, double H, const VectorXd& f0, const VectorXd& f1) {
  VectorXd coeff(2 * n_);
  coeff << f0, f1 - f0;
  advance(t, H, 1, coeff);
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
    check(api_->probe_samples(self_, times.data(), values.data(), times.size(), &n),
          "probe_samples");
    for (std::uint64_t s = 0; s < n; ++s)
      for (std::size_t p = 0; p < probes; ++p)
        sample(times[s], p, &values[(s * probes + p) * RUMBLE_PROBE_VALUES]);
  }
}

VectorXd TestSoil::displacement() {
  VectorXd u(n_), v(n_);
  check(api_->motion(self_, u.data(), v.data(), n_), "motion");
  return u;
}

VectorXd TestSoil::velocity() {
  VectorXd u(n_), v(n_);
  check(api_->motion(self_, u.data(), v.data(), n_), "motion");
  return v;
}

MatrixXcd TestSoil::receptance(double f_hz) {
  MatrixXd re(n_, n_), im(n_, n_);
  check(api_->frequency_response(self_, f_hz, re.data(), im.data(), n_), "frequency_response");
  return re.cast<std::complex<double>>() + std::complex<double>(0.0, 1.0) * im;
}

std::vector<double> TestSoil::save() {
  std::uint64_t size = 0;
  check(api_->common.state_size(self_, &size), "state_size");
  std::vector<double> state(size);
  check(api_->common.save_state(self_, state.data(), size), "save_state");
  return state;
}

void TestSoil::restore(const std::vector<double>& state) {
  check(api_->common.restore_state(self_, state.data(), state.size()), "restore_state");
}

}  // namespace rumble::test
