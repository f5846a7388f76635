#include "distributed/distributed_soil.hpp"

#include <rumble/abi.h>

#include <algorithm>
#include <memory>
#include <optional>
#include <sstream>
#include <utility>

#include "distributed/aggregation_rank_statics.hpp"
#include "distributed/distributed_operator.hpp"
#include "distributed/distributed_statics.hpp"
#include "distributed/geometric_rank_statics.hpp"
#include "distributed/part_operator.hpp"
#include "distributed/part_pml.hpp"
#include "distributed/part_stiffness.hpp"
#include "distributed/rank_agreement.hpp"
#include "distributed/rank_effective_system.hpp"
#include "distributed/refined_partition.hpp"
#include "memory_model.hpp"
#include "mesh/mesh_memory.hpp"
#include "operator/elasticity.hpp"

namespace rumble::fem {

DistributedSoil::DistributedSoil(MPI_Comm comm) : petsc_(PetscSession::get()), comm_(comm) {
  MPI_Comm_rank(comm_, &rank_);
  MPI_Comm_size(comm_, &ranks_);
}

void DistributedSoil::lay_out(const TetMesh* mesh, const FemSettings& settings,
                              const std::vector<Footprint>& footprints, unsigned threads,
                              int refine, const PmlProfile* pml) {
  statics_.reset();   // (they refer to the old partition)
  implicit_.reset();  // (it refers to the old step)
  step_.reset();
  part_ = {};
  coarse_.reset();
  refine_ = refine;
  aggregation_statics_ = settings.aggregation_statics;
  if (refine > 0) {
    MeshPartition coarse = partition_mesh(comm_, mesh, true);
    coarse_nodes_ = coarse.global_nodes;
    part_ = refine_partition(comm_, coarse, refine);
    if (settings.geometric_statics) {  // (1/8 of the part per level)
      coarse.names = {};
      coarse_ = std::make_unique<MeshPartition>(std::move(coarse));
    }
  } else {
    part_ = partition_mesh(comm_, mesh);
    coarse_nodes_ = part_.global_nodes;
  }
  split_peak_ = resident_memory().peak;
  build_step(settings, footprints, threads, pml);
  state_ = step_->rest_state();
  const Eigen::Index n = step_->dofs();
  u_static_ = Eigen::VectorXd::Zero(n);
  f_ = Eigen::VectorXd::Zero(n);
  df_ = Eigen::VectorXd::Zero(n);
  far_ = {};
  far_field_set_ = false;
  probes_.clear();
  probe_count_ = 0;
  weights_ = part_footprint_weights(comm_, part_, footprints);
  owned_weights_.clear();
  for (const std::vector<NodalWeight>& footprint : weights_) {
    owned_weights_.emplace_back();
    for (const NodalWeight& w : footprint)
      if (part_.owns(w.node, rank_)) owned_weights_.back().push_back(w);
  }
  set_loaded_nodes();
  make_statics_ = [this, settings, footprints, refine]() -> std::unique_ptr<RankStatics> {
    if (!coarse_ && settings.aggregation_statics)
      return std::make_unique<AggregationRankStatics>(
          part_, step_->soil(), ElementStiffness(part_.mesh, settings), comm_);
    if (!coarse_) return std::make_unique<DistributedStatics>(part_, step_->soil(), comm_);
    const std::unique_ptr<DistributedOperator> coarse_op =
        part_operator(*coarse_, settings, footprints, 1, StepPrecision::kDouble, comm_);
    return std::make_unique<GeometricRankStatics>(part_, step_->soil(), *coarse_, *coarse_op,
                                                  refine, comm_);
  };
  peak_estimate_ = estimate_peak();
}

void DistributedSoil::build_step(const FemSettings& settings,
                                 const std::vector<Footprint>& footprints, unsigned threads,
                                 const PmlProfile* pml) {
  std::unique_ptr<DistributedOperator> op = part_operator(
      part_, settings, footprints, threads,
      settings.single_precision_step ? StepPrecision::kSingle : StepPrecision::kDouble, comm_);
  // K's rows are for the statics (their matrix, the geometric multigrid's product): freed once
  // they are done (free_statics), built again on every rank if a later static solve asks.
  op->set_stiffness_source([this, settings] {
    // (a rank that cannot build its rows says so on every rank, before the exchange that
    // completes them)
    std::optional<CsrMatrix> again;
    on_every_rank(comm_, [&] { again.emplace(assemble_stiffness(part_.mesh, settings)); });
    complete_shared_entries(part_, *again, comm_);
    return std::move(*again);
  });
  DistributedOperator& soil = *op;  // (owned by the step from here)
  // Lanczos on the ranks' operator (its sums over the ranks in rank order): every rank gets
  // the same stable step, one process's to rounding (fem_partition_check.cpp).
  step_.emplace(std::move(op), settings.damping.mass_coefficient(),
                settings.damping.stiffness_coefficient());
  // (after the stable step's products: the hook is for the statics')
  if (!failing_products_.empty()) soil.fail_products_on_purpose(failing_products_);
  if (settings.damping.maxwell) step_->set_maxwell_damping(settings.damping.maxwell_mechanisms());
  if (pml) step_->set_pml(part_pml(part_, settings, *pml, comm_));
  if (settings.implicit)
    implicit_ = std::make_unique<ImplicitSolver>(
        *step_, settings.damping.mass_coefficient(), settings.damping.stiffness_coefficient(),
        std::make_unique<RankEffectiveSystem>(part_, step_->soil(), comm_));
}

double DistributedSoil::estimate_peak() const {
  const ResidentMemory resident = resident_memory();
  // GAMG on the ranks copies this rank's rows into PETSc's matrix and builds its hierarchy, the
  // geometric multigrid builds its coarse level (memory_model.hpp): the statics' peak on every
  // rank above the factor limit.
  const auto nonzeros = static_cast<double>(step_->stiffness().nonzeros());
  const double per_nonzero = coarse_                ? memory::kGeometricRankBytesPerNonzero
                             : aggregation_statics_ ? memory::kAggregationRankBytesPerNonzero
                                                    : memory::kGamgBytesPerNonzero;
  double mine = std::max(resident.peak, resident.now + per_nonzero * nonzeros);
  if (implicit_)  // (the steps' factor, after the statics have freed theirs)
    mine = std::max(
        mine, resident.now + memory::rank_factor_bytes(static_cast<double>(whole_dofs()), ranks_));
  if (resident.now == 0.0) mine = 0.0;  // (no /proc: nothing to start from)
  double most = 0.0;
  MPI_Allreduce(&mine, &most, 1, MPI_DOUBLE, MPI_MAX, comm_);
  return most;
}

void DistributedSoil::set_loaded_nodes() {
  std::vector<std::int32_t> loaded = loaded_nodes(weights_);
  if (far_) loaded.insert(loaded.end(), far_->nodes().begin(), far_->nodes().end());
  std::sort(loaded.begin(), loaded.end());
  loaded.erase(std::unique(loaded.begin(), loaded.end()), loaded.end());
  step_->set_loaded_nodes(std::move(loaded));
}

double DistributedSoil::set_far_field(const FemSettings& settings,
                                      const std::vector<Footprint>& footprints) {
  if (far_field_set_ || !static_far_field_applies(settings)) return far_mean_distance_;
  far_field_set_ = true;
  const std::vector<BoundaryNode>& boundary = step_->boundary();
  far_.emplace(part_.mesh, settings, footprints, boundary);  // (its rows: node by node)
  far_mean_distance_ = boundary_mean_distance(comm_, part_, boundary, footprints);
  set_loaded_nodes();
  return far_mean_distance_;
}

bool DistributedSoil::solve_static(const double* F, double* averages) {
  const bool built = !statics_;
  if (built) {
    statics_ = make_statics_();
    statics_->set_stop_check(stop_check_);
  }
  Eigen::VectorXd f = Eigen::VectorXd::Zero(step_->dofs());
  for (std::size_t j = 0; j < weights_.size(); ++j)  // (as FemSoil::spread, on this rank's nodes)
    for (const NodalWeight& w : weights_[j]) f[3 * w.node + 2] += w.weight * F[j];
  if (far_) far_->add(F, f, step_->threads());
  u_static_ = statics_->solve(f);
  std::vector<double> unused(weights_.size());
  footprint_averages(u_static_, u_static_, averages, unused.data());
  return built;
}

void DistributedSoil::set_static(const Eigen::VectorXd* whole) {
  part_.from_root->to_leaves(whole ? whole->data() : nullptr, u_static_.data(), 3);
}

void DistributedSoil::set_probes(const std::vector<Probe>& probes) {
  probes_ = part_probes(comm_, part_, probes);
  probe_count_ = probes.size();
  probe_rows_.assign(probe_count_ * RUMBLE_PROBE_VALUES, 0.0);
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
  // (set_probes made the rows: nothing here can fail before the reduction the others wait in)
  std::vector<double>& mine = probe_rows_;
  std::fill(mine.begin(), mine.end(), 0.0);
  for (const PartProbe& p : probes_) {
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
    << " MiB of operator and step on the largest rank; ";
  if (refine_ > 0)
    m << "rank 0 split the coarse mesh of " << coarse_nodes_
      << " nodes only, and each rank refined its part " << refine_
      << " times after the split (mesh.refine): " << part_.global_nodes << " nodes in all; ";
  if (split_peak_ > 0.0)  // (0: no /proc)
    m << "rank 0's peak resident memory through the meshing and the split " << split_peak_ / 1e9
      << " GB (VmHWM); ";
  m << "each rank built its share from its part; stable step " << step_->stable_step() << " s ("
    << step_->eigen_iterations() << " Lanczos iterations over the ranks)";
  return m.str();
}

}  // namespace rumble::fem
