// The soil's operator behind one small interface (docs/decisions/0006-fem-soil.md): the elastic
// stiffness K, the lumped mass M, the truncation surface's spring and dashpot blocks S and D
// (boundary_blocks.hpp) and the fixed nodes, as the time integrators (time/), the statics
// (statics/), the receptance (frequency/) and the plugin use them. A back end keeps K its own way
// and implements the virtual calls; csr_operator.hpp (K's CSR rows and upper symmetric blocks,
// OpenMP threads) is the first. README.md in this folder has the rule for back ends.
//
// The node data (mass, boundary blocks, fixed nodes, threads, the stop check) are plain members:
// the integrators read them node by node inside their loops, never through a virtual call. The
// virtual calls are whole products and set-ups: one call per product, per thread per step for the
// step's fused product (stepped_product), never one per node or DOF.
#pragma once

#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <utility>
#include <vector>

#include "operator/boundary_blocks.hpp"
#include "operator/csr_matrix.hpp"

namespace rumble::fem {

/// How the step streams K: its values rounded to single precision (4 B each, the sums in double)
/// or in double. Rounding moves each entry by at most 6e-8 of itself, far below the step's
/// O(dt^2) error; K stays symmetric, so the step keeps its energy (docs/fem-soil.md §4.2).
enum class StepPrecision { kDouble, kSingle };

/// Takes the step's product (K x) in runs of consecutive nodes: products[3 k + c] is (K x) at
/// node first + k, DOF c (K as the step reads it, without S). Called by the thread that owns
/// those nodes; runs of one call never overlap.
class NodeProducts {
 public:
  virtual ~NodeProducts() = default;
  virtual void take(std::int64_t first, std::int64_t count, const double* products) = 0;
};

/// NodeProducts from a per-node function finish(node, product) (3 doubles).
template <class Finish>
class NodeProductsOf final : public NodeProducts {
 public:
  explicit NodeProductsOf(Finish& finish) : finish_(finish) {}
  void take(std::int64_t first, std::int64_t count, const double* products) override {
    for (std::int64_t k = 0; k < count; ++k) finish_(first + k, products + 3 * k);
  }

 private:
  Finish& finish_;
};

/// Gathers one thread's node products, which come in ascending runs of nodes, into runs of up
/// to kRun nodes (on the stack, in the cache) and hands each to `take` at once: the virtual call
/// once per run, not per node. add() each product in order, then flush().
class ProductRuns {
 public:
  explicit ProductRuns(NodeProducts& take) : take_(take) {}
  void add(std::int64_t i, const double* product) {
    if (count_ == kRun || (count_ > 0 && i != first_ + count_)) flush();
    if (count_ == 0) first_ = i;
    std::copy_n(product, 3, run_ + 3 * count_);
    ++count_;
  }
  void flush() {
    if (count_ > 0) take_.take(first_, count_, run_);
    count_ = 0;
  }

 private:
  static constexpr std::int64_t kRun = 64;
  NodeProducts& take_;
  double run_[3 * kRun];
  std::int64_t first_ = 0, count_ = 0;
};

class SoilOperator {
 public:
  virtual ~SoilOperator() = default;
  SoilOperator(const SoilOperator&) = delete;
  SoilOperator& operator=(const SoilOperator&) = delete;

  // The node data, 3 DOFs per node.
  Eigen::Index nodes() const { return mass_.size(); }
  Eigen::Index dofs() const { return 3 * mass_.size(); }
  /// Lumped mass per node [kg].
  const Eigen::VectorXd& mass() const { return mass_; }
  /// The truncation surface's blocks S (springs_act()) and D.
  const std::vector<BoundaryNode>& boundary() const { return boundary_; }
  /// Per node: its index into boundary(), or -1.
  const std::vector<std::int32_t>& boundary_of() const { return boundary_of_; }
  /// Whether S acts in the dynamics (the statics always take it).
  bool springs_act() const { return springs_; }
  /// Per node: never moves (its DOFs' rows and columns are identity in every matrix).
  const std::vector<char>& fixed() const { return fixed_; }
  unsigned threads() const { return threads_; }
  /// Called between the iterations of long loops (eigenvalue iterations, conjugate gradients):
  /// the plugin's Ctrl-C check, which throws to stop. None by default.
  void set_stop_check(std::function<void()> check) { stop_check_ = std::move(check); }
  void check_stop() const {
    if (stop_check_) stop_check_();
  }

  // What a back end implements.
  /// Threads for the products (the host grants them per run).
  virtual void set_threads(unsigned threads) = 0;
  /// y = K x + S x (S when with_springs), K in double; 0 on fixed nodes.
  virtual void stiffness_times(const Eigen::VectorXd& x, Eigen::VectorXd& y,
                               bool with_springs) const = 0;
  /// The same with K as the step reads it (precision()): the statics' and the eigenvalue
  /// iterations' product, threaded.
  virtual void stepped_stiffness_times(const Eigen::VectorXd& x, Eigen::VectorXd& y,
                                       bool with_springs) const = 0;
  /// The explicit step's product: K x (as the step reads it) handed to `take` node by node,
  /// every node once. Called by every thread of an OpenMP team, x complete before (a barrier)
  /// and unchanged; no barrier at the end.
  virtual void stepped_product(const double* x, NodeProducts& take) const = 0;
  virtual StepPrecision precision() const = 0;
  /// K's assembled rows in double (CSR, 3 DOFs per node): what the direct solvers factor
  /// (effective_matrix.hpp), the matrices the plugin exports (linear_matrices.hpp) and the
  /// receptance's.
  virtual const CsrMatrix& stiffness() const = 0;
  /// K's diagonal in double (on a rank, its part's: summed over the ranks by the caller): the
  /// multigrids' Jacobi. By default read from stiffness()'s rows.
  virtual Eigen::VectorXd stiffness_diagonal() const {
    const std::vector<double> d = stiffness().diagonal();
    return Eigen::Map<const Eigen::VectorXd>(d.data(), static_cast<Eigen::Index>(d.size()));
  }
  /// Memory held [bytes], the node data included.
  virtual std::size_t bytes() const = 0;

  // K's assembled rows when the step reads its own copy (issue #33: memory per DOF). A back end
  // that can build them again frees them between uses; by default it keeps them.
  /// `assemble` builds K's rows, the same to the bit as those given (the assembly is
  /// deterministic): from then on they may be freed and are built again when next asked for.
  virtual void set_stiffness_source(std::function<CsrMatrix()> assemble) { (void)assemble; }
  /// Frees K's rows until stiffness() is next called (not while a caller reads them); nothing
  /// without a source.
  virtual void release_stiffness() const {}
  /// K's rows handed over to a caller that would otherwise copy them (the statics' multigrid):
  /// with a source the operator's are moved out (built again when next asked for), else copied.
  virtual CsrMatrix take_stiffness() const { return stiffness(); }
  /// Whether K's rows are held now (bytes() counts them then).
  virtual bool holds_stiffness() const { return true; }

  // Sums over the whole soil, for the eigenvalue iterations that set the stable step (issue #33:
  // on many ranks every rank must reach the same step). One process sums its own nodes.
  /// sum over the DOFs of x_k y_k, each weighted by its node's `node_weight` when not null:
  /// on many ranks each node counted once (by its owner), the ranks' sums added in one fixed
  /// order, the same value on every rank. Collective there.
  virtual double dot(const Eigen::VectorXd& x, const Eigen::VectorXd& y,
                     const double* node_weight) const {
    if (node_weight == nullptr) return x.dot(y);
    const std::int64_t n = x.size();
    double s = 0.0;
#pragma omp parallel for num_threads(threads_) reduction(+ : s) schedule(static)
    for (std::int64_t k = 0; k < n; ++k) s += node_weight[k / 3] * x[k] * y[k];
    return s;
  }
  /// The sum and the largest over the soil's nodes of a per-node value that every copy of a
  /// node holds alike: on many ranks each node counted once (by its owner), the same value on
  /// every rank. Collective there. For the local time stepping's choice (time/
  /// local_steps_choice.cpp), whose counts must be one process's on any number of ranks.
  virtual double sum_over_nodes(const std::vector<double>& per_node) const {
    double s = 0.0;
    for (const double v : per_node) s += v;
    return s;
  }
  virtual double max_over_nodes(const std::vector<double>& per_node) const {
    return per_node.empty() ? 0.0 : *std::max_element(per_node.begin(), per_node.end());
  }
  /// K as the step reads it (precision()), block by block, each once: visit(i, j, block) with
  /// K_ij's 9 values row-major [N/m], for the diagonal (j == i) and for each pair of neighbours
  /// in one of its two orders (K_ji is the transpose). What the local time stepping's set-up
  /// reads, so that it needs no assembled rows (on the ranks they would be built again for it:
  /// 0.7 kB per DOF of a rank's share at its peak). By default from stiffness()'s rows.
  using BlockVisit = std::function<void(std::int32_t, std::int32_t, const double*)>;
  virtual void for_each_step_block(const BlockVisit& visit) const {
    stiffness().for_each_upper_block(visit);
  }
  /// From K's whole rows as the step reads them (for_each_step_block; a rank's part holds them
  /// only in part at its shared nodes and completes them over the ranks). Collective there.
  /// Per DOF k: sum_j |K_kj| (Gershgorin's bound on M^-1 K's eigenvalues, over the mass).
  virtual std::vector<double> row_magnitude_sums() const {
    std::vector<double> sums(static_cast<std::size_t>(dofs()), 0.0);
    for_each_step_block([&](std::int32_t i, std::int32_t j, const double* b) {
      for (int c = 0; c < 3; ++c)
        for (int d = 0; d < 3; ++d) {
          sums[3 * static_cast<std::size_t>(i) + c] += std::abs(b[3 * c + d]);
          if (j != i) sums[3 * static_cast<std::size_t>(j) + d] += std::abs(b[3 * c + d]);
        }
    });
    return sums;
  }
  /// Per node i: how many nodes j with flag[j] (per node, alike at every copy) K's pattern
  /// couples it to, i itself included.
  virtual std::vector<std::int32_t> flagged_neighbours(const std::vector<char>& flag) const {
    std::vector<std::int32_t> count(static_cast<std::size_t>(nodes()), 0);
    for_each_step_block([&](std::int32_t i, std::int32_t j, const double*) {
      count[i] += flag[j] ? 1 : 0;
      if (j != i) count[j] += flag[i] ? 1 : 0;
    });
    return count;
  }
  /// Node i's number in the whole mesh: the eigenvalue iterations' start follows it, so that
  /// a split soil starts where one process does.
  virtual std::int64_t whole_node(std::int64_t i) const {
    return i;
  }
  /// Whether the operator is one rank's part of a mesh split over ranks, whose nodes
  /// [0, shared_nodes()) other ranks hold too (false on one process: none).
  virtual bool spans_ranks() const {
    return false;
  }
  virtual std::int32_t shared_nodes() const {
    return 0;
  }
  /// Sums `width` values per node over the ranks at the shared nodes (values[width i + c] for
  /// i < shared_nodes()), each copy then holding the sum: a step's own per-node terms (the
  /// matched layer's forces, time/explicit_solver.cpp). Collective over the ranks; called by one
  /// thread. Nothing to sum on one process.
  virtual void sum_shared_nodes(double* values, int width) const {
    (void)values;
    (void)width;
  }

 protected:
  SoilOperator(Eigen::VectorXd mass, std::vector<BoundaryNode> boundary, bool springs,
               std::vector<char> fixed, unsigned threads)
      : mass_(std::move(mass)),
        boundary_(std::move(boundary)),
        boundary_of_(mass_.size(), -1),
        springs_(springs),
        fixed_(std::move(fixed)),
        threads_(threads < 1 ? 1 : threads) {
    for (std::size_t k = 0; k < boundary_.size(); ++k)
      boundary_of_[boundary_[k].node] = static_cast<std::int32_t>(k);
  }
  /// The node data's bytes.
  std::size_t node_bytes() const {
    return static_cast<std::size_t>(mass_.size()) * (8 + 4 + 1) +
           boundary_.size() * sizeof(BoundaryNode);
  }

  Eigen::VectorXd mass_;
  std::vector<BoundaryNode> boundary_;
  std::vector<std::int32_t> boundary_of_;  // per node: index into boundary_, or -1
  bool springs_;
  std::vector<char> fixed_;
  unsigned threads_;

 private:
  std::function<void()> stop_check_;
};

}  // namespace rumble::fem
