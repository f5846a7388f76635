// ABI 1.1 test fixtures (not shipped):
//   picky_soil      c u' + k u = F per footprint (backward Euler, sub-steps of at most
//                   `sub_step`), that refuses (DISCARD, state unchanged) any step longer than
//                   `max_step`; records probes (the nearest footprint's u and v as uz and vz at
//                   every sub-step); keeps its own checkpoints; stalls from `stall_at` [s]
//                   (or in its statics, `stall_in_statics`) until the host asks it to stop (or,
//                   `deaf`, for 60 s without asking, as a dense factorisation would); writes
//                   field snapshots and its linear matrices; finalize() writes finalized.json
//                   (advances, refusals, threads, checkpoint and state-copy counts) to the results
//                   directory.
//   forgetful_soil  the same spring-dashpot with no save/restore, once per process, no probes.
//   needy_coupler   needs save/restore of every soil, a participant "reduced_soil", and macro
//                   steps of at most 1 ms (declared only: validate refuses before it runs).
#include <array>
#include <chrono>
#include <cmath>
#include <csignal>
#include <cstdlib>
#include <fstream>
#include <limits>
#include <rumble/params.hpp>
#include <rumble/plugin.hpp>
#include <string>
#include <thread>
#include <tuple>
#include <vector>

namespace {

/// c u' + k u = F per footprint, backward Euler in sub-steps.
class SpringDashpot {
 public:
  void configure(const rumble::Params& p) {
    k_ = p.get<double>("k");
    c_ = p.get<double>("c");
    sub_step_ = p.get<double>("sub_step");
  }
  void resize(std::size_t n) {
    u_.assign(n, 0.0);
    v_.assign(n, 0.0);
  }
  void statics(const double* force, double* u) {
    for (std::size_t i = 0; i < u_.size(); ++i) u[i] = u_[i] = force[i] / k_;
  }
  /// Integrates over [t, t + H]; after each sub-step calls observe(t_now).
  template <class Observe>
  void step(double t, double H, const rumble::Waveform& force, Observe&& observe) {
    const int n_sub = std::max(1, static_cast<int>(std::ceil(H / sub_step_ - 1e-9)));
    const double h = H / n_sub;
    for (int s = 1; s <= n_sub; ++s) {
      for (std::size_t i = 0; i < u_.size(); ++i) {
        const double f = force.at(i, static_cast<double>(s) / n_sub);
        const double u = (c_ * u_[i] + h * f) / (c_ + h * k_);
        v_[i] = (u - u_[i]) / h;
        u_[i] = u;
      }
      observe(t + s * h);
    }
  }
  std::vector<double> u_, v_;  // m, m/s
  double k() const { return k_; }
  double c() const { return c_; }

 private:
  double k_ = 0.0, c_ = 0.0, sub_step_ = 0.0;  // N/m, N s/m, s
};

constexpr const char* kSpringSchema = R"(
    "k": {"type": "number", "exclusiveMinimum": 0, "default": 1.0e8},
    "c": {"type": "number", "exclusiveMinimum": 0, "default": 2.0e5},
    "sub_step": {"type": "number", "exclusiveMinimum": 0, "default": 1.25e-4})";

class PickySoil : public rumble::Soil {
 public:
  static constexpr const char* kTypeName = "picky_soil";
  static constexpr const char* kSummary = "test fixture: refuses long steps, records probes";
  static const char* params_schema() {
    static const std::string s = std::string(R"({"type": "object", "additionalProperties": false,
  "properties": {)") + kSpringSchema +
                                 R"(,
    "max_step": {"type": "number", "exclusiveMinimum": 0, "default": 1.0},
    "csc_defect": {"enum": ["none", "unsorted", "nan", "stiffer"], "default": "none"},
    "stall_at": {"type": "number", "default": 1.0e30},
    "stall_in_statics": {"type": "boolean", "default": false},
    "deaf": {"type": "boolean", "default": false},
    "resolution": {"type": "number", "default": 0},
    "exit_at": {"type": "number", "default": 1.0e30},
    "crash_at": {"type": "number", "default": 1.0e30}}})";
    return s.c_str();
  }
  PickySoil(const std::string& params, const rumble::Host& host) : host_(host) {
    const rumble::Params p(params);
    spring_.configure(p);
    max_step_ = p.get<double>("max_step");
    csc_defect_ = p.get<std::string>("csc_defect");
    stall_at_ = p.get<double>("stall_at");
    stall_in_statics_ = p.get_or<bool>("stall_in_statics", false);
    deaf_ = p.get_or<bool>("deaf", false);
    exit_at_ = p.get_or<double>("exit_at", 1.0e30);  // tests build it without the schema too
    crash_at_ = p.get_or<double>("crash_at", 1.0e30);
    resolution_ = p.get_or<double>("resolution", 0.0);
  }
  void accept_layout(const std::vector<rumble::Footprint>& f) override {
    footprints_ = f;
    spring_.resize(f.size());
  }
  void initialize(double, const double* force, double* u) override {
    if (stall_in_statics_) stall();
    spring_.statics(force, u);
  }
  void advance(double t, double H, const rumble::Waveform& force) override {
    if (H > max_step_ * (1.0 + 1e-12)) {
      ++refusals_;
      throw rumble::Discard("picky_soil takes steps of at most " + std::to_string(max_step_) +
                            " s, asked " + std::to_string(H));
    }
    if (t >= stall_at_) stall();
    if (t >= exit_at_) std::exit(0);          // a careless plugin ending the process (issue #8)
    if (t >= crash_at_) std::raise(SIGSEGV);  // a plugin's bad pointer (issue #30 item 4)
    ++advances_;
    spring_.step(t, H, force, [&](double now) { record(now); });
  }
  void motion(double* u, double* v) const override {
    for (std::size_t i = 0; i < spring_.u_.size(); ++i) {
      u[i] = spring_.u_[i];
      v[i] = spring_.v_[i];
    }
  }
  std::size_t state_size() const override { return 2 * spring_.u_.size(); }
  void save_state(double* b) const override {
    ++state_copies_;
    const std::size_t n = spring_.u_.size();
    std::copy(spring_.u_.begin(), spring_.u_.end(), b);
    std::copy(spring_.v_.begin(), spring_.v_.end(), b + n);
  }
  void restore_state(const double* b) override {
    const std::size_t n = spring_.u_.size();
    std::copy(b, b + n, spring_.u_.begin());
    std::copy(b + n, b + 2 * n, spring_.v_.begin());
    ++state_copies_;
  }
  // Own checkpoints: the state stays here; the host never copies it (state_copies_ stays 0).
  void checkpoint_save(std::uint32_t slot) override {
    slots_.at(slot) = {spring_.u_, spring_.v_};
    saved_.at(slot) = true;
    ++checkpoints_;
  }
  void checkpoint_restore(std::uint32_t slot) override {
    if (!saved_.at(slot))
      throw std::runtime_error("picky_soil: checkpoint slot " + std::to_string(slot) + " is empty");
    std::tie(spring_.u_, spring_.v_) = slots_[slot];
  }
  void checkpoint_free(std::uint32_t slot) override {
    slots_.at(slot) = {};
    saved_.at(slot) = false;
  }
  void set_probes(const std::vector<rumble::Probe>& probes, double) override {
    nearest_.clear();
    for (const rumble::Probe& p : probes) {
      std::size_t best = 0;
      for (std::size_t i = 1; i < footprints_.size(); ++i)
        if (std::abs(footprints_[i].x - p.x) < std::abs(footprints_[best].x - p.x)) best = i;
      nearest_.push_back(best);
    }
    row_.assign(probes.size() * RUMBLE_PROBE_VALUES, 0.0);
  }
  /// ABI 1.3: `resolution` [Hz] at every probe when given (negative: a defect to be caught).
  std::vector<double> probe_resolution(std::string& rule) const override {
    if (resolution_ == 0.0) return {};
    rule = "picky_soil's params.resolution";
    return std::vector<double>(nearest_.size(), resolution_);
  }
  /// M = 0, C = c I, K = k I, B = I; or, on request, a CSC with the defect named ("stiffer": a
  /// valid K = 2 k I that does not describe the soil).
  void linear_matrix(rumble_matrix which, rumble::CscMatrix& out) override {
    const std::size_t n = spring_.u_.size();
    const double k = csc_defect_ == "stiffer" ? 2.0 * spring_.k() : spring_.k();
    const double value = which == RUMBLE_MATRIX_DAMPING     ? spring_.c()
                         : which == RUMBLE_MATRIX_STIFFNESS ? k
                         : which == RUMBLE_MATRIX_INPUT     ? 1.0
                                                            : 0.0;
    out.rows = out.cols = n;
    out.col_ptr.assign(1, 0);
    for (std::size_t j = 0; j < n; ++j) {
      if (value != 0.0) {
        out.row_index.push_back(static_cast<std::int64_t>(j));
        out.values.push_back(csc_defect_ == "nan" ? std::nan("") : value);
        if (csc_defect_ == "unsorted" && j > 0) {  // a second entry above the diagonal
          out.row_index.push_back(0);
          out.values.push_back(value);
        }
      }
      out.col_ptr.push_back(static_cast<std::int64_t>(out.values.size()));
    }
  }
  /// A VTU of the footprint centres with their displacement u (vertical) as point data.
  void write_fields(double t, const std::string& path) override {
    std::ofstream out(path);
    const std::size_t n = footprints_.size();
    out << "<?xml version=\"1.0\"?>\n<VTKFile type=\"UnstructuredGrid\" version=\"0.1\">\n"
        << "<!-- picky_soil at t = " << t << " s -->\n<UnstructuredGrid><Piece NumberOfPoints=\""
        << n << "\" NumberOfCells=\"0\">\n<Points><DataArray type=\"Float64\" "
        << "NumberOfComponents=\"3\" format=\"ascii\">";
    for (const rumble::Footprint& f : footprints_) out << ' ' << f.x << ' ' << f.y << " 0";
    out << "</DataArray></Points>\n<PointData><DataArray type=\"Float64\" Name=\"u\" "
        << "format=\"ascii\">";
    for (double u : spring_.u_) out << ' ' << u;
    out << "</DataArray></PointData>\n<Cells><DataArray type=\"Int64\" Name=\"connectivity\"/>"
        << "<DataArray type=\"Int64\" Name=\"offsets\"/><DataArray type=\"UInt8\" "
        << "Name=\"types\"/></Cells>\n</Piece></UnstructuredGrid>\n</VTKFile>\n";
    if (!out) throw std::runtime_error("picky_soil: cannot write " + path);
  }
  void finalize() override {
    std::ofstream out(host_.results_dir() + "/finalized.json");
    out << "{\"advances\": " << advances_ << ", \"refusals\": " << refusals_
        << ", \"threads\": " << host_.threads() << ", \"checkpoints\": " << checkpoints_
        << ", \"state_copies\": " << state_copies_ << "}\n";
  }

 private:
  void record(double t) {
    if (nearest_.empty()) return;
    for (std::size_t p = 0; p < nearest_.size(); ++p) {
      row_[p * RUMBLE_PROBE_VALUES + 2] = spring_.v_[nearest_[p]];
      row_[p * RUMBLE_PROBE_VALUES + 5] = spring_.u_[nearest_[p]];
    }
    samples().push(t, row_.data());
  }
  /// A long advance, as a big FEM soil's: works in 10 ms slices and honours a stop request
  /// (unless deaf_).
  void stall() {
    const auto start = std::chrono::steady_clock::now();
    while (std::chrono::steady_clock::now() - start < std::chrono::seconds(60)) {
      if (!deaf_) host_.check_stop(-1.0);
      std::this_thread::sleep_for(std::chrono::milliseconds(10));
    }
    throw std::runtime_error("picky_soil stalled 60 s and no stop request came");
  }

  rumble::Host host_;
  SpringDashpot spring_;
  std::vector<rumble::Footprint> footprints_;
  std::vector<std::size_t> nearest_;  // footprint of each probe
  std::vector<double> row_;
  double max_step_ = 0.0, stall_at_ = 0.0, exit_at_ = 0.0, crash_at_ = 0.0;  // s
  double resolution_ = 0.0;                                                  // Hz, 0: not said
  bool stall_in_statics_ = false, deaf_ = false;
  std::string csc_defect_;
  long advances_ = 0, refusals_ = 0, checkpoints_ = 0;
  mutable long state_copies_ = 0;  // save_state/restore_state: the host-copy path
  std::array<std::pair<std::vector<double>, std::vector<double>>, RUMBLE_CHECKPOINT_SLOTS> slots_;
  std::array<bool, RUMBLE_CHECKPOINT_SLOTS> saved_{};
};

/// picky_soil declaring that it never refuses a step (ABI 1.7), which its max_step breaks: the
/// host must stop the run rather than let a coupler that kept no checkpoint go on.
class BoastfulSoil final : public PickySoil {
 public:
  using PickySoil::PickySoil;
  static constexpr const char* kTypeName = "boastful_soil";
  static constexpr const char* kSummary = "test fixture: picky_soil that says it never refuses";
  static constexpr std::uint64_t kCapabilities = rumble::kCapNeverRefuses;
};

class ForgetfulSoil final : public rumble::Soil {
 public:
  static constexpr const char* kTypeName = "forgetful_soil";
  static constexpr const char* kSummary = "test fixture: no save/restore, once per process";
  static constexpr std::uint64_t kCapabilities = rumble::kCapOncePerProcess;
  static const char* params_schema() {
    static const std::string s = std::string(R"({"type": "object", "additionalProperties": false,
  "properties": {)") + kSpringSchema +
                                 "}}";
    return s.c_str();
  }
  ForgetfulSoil(const std::string& params, const rumble::Host&) {
    spring_.configure(rumble::Params(params));
  }
  void accept_layout(const std::vector<rumble::Footprint>& f) override { spring_.resize(f.size()); }
  void initialize(double, const double* force, double* u) override { spring_.statics(force, u); }
  void advance(double t, double H, const rumble::Waveform& force) override {
    spring_.step(t, H, force, [](double) {});
  }
  void motion(double* u, double* v) const override {
    for (std::size_t i = 0; i < spring_.u_.size(); ++i) {
      u[i] = spring_.u_[i];
      v[i] = spring_.v_[i];
    }
  }

 private:
  SpringDashpot spring_;
};

class NeedyCoupler final : public rumble::Coupler {
 public:
  static constexpr const char* kTypeName = "needy_coupler";
  static constexpr const char* kSummary = "test fixture: declares needs, never runs";
  static constexpr std::uint64_t kSoilNeeds = rumble::kCapSaveRestore;
  static constexpr double kMaxMacroStep = 1e-3;  // s
  static const char* participants_json() {
    return R"({"reduced_soil": {"kind": "soil", "required": true,
               "description": "the soil of the first pass"}})";
  }
  static const char* params_schema() { return R"({"type": "object"})"; }
  NeedyCoupler(const std::string&, const rumble::Host&) {}
  void run(const rumble::CosimHost&, double, double, double) override {
    throw std::logic_error("needy_coupler is a validate-only fixture");
  }
};

}  // namespace

RUMBLE_PLUGIN("boundary_fixtures", "1.1.0", PickySoil, BoastfulSoil, ForgetfulSoil, NeedyCoupler)
