#include "distributed/distributed_soil.hpp"

#include <rumble/abi.h>

#include <algorithm>
#include <memory>
#include <sstream>
#include <utility>

#include "distributed/distributed_operator.hpp"
#include "distributed/part_stiffness.hpp"
#include "distributed/rank_agreement.hpp"
#include "operator/elasticity.hpp"

namespace rumble::fem {

namespace {

/// Rank 0's values on every rank (the size first).
template <class T>
void broadcast(MPI_Comm comm, std::vector<T>& values, MPI_Datatype type) {
  long long n = static_cast<long long>(values.size());
  MPI_Bcast(&n, 1, MPI_LONG_LONG, 0, comm);
  values.resize(static_cast<std::size_t>(n));
  if (n > 0) MPI_Bcast(values.data(), static_cast<int>(n), type, 0, comm);
}

constexpr int kBoundaryDoubles = 16;  // node, normal (3), area, two dashpots, spring (9)

void pack(const BoundaryNode& b, std::vector<double>& out) {
  out.push_back(b.node);
  out.insert(out.end(), b.normal.data(), b.normal.data() + 3);
  out.push_back(b.area);
  out.push_back(b.dashpot_normal);
  out.push_back(b.dashpot_tangential);
  out.insert(out.end(), b.spring.data(), b.spring.data() + 9);
}

BoundaryNode unpack(const double* in, std::int32_t node) {
  BoundaryNode b;
  b.node = node;
  b.normal = Eigen::Map<const Eigen::Vector3d>(in + 1);
  b.area = in[4];
  b.dashpot_normal = in[5];
  b.dashpot_tangential = in[6];
  b.spring = Eigen::Map<const Eigen::Matrix3d>(in + 7);
  return b;
}

}  // namespace

DistributedSoil::DistributedSoil(MPI_Comm comm) : petsc_(PetscSession::get()), comm_(comm) {
  MPI_Comm_rank(comm_, &rank_);
  MPI_Comm_size(comm_, &ranks_);
}

std::vector<BoundaryNode> DistributedSoil::local_boundary(const ExplicitSolver* whole) const {
  std::vector<double> packed;
  if (whole != nullptr)
    for (const BoundaryNode& b : whole->boundary()) pack(b, packed);
  broadcast(comm_, packed, MPI_DOUBLE);
  std::vector<BoundaryNode> mine;
  for (std::size_t k = 0; k < packed.size(); k += kBoundaryDoubles)
    if (const std::int32_t local = part_.local_of(static_cast<std::int32_t>(packed[k])); local >= 0)
      mine.push_back(unpack(packed.data() + k, local));
  return mine;
}

std::vector<char> DistributedSoil::local_fixed(const ExplicitSolver* whole) const {
  std::vector<int> root, leaves(static_cast<std::size_t>(part_.nodes()), 0);
  if (whole != nullptr) root.assign(whole->fixed().begin(), whole->fixed().end());
  part_.from_root->to_leaves(root.data(), leaves.data(), 1);
  return std::vector<char>(leaves.begin(), leaves.end());
}

void DistributedSoil::lay_out(const TetMesh* mesh, const ExplicitSolver* whole,
                              const FemSettings& settings, unsigned threads) {
  statics_.reset();  // (they refer to the old partition)
  step_.reset();
  part_ = partition_mesh(comm_, mesh);
  double eigen[2] = {whole ? whole->largest_eigenvalue() : 0.0,
                     whole ? static_cast<double>(whole->eigen_iterations()) : 0.0};
  MPI_Bcast(eigen, 2, MPI_DOUBLE, 0, comm_);
  std::vector<BoundaryNode> boundary = local_boundary(whole);
  std::vector<char> fixed = local_fixed(whole);
  std::optional<CsrMatrix> K;
  Eigen::VectorXd mass;
  on_every_rank(comm_, [&] {  // (a degenerate tetrahedron throws on its rank alone)
    K.emplace(assemble_stiffness(part_.mesh, settings));
    mass = lumped_mass(part_.mesh, settings);
  });
  complete_shared_entries(part_, *K, comm_);
  complete_mass(part_, mass);
  auto op = std::make_unique<DistributedOperator>(
      std::move(*K), std::move(mass), std::move(boundary), settings.boundary.springs(),
      std::move(fixed), threads,
      settings.single_precision_step ? StepPrecision::kSingle : StepPrecision::kDouble,
      part_.shared, *part_.halo);
  step_.emplace(std::move(op), settings.damping.mass_coefficient(),
                settings.damping.stiffness_coefficient(), eigen[0], static_cast<int>(eigen[1]));
  if (settings.damping.maxwell) step_->set_maxwell_damping(settings.damping.maxwell_mechanisms());
  state_ = step_->rest_state();
  const Eigen::Index n = step_->dofs();
  u_static_ = Eigen::VectorXd::Zero(n);
  f_ = Eigen::VectorXd::Zero(n);
  df_ = Eigen::VectorXd::Zero(n);
  far_ = {};
  far_field_set_ = false;
  probes_.clear();
  probe_count_ = 0;
}

void DistributedSoil::set_footprints(const FootprintWeights* whole) {
  std::vector<double> packed;  // per footprint: its count, then (node, weight) pairs
  if (whole != nullptr)
    for (const std::vector<NodalWeight>& footprint : *whole) {
      packed.push_back(static_cast<double>(footprint.size()));
      for (const NodalWeight& w : footprint) {
        packed.push_back(w.node);
        packed.push_back(w.weight);
      }
    }
  broadcast(comm_, packed, MPI_DOUBLE);
  weights_.clear();
  owned_weights_.clear();
  for (std::size_t k = 0; k < packed.size();) {
    const auto count = static_cast<std::size_t>(packed[k++]);
    weights_.emplace_back();
    owned_weights_.emplace_back();
    for (std::size_t i = 0; i < count; ++i, k += 2) {
      const std::int32_t local = part_.local_of(static_cast<std::int32_t>(packed[k]));
      if (local < 0) continue;
      weights_.back().push_back({local, packed[k + 1]});
      if (part_.owns(local, rank_)) owned_weights_.back().push_back({local, packed[k + 1]});
    }
  }
  set_loaded_nodes();
}

void DistributedSoil::set_loaded_nodes() {
  std::vector<std::int32_t> loaded = loaded_nodes(weights_);
  loaded.insert(loaded.end(), far_.nodes.begin(), far_.nodes.end());
  std::sort(loaded.begin(), loaded.end());
  loaded.erase(std::unique(loaded.begin(), loaded.end()), loaded.end());
  step_->set_loaded_nodes(std::move(loaded));
}

void DistributedSoil::set_far_field(const StaticFarField* whole) {
  if (far_field_set_) return;
  far_field_set_ = true;
  std::vector<int> nodes;
  std::vector<double> loads;
  long long columns = whole ? whole->loads().cols() : 0;
  if (whole != nullptr) {
    nodes = whole->nodes();
    loads.assign(whole->loads().data(), whole->loads().data() + whole->loads().size());
  }
  MPI_Bcast(&columns, 1, MPI_LONG_LONG, 0, comm_);
  broadcast(comm_, nodes, MPI_INT);
  broadcast(comm_, loads, MPI_DOUBLE);
  if (columns == 0) return;
  const Eigen::Map<const Eigen::MatrixXd> all(loads.data(),
                                              3 * static_cast<Eigen::Index>(nodes.size()), columns);
  std::vector<Eigen::Index> rows;
  for (std::size_t k = 0; k < nodes.size(); ++k)
    if (const std::int32_t local = part_.local_of(nodes[k]); local >= 0) {
      far_.nodes.push_back(local);
      rows.push_back(static_cast<Eigen::Index>(k));
    }
  far_.loads.resize(3 * static_cast<Eigen::Index>(rows.size()), columns);
  for (std::size_t r = 0; r < rows.size(); ++r)
    far_.loads.middleRows<3>(3 * static_cast<Eigen::Index>(r)) = all.middleRows<3>(3 * rows[r]);
  set_loaded_nodes();
}

void DistributedSoil::set_far_field_force(const double* F, Eigen::VectorXd& f) const {
  far_.g.resize(far_.loads.rows());
  far_.g.noalias() = far_.loads * Eigen::Map<const Eigen::VectorXd>(F, far_.loads.cols());
  for (std::size_t k = 0; k < far_.nodes.size(); ++k)
    f.segment<3>(3 * static_cast<Eigen::Index>(far_.nodes[k])) =
        far_.g.segment<3>(3 * static_cast<Eigen::Index>(k));
}

bool DistributedSoil::solve_static(const double* F, double* averages) {
  const bool built = !statics_;
  if (built) statics_ = std::make_unique<DistributedStatics>(part_, step_->soil(), comm_);
  Eigen::VectorXd f = Eigen::VectorXd::Zero(step_->dofs());
  for (std::size_t j = 0; j < weights_.size(); ++j)  // (as FemSoil::spread, on this rank's nodes)
    for (const NodalWeight& w : weights_[j]) f[3 * w.node + 2] += w.weight * F[j];
  if (has_far_field()) {
    far_.g.resize(far_.loads.rows());
    far_.g.noalias() = far_.loads * Eigen::Map<const Eigen::VectorXd>(F, far_.loads.cols());
    for (std::size_t k = 0; k < far_.nodes.size(); ++k)
      f.segment<3>(3 * static_cast<Eigen::Index>(far_.nodes[k])) +=
          far_.g.segment<3>(3 * static_cast<Eigen::Index>(k));
  }
  u_static_ = statics_->solve(f);
  std::vector<double> unused(weights_.size());
  footprint_averages(u_static_, u_static_, averages, unused.data());
  return built;
}

void DistributedSoil::set_static(const Eigen::VectorXd* whole) {
  part_.from_root->to_leaves(whole ? whole->data() : nullptr, u_static_.data(), 3);
}

void DistributedSoil::set_probes(const std::vector<ProbePoint>* whole) {
  std::vector<double> packed;  // per receiver: 4 nodes, 4 weights
  if (whole != nullptr)
    for (const ProbePoint& p : *whole) {
      packed.insert(packed.end(), p.nodes.begin(), p.nodes.end());
      packed.insert(packed.end(), p.weights.begin(), p.weights.end());
    }
  broadcast(comm_, packed, MPI_DOUBLE);
  probe_count_ = packed.size() / 8;
  std::vector<int> sampler(probe_count_, ranks_), lowest(probe_count_, 0);
  std::vector<ProbePoint> local(probe_count_);
  for (std::size_t p = 0; p < probe_count_; ++p) {
    bool holds = true;
    for (int a = 0; a < 4; ++a) {
      local[p].nodes[a] = part_.local_of(static_cast<std::int32_t>(packed[8 * p + a]));
      local[p].weights[a] = packed[8 * p + 4 + a];
      holds = holds && local[p].nodes[a] >= 0;
    }
    if (holds) sampler[p] = rank_;
  }
  MPI_Allreduce(sampler.data(), lowest.data(), static_cast<int>(probe_count_), MPI_INT, MPI_MIN,
                comm_);
  probes_.clear();
  for (std::size_t p = 0; p < probe_count_; ++p)
    if (lowest[p] == rank_) probes_.push_back({p, local[p]});
}

void DistributedSoil::footprint_averages(const Eigen::VectorXd& x, const Eigen::VectorXd& y,
                                         double* w_average, double* v_average) const {
  const std::size_t n = owned_weights_.size();
  std::vector<double> mine(2 * n), all(root() ? 2 * n * static_cast<std::size_t>(ranks_) : 0);
  for (std::size_t j = 0; j < n; ++j) {
    mine[j] = footprint_average(owned_weights_[j], x.data());
    mine[n + j] = footprint_average(owned_weights_[j], y.data());
  }
  MPI_Gather(mine.data(), static_cast<int>(2 * n), MPI_DOUBLE, all.data(), static_cast<int>(2 * n),
             MPI_DOUBLE, 0, comm_);
  if (!root()) return;
  for (std::size_t j = 0; j < n; ++j) {
    w_average[j] = v_average[j] = 0.0;
    for (int r = 0; r < ranks_; ++r) {  // (in rank order: the same sum on every run)
      w_average[j] += all[2 * n * r + j];
      v_average[j] += all[2 * n * r + n + j];
    }
  }
}

void DistributedSoil::sample_probes(double* rows) const {
  std::vector<double> mine(probe_count_ * RUMBLE_PROBE_VALUES, 0.0);
  for (const LocalProbe& p : probes_) {
    double* out = mine.data() + p.index * RUMBLE_PROBE_VALUES;
    for (int a = 0; a < 4; ++a) {  // (as one process samples it: fem_outputs.cpp)
      const std::int64_t node = p.point.nodes[a];
      const double w = p.point.weights[a];
      for (int c = 0; c < 3; ++c) {
        out[c] += w * state_.v[3 * node + c];
        out[3 + c] += w * (u_static_[3 * node + c] + state_.w[3 * node + c]);
      }
    }
  }
  // One rank holds each receiver's row, the others zeros: the sum is that row exactly.
  MPI_Reduce(mine.data(), rows, static_cast<int>(mine.size()), MPI_DOUBLE, MPI_SUM, 0, comm_);
}

void DistributedSoil::gather(const Eigen::VectorXd& local, Eigen::VectorXd* whole) const {
  part_.from_root->copy_to_roots(local.data(), whole ? whole->data() : nullptr, 3);
}

std::string DistributedSoil::summary() const {
  // Per rank: tetrahedra, nodes, owned nodes, ghosts, bytes of the step.
  const long long ghosts =
      std::count_if(part_.owner.begin(), part_.owner.end(), [&](int o) { return o != rank_; });
  const long long mine[5] = {static_cast<long long>(part_.mesh.tets.size()), part_.nodes(),
                             part_.nodes() - ghosts, ghosts,
                             static_cast<long long>(step_->bytes())};
  std::vector<long long> all(root() ? 5 * static_cast<std::size_t>(ranks_) : 0);
  MPI_Gather(mine, 5, MPI_LONG_LONG, all.data(), 5, MPI_LONG_LONG, 0, comm_);
  if (!root()) return "";
  const auto range = [&](int k) {  // (fewest-most over the ranks, and the sum)
    long long lo = all[k], hi = all[k], sum = 0;
    for (int r = 0; r < ranks_; ++r) {
      lo = std::min(lo, all[5 * r + k]);
      hi = std::max(hi, all[5 * r + k]);
      sum += all[5 * r + k];
    }
    return std::make_pair(std::to_string(lo) + "-" + std::to_string(hi), sum);
  };
  long long most_bytes = 0;
  for (int r = 0; r < ranks_; ++r) most_bytes = std::max(most_bytes, all[5 * r + 4]);
  std::ostringstream m;
  m.precision(3);
  m << "fem: the mesh split over " << ranks_ << " ranks (" << partitioner_name()
    << "): tetrahedra per rank " << range(0).first << ", nodes " << range(1).first << " (owned "
    << range(2).first << ", ghosts " << range(3).first << "); halo "
    << static_cast<double>(range(3).second) * 48.0 / 1024.0
    << " KiB exchanged per step (each ghost's product summed to its owner and copied back); "
    << static_cast<double>(most_bytes) / 1048576.0
    << " MiB of operator and step on the largest rank";
  return m.str();
}

}  // namespace rumble::fem
