// split_dashpot: a distributed soil for the mirror's tests
// (docs/decisions/0012-distributed-soil.md). The model is template_soil's (sdk/template): a spring
// k and a dashpot c under each footprint,
//   c u' + k u = F,
// integrated exactly over a step for a force held constant over it (waveform order 0; the first
// coefficient of a higher order is the force at the step's start). Footprint i belongs to rank
// i mod size: each rank integrates its own, and motion() sums over the ranks (the others hold 0,
// so the sum is exact), as a distributed soil reduces what rank 0 must return. The results are
// then bit-identical on any rank count. `fail_rank` makes one rank's advance fail from `fail_at`
// on, before any collective operation, as a plugin error on one rank would.
#define OMPI_SKIP_MPICXX 1
#include <mpi.h>

#include <cmath>
#include <rumble/params.hpp>
#include <rumble/plugin.hpp>
#include <stdexcept>
#include <string>
#include <vector>

namespace {

class SplitDashpot final : public rumble::Soil {
 public:
  static constexpr const char* kTypeName = "split_dashpot";
  static constexpr const char* kSummary =
      "test: a dashpot soil whose footprints are split over MPI ranks";
  static constexpr std::uint64_t kCapabilities = rumble::kCapDistributed;
  static const char* params_schema() {
    return R"schema({
  "type": "object",
  "additionalProperties": false,
  "properties": {
    "stiffness": {"type": "number", "minimum": 1.0e4, "maximum": 1.0e13, "default": 1.0e8,
                  "description": "spring stiffness under each footprint [N/m]"},
    "damping": {"type": "number", "exclusiveMinimum": 0, "maximum": 1.0e10, "default": 1.0e5,
                "description": "dashpot coefficient under each footprint [N s/m]"},
    "fail_rank": {"type": "integer", "minimum": -1, "maximum": 1000, "default": -1,
                  "description": "the rank whose advance fails, -1 for none"},
    "fail_at": {"type": "number", "minimum": 0, "maximum": 1000, "default": 0,
                "description": "from this time on [s]"}
  }
})schema";
  }

  SplitDashpot(const std::string& params_json, const rumble::Host& host) : host_(host) {
    const rumble::Params p(params_json, params_schema());
    stiffness_ = p.get<double>("stiffness");
    damping_ = p.get<double>("damping");
    fail_rank_ = p.get<int>("fail_rank");
    fail_at_ = p.get<double>("fail_at");
    const std::optional<rumble::HostCommunicator> c = host.communicator();
    if (!c) throw std::runtime_error("split_dashpot needs a host with MPI (ABI 1.4)");
    comm_ = MPI_Comm_f2c(static_cast<MPI_Fint>(c->fortran_handle));
    rank_ = c->rank;
    size_ = c->size;
  }

  void accept_layout(const std::vector<rumble::Footprint>& footprints) override {
    u_.assign(footprints.size(), 0.0);
    v_.assign(footprints.size(), 0.0);
    std::size_t mine = 0;
    for (std::size_t i = 0; i < u_.size(); ++i) mine += owns(i) ? 1 : 0;
    host_.info("split_dashpot: rank " + std::to_string(rank_) + " of " + std::to_string(size_) +
               " ranks owns " + std::to_string(mine) + " footprints");
  }

  void initialize(double /*t0*/, const double* static_force, double* static_u) override {
    for (std::size_t i = 0; i < u_.size(); ++i) {
      u_[i] = owns(i) ? static_force[i] / stiffness_ : 0.0;
      v_[i] = 0.0;
    }
    std::vector<double> v(u_.size());
    reduce(static_u, v.data());
  }

  void advance(double t, double H, const rumble::Waveform& force) override {
    if (rank_ == fail_rank_ && t >= fail_at_)
      throw std::runtime_error("split_dashpot failed on purpose at t = " + std::to_string(t));
    const double decay = std::exp(-stiffness_ * H / damping_);
    for (std::size_t i = 0; i < u_.size(); ++i) {
      if (!owns(i)) continue;
      const double f = force.at(i, 0.0);
      const double u_end = f / stiffness_ + (u_[i] - f / stiffness_) * decay;
      v_[i] = (f - stiffness_ * u_end) / damping_;
      u_[i] = u_end;
    }
  }

  void motion(double* u, double* v) const override { reduce(u, v); }

  std::size_t state_size() const override { return 2 * u_.size(); }
  void save_state(double* buffer) const override {
    for (std::size_t i = 0; i < u_.size(); ++i) {
      buffer[i] = u_[i];
      buffer[u_.size() + i] = v_[i];
    }
  }
  void restore_state(const double* buffer) override {
    for (std::size_t i = 0; i < u_.size(); ++i) {
      u_[i] = buffer[i];
      v_[i] = buffer[u_.size() + i];
    }
  }

 private:
  bool owns(std::size_t i) const {
    return static_cast<int>(i % static_cast<std::size_t>(size_)) == rank_;
  }
  /// Every rank's own footprints into u and v (a sum: the others hold 0 there).
  void reduce(double* u, double* v) const {
    const int n = static_cast<int>(u_.size());
    MPI_Allreduce(u_.data(), u, n, MPI_DOUBLE, MPI_SUM, comm_);
    MPI_Allreduce(v_.data(), v, n, MPI_DOUBLE, MPI_SUM, comm_);
  }

  rumble::Host host_;
  MPI_Comm comm_ = MPI_COMM_NULL;
  int rank_ = 0, size_ = 1, fail_rank_ = -1;
  double stiffness_ = 0.0, damping_ = 0.0, fail_at_ = 0.0;
  std::vector<double> u_, v_;
};

}  // namespace

RUMBLE_PLUGIN("split_dashpot", "0.1.0", SplitDashpot)
