#include "vehicle_harness.hpp"

#include <fstream>
#include <sstream>
#include <stdexcept>

#include "plugin/registry.hpp"

namespace rumble::test {
namespace {

/// The registry, with the two vehicle libraries loaded once per process.
const PluginRegistry& registry() {
  static const PluginRegistry r = [] {
    PluginRegistry reg;
    reg.load_library(std::string(RUMBLE_TEST_PLUGIN_DIR) + "/quarter_car.so");
    reg.load_library(std::string(RUMBLE_TEST_PLUGIN_DIR) + "/mbs.so");
    return reg;
  }();
  return r;
}

const rumble_factory& factory(const std::string& type) {
  const ComponentType* t = registry().find(RUMBLE_KIND_VEHICLE, type);
  if (t == nullptr) throw std::runtime_error("vehicle type not registered: " + type);
  return t->factory();
}

rumble_host make_host(const std::string& scenario_dir) {
  rumble_host h{};
  h.struct_size = sizeof(rumble_host);
  h.abi_minor = RUMBLE_ABI_MINOR;
  h.scenario_dir = scenario_dir.c_str();
  return h;
}

}  // namespace

std::string vehicles_dir() {
  return std::string(RUMBLE_TEST_SOURCE_DIR) + "/scenarios/vehicles";
}

std::string read_text(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw std::runtime_error("cannot read " + path);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

std::string creation_error(const std::string& type, const std::string& params_json,
                           const std::string& scenario_dir) {
  const rumble_factory& f = factory(type);
  const rumble_host host = make_host(scenario_dir);
  rumble_instance* instance = nullptr;
  const char* error = nullptr;
  const rumble_status s = f.create(params_json.c_str(), &host, &instance, &error);
  if (s == RUMBLE_OK) {
    static_cast<const rumble_vehicle_api*>(f.api)->common.destroy(instance);
    return "";
  }
  return error != nullptr ? error : "(no message)";
}

TestVehicle::TestVehicle(const std::string& type, const std::string& params_json,
                         const std::string& scenario_dir)
    : scenario_dir_(scenario_dir) {
  const rumble_factory& f = factory(type);
  api_ = static_cast<const rumble_vehicle_api*>(f.api);
  host_ = make_host(scenario_dir_);
  const char* error = nullptr;
  if (f.create(params_json.c_str(), &host_, &self_, &error) != RUMBLE_OK) {
    throw std::runtime_error(std::string("create failed: ") + (error ? error : ""));
  }
  std::uint64_t n = 0;
  check(api_->dof_count(self_, &n), "dof_count");
  n_ = static_cast<Eigen::Index>(n);
  std::uint64_t nw = 0;
  check(api_->wheels(self_, nullptr, 0, &nw), "wheels");
  wheels_.resize(nw);
  check(api_->wheels(self_, wheels_.data(), nw, &nw), "wheels");
}

TestVehicle::~TestVehicle() {
  if (self_ != nullptr) api_->common.destroy(self_);
}

void TestVehicle::check(rumble_status status, const char* call) const {
  if (status != RUMBLE_OK) {
    throw std::runtime_error(std::string(call) + " returned " + std::to_string(status) + ": " +
                             api_->common.last_message(self_));
  }
}

// The calls a host makes: the ABI's forms with array lengths.
MatrixXd TestVehicle::mass(const VectorXd& q) {
  MatrixXd m(n_, n_);
  const auto n = static_cast<std::uint64_t>(n_);
  check(api_->mass_matrix2(self_, q.data(), n, m.data(), n * n), "mass_matrix");
  return m;
}

VectorXd TestVehicle::forces(const VectorXd& q, const VectorXd& qd) {
  VectorXd f(n_);
  check(api_->forces2(self_, 0.0, q.data(), qd.data(), static_cast<std::uint64_t>(n_), f.data()),
        "forces");
  return f;
}

void TestVehicle::wheel_kinematics(const VectorXd& q, VectorXd& z, MatrixXd& jacobian) {
  z.resize(wheel_count());
  jacobian.resize(wheel_count(), n_);
  check(api_->wheel_kinematics2(self_, q.data(), static_cast<std::uint64_t>(n_), z.data(),
                                static_cast<std::uint64_t>(wheel_count()), jacobian.data()),
        "wheel_kinematics");
}

void TestVehicle::tangent(const VectorXd& q, const VectorXd& qd, MatrixXd& k, MatrixXd& c) {
  k.resize(n_, n_);
  c.resize(n_, n_);
  if (api_->tangent2 == nullptr) throw std::runtime_error("no tangent");
  check(api_->tangent2(self_, 0.0, q.data(), qd.data(), static_cast<std::uint64_t>(n_), k.data(),
                       c.data()),
        "tangent");
}

std::vector<std::string> TestVehicle::output_names() {
  std::uint64_t n = 0;
  check(api_->output_names2(self_, nullptr, 0, &n), "output_names");
  std::vector<const char*> raw(static_cast<std::size_t>(n), nullptr);
  check(api_->output_names2(self_, raw.data(), n, &n), "output_names");
  return std::vector<std::string>(raw.begin(), raw.end());
}

VectorXd TestVehicle::outputs(const VectorXd& q, const VectorXd& qd) {
  VectorXd v(static_cast<Eigen::Index>(output_names().size()));
  check(api_->outputs2(self_, 0.0, q.data(), qd.data(), static_cast<std::uint64_t>(n_), v.data(),
                       static_cast<std::uint64_t>(v.size())),
        "outputs");
  return v;
}

}  // namespace rumble::test
