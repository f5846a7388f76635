// mbs: a multibody vehicle in minimal coordinates defined in JSON (docs/vehicles.md), in the
// spirit of the seed paper's library: bodies placed by chains of homogeneous transformations
// driven by the DOFs, linear spring-dampers between body points, wheels at body points.
//
// Accuracy: positions, Jacobians and the quadratic velocity terms are exact (analytic chain
// derivatives, kinematics.hpp). The tangent K = -df/dq, C = -df/dq' is computed by complex-step
// differentiation, f'(x) = Im f(x + i h) / h, which has no subtractive cancellation: with
// h = 1e-20 its truncation error h^2 |f'''| / 6 is far below double round-off, so the tangent is
// exact to round-off (2 n complex force evaluations per call).
#include <algorithm>
#include <cmath>
#include <complex>
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <rumble/params_file.hpp>
#include <rumble/plugin.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "definition.hpp"
#include "dynamics.hpp"
#include "json_reader.hpp"
#include "kinematics.hpp"
#include "mbs_schema.hpp"

namespace rumble::mbs {
namespace {

using Complex = std::complex<double>;
using vehicles::fail;

constexpr double kComplexStep = 1e-20;  // imaginary step of the complex-step tangent

// A vehicle definition is a few kilobytes; the limit keeps /dev/zero or a mistaken data file
// from being read into memory (it once grew to 4 GB).
constexpr std::uintmax_t kMaxDefinitionBytes = 1u << 20;

nlohmann::json parse_json(const std::string& text, const std::string& where) {
  try {
    return nlohmann::json::parse(text);
  } catch (const nlohmann::json::parse_error& e) {
    // "[json.exception.parse_error.101] parse error at line 3, column 5: ..." without the tag.
    std::string what = e.what();
    if (const auto tag = what.find("] ");
        what.rfind("[json.exception", 0) == 0 && tag != std::string::npos)
      what.erase(0, tag + 2);
    fail(where, "not valid JSON: " + what, {},
         "a vehicle definition is one JSON object (docs/vehicles.md); is this the right file?");
  }
}

/// Refuses a key written twice in one object of a definition file: nlohmann keeps the last value
/// and drops the other without a word (the engine refuses the same in a scenario). `where` is the
/// file as written plus "#"; the refusal points at the repeated member.
void refuse_duplicate_keys(const std::string& text, const std::string& where) {
  struct Frame {
    bool object = false;
    std::string pointer;
    std::vector<std::string> keys;  // objects: the keys so far (a definition has a few)
    std::size_t index = 0;          // arrays: the next element's index
  };
  std::vector<Frame> stack;
  std::string duplicate;  // pointer of the first repeat found
  const auto child_pointer = [&]() -> std::string {
    if (stack.empty()) return "";
    Frame& parent = stack.back();
    if (parent.object) return parent.pointer + "/" + parent.keys.back();
    return parent.pointer + "/" + std::to_string(parent.index++);
  };
  using Event = nlohmann::json::parse_event_t;
  const auto callback = [&](int /*depth*/, Event event, nlohmann::json& parsed) {
    switch (event) {
      case Event::object_start:
      case Event::array_start: {
        Frame f;
        f.object = event == Event::object_start;
        f.pointer = child_pointer();
        stack.push_back(std::move(f));
        break;
      }
      case Event::object_end:
      case Event::array_end:
        stack.pop_back();
        break;
      case Event::key: {
        Frame& f = stack.back();
        const std::string key = parsed.get<std::string>();
        if (duplicate.empty() && std::find(f.keys.begin(), f.keys.end(), key) != f.keys.end())
          duplicate = f.pointer + "/" + key;
        f.keys.push_back(key);
        break;
      }
      case Event::value:
        if (!stack.empty() && !stack.back().object) ++stack.back().index;
        break;
    }
    return true;
  };
  try {
    const nlohmann::json parsed = nlohmann::json::parse(text, callback);  // a second, small parse
    static_cast<void>(parsed);
  } catch (const nlohmann::json::exception&) {
    return;  // parse_json says what is wrong with the text
  }
  if (!duplicate.empty()) {
    fail(where + duplicate,
         "duplicate key; JSON keeps only the last value and would drop the "
         "other without a word",
         {}, "keep one of the two");
  }
}

/// The text of the definition file `name` (relative to the scenario file's directory `dir`): a
/// regular file of at most kMaxDefinitionBytes, else a refusal at params/file naming the value
/// and the fix (rumble/params_file.hpp).
std::string read_definition_file(const nlohmann::json& name, const std::string& dir) {
  const std::filesystem::path path = rumble::checked_params_file(
      "params/file", name.get<std::string>(), vehicles::shown(name), dir,
      {.noun = "a vehicle definition",
       .file_noun = "a vehicle definition file (JSON)",
       .max_bytes = kMaxDefinitionBytes});
  std::ifstream in(path, std::ios::binary);
  if (!in) {
    fail("params/file", "cannot read \"" + path.string() + "\"", vehicles::shown(name),
         "check the file's permissions");
  }
  // At most one byte past the limit, in case the file grew since its size was read.
  std::string text(kMaxDefinitionBytes + 1, '\0');
  in.read(text.data(), static_cast<std::streamsize>(text.size()));
  text.resize(static_cast<std::size_t>(in.gcount()));
  if (text.size() > kMaxDefinitionBytes) {
    fail("params/file",
         "\"" + path.string() + "\" is too large (more than " +
             std::to_string(kMaxDefinitionBytes) + " bytes)",
         vehicles::shown(name), "is this the right file?");
  }
  return text;
}

/// params -> Definition: inline, or from the file named by params/file (relative to the
/// scenario directory); error pointers then read "<file as written>#/bodies/2/mass".
Definition load_definition(const std::string& params_json, const rumble::Host& host) {
  const nlohmann::json params = parse_json(params_json, "params");
  if (!params.is_object() || !params.contains("file")) return parse_definition(params, "params");
  const nlohmann::json& file = params.at("file");
  if (!file.is_string() || file.get<std::string>().empty()) {
    fail("params/file", "expected a non-empty string (a path)", vehicles::shown(file));
  }
  for (const auto& item : params.items()) {
    if (item.key() != "file") {
      fail("params/" + item.key(), "not allowed together with \"file\"", {},
           "put the whole definition in the file, or give it inline without \"file\"");
    }
  }
  const std::string name = file.get<std::string>();
  // (a scenario given as "x.json" has the directory "": the current one)
  const std::string text = read_definition_file(file, host.scenario_dir());
  nlohmann::json definition = parse_json(text, name + "#");
  refuse_duplicate_keys(text, name + "#");
  return parse_definition(definition, name + "#");
}

class MbsVehicle final : public rumble::Vehicle {
 public:
  static constexpr const char* kTypeName = "mbs";
  static constexpr const char* kSummary =
      "multibody vehicle from JSON: bodies on chains of transformations, spring-dampers, wheels "
      "(vertical plane)";
  /// Takes any step it is given (a coupler need not keep the other side's checkpoint for it).
  static constexpr std::uint64_t kCapabilities = rumble::kCapNeverRefuses;
  static const char* params_schema() { return mbs_params_schema(); }

  MbsVehicle(const std::string& params_json, const rumble::Host& host)
      : d_(load_definition(params_json, host)),
        n_(d_.dof_names.size()),
        kin_(d_),
        work_(n_),
        zeros_(n_, 0.0),
        kin_c_(d_),
        work_c_(n_),
        q_c_(n_),
        qd_c_(n_),
        f_c_(n_) {
    compute_nominal();
    check_mass_matrix();
  }

  std::size_t dof_count() const override { return n_; }

  std::vector<rumble::Wheel> wheels() const override {
    std::vector<rumble::Wheel> w;
    for (std::size_t i = 0; i < d_.wheels.size(); ++i) {
      w.push_back(rumble::Wheel{nominal_.wheel_x[i], d_.wheels[i].radius});
    }
    return w;
  }

  void mass_matrix(const double* q, double* m) override {
    kin_.update(q, zeros_.data());  // M depends on q only
    rumble::mbs::mass_matrix(d_, kin_, m);
  }

  void forces(double /*t*/, const double* q, const double* qd, double* f) override {
    kin_.update(q, qd);
    generalized_forces(d_, nominal_, kin_, work_, qd, f);
  }

  void wheel_kinematics(const double* q, double* z, double* jacobian) override {
    kin_.update(q, zeros_.data());
    const std::size_t nw = d_.wheels.size();
    for (std::size_t i = 0; i < nw; ++i) {
      kin_.point(d_.wheels[i].centre, work_.a);
      // The contact point lies a fixed radius below the centre: same vertical motion.
      z[i] = work_.a.z - nominal_.wheel_z[i];
      for (std::size_t j = 0; j < n_; ++j) jacobian[j * nw + i] = work_.a.jz[j];
    }
  }

  bool tangent(double /*t*/, const double* q, const double* qd, double* k, double* c) override {
    for (std::size_t j = 0; j < n_; ++j) {
      q_c_[j] = q[j];
      qd_c_[j] = qd[j];
    }
    for (std::size_t j = 0; j < n_; ++j) {
      q_c_[j] += Complex(0.0, kComplexStep);
      complex_forces();
      for (std::size_t i = 0; i < n_; ++i) k[j * n_ + i] = -f_c_[i].imag() / kComplexStep;
      q_c_[j] = q[j];
      qd_c_[j] += Complex(0.0, kComplexStep);
      complex_forces();
      for (std::size_t i = 0; i < n_; ++i) c[j * n_ + i] = -f_c_[i].imag() / kComplexStep;
      qd_c_[j] = qd[j];
    }
    return true;
  }

  std::vector<std::string> output_names() const override {
    std::vector<std::string> names;
    for (const Element& e : d_.elements) names.push_back(e.name + "_force [N]");
    return names;
  }

  /// Each element's compression force F [N] (see Element).
  void outputs(double /*t*/, const double* q, const double* qd, double* values) override {
    kin_.update(q, qd);
    for (std::size_t e = 0; e < d_.elements.size(); ++e) {
      values[e] = element_force<double>(d_.elements[e], nominal_.element_length[e], kin_, work_, qd,
                                        nullptr);
    }
  }

 private:
  void complex_forces() {
    kin_c_.update(q_c_.data(), qd_c_.data());
    generalized_forces(d_, nominal_, kin_c_, work_c_, qd_c_.data(), f_c_.data());
  }

  /// Element lengths and wheel positions at q = 0, and the checks that need them.
  void compute_nominal() {
    kin_.update(zeros_.data(), zeros_.data());
    for (const Element& e : d_.elements) {
      kin_.point(e.a, work_.a);
      kin_.point(e.b, work_.b);
      const double dx = work_.b.x - work_.a.x;
      const double dz = work_.b.z - work_.a.z;
      double s0 = dz;
      if (e.direction == Direction::kX) s0 = dx;
      if (e.direction == Direction::kLine) {
        s0 = std::hypot(dx, dz);
        if (!(s0 > 0.0)) {
          fail(e.where + "/direction",
               "a \"line\" element needs two distinct points at q = 0 (its direction is the line "
               "between them)",
               "\"line\" with both points at [" + std::to_string(work_.a.x) + ", " +
                   std::to_string(work_.a.z) + "]",
               "move one point, or use direction \"z\" or \"x\"");
        }
      }
      nominal_.element_length.push_back(s0);
    }
    for (const WheelDef& w : d_.wheels) {
      kin_.point(w.centre, work_.a);
      nominal_.wheel_x.push_back(work_.a.x);
      nominal_.wheel_z.push_back(work_.a.z);
      bool moves = false;
      for (std::size_t j = 0; j < n_; ++j) moves = moves || work_.a.jz[j] != 0.0;
      if (!moves) {
        fail(w.where + "/body",
             "the wheel centre does not move vertically with any DOF, so the contact force has "
             "nothing to act on",
             vehicles::shown(nlohmann::json(w.centre.body_name)),
             "drive this body (or one of its parents) with a \"tz\" transformation that has a "
             "\"dof\"");
      }
    }
  }

  /// M(0) must be positive definite (Cholesky), else name the first DOF that has no inertia.
  void check_mass_matrix() {
    std::vector<double> m(n_ * n_);
    mass_matrix(zeros_.data(), m.data());
    double scale = 0.0;
    for (std::size_t j = 0; j < n_; ++j) scale = std::max(scale, m[j * n_ + j]);
    for (std::size_t j = 0; j < n_; ++j) {  // in-place lower Cholesky, column by column
      double pivot = m[j * n_ + j];
      for (std::size_t k = 0; k < j; ++k) pivot -= m[k * n_ + j] * m[k * n_ + j];
      if (!(pivot > 1e-12 * scale)) {
        fail(d_.dof_where[j] + "/dof",
             "the mass matrix is singular at q = 0: DOF \"" + d_.dof_names[j] +
                 "\" moves no mass or inertia that the DOFs before it do not already move",
             {},
             "place a body with mass (for a rotation: pitch inertia, or a centre of mass off the "
             "axis) after this transformation, or remove the DOF");
      }
      const double l = std::sqrt(pivot);
      m[j * n_ + j] = l;
      for (std::size_t i = j + 1; i < n_; ++i) {
        double v = m[j * n_ + i];
        for (std::size_t k = 0; k < j; ++k) v -= m[k * n_ + i] * m[k * n_ + j];
        m[j * n_ + i] = v / l;
      }
    }
  }

  Definition d_;  // first: the kinematics below keep a reference to it
  std::size_t n_;
  Nominal nominal_;
  Kinematics<double> kin_;
  Workspace<double> work_;
  std::vector<double> zeros_;  // q' = 0 where only positions matter
  Kinematics<Complex> kin_c_;  // complex-step tangent
  Workspace<Complex> work_c_;
  std::vector<Complex> q_c_, qd_c_, f_c_;
};

}  // namespace
}  // namespace rumble::mbs

RUMBLE_PLUGIN("mbs", "0.1.0", rumble::mbs::MbsVehicle)
