// Smoothed-aggregation algebraic multigrid (Vanek, Mandel and Brezina 1996) for the static
// stiffness K + S, as the preconditioner of conjugate gradients on meshes whose Cholesky factor
// does not fit (StaticSolver above its factor limit; docs/numerics.md §4.2: 17 GB at 1e6 DOFs).
// Jacobi-preconditioned CG needs a number of iterations that grows with the mesh (613 at 6.8e4
// DOFs, 886 at 2.1e5 on the stiff example, bench/fem/fem_static_bench.cpp) and the engine's
// static iteration asks for a solve per track/soil iteration; multigrid's count stays nearly
// flat.
//
// Hierarchy: nodes (3 DOFs each on the mesh, up to 6 on coarse levels) are aggregated greedily
// over the matrix graph (a root and its unaggregated neighbours, then the rest joined to a
// neighbouring aggregate); the tentative prolongator interpolates the six rigid-body modes (the
// near-null space of elasticity, from the node coordinates) exactly on each aggregate (a QR per
// aggregate), and is smoothed by one damped Jacobi step, P = (I - 4/3 D^-1 A / lambda) P0; the
// coarse matrix is P^T A P, down to a few thousand DOFs factored by CHOLMOD. One V-cycle with
// a damped Jacobi sweep before and after the coarse correction is a symmetric positive definite
// preconditioner, as CG requires.
#pragma once

#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <memory>
#include <vector>

#include "operator/effective_matrix.hpp"
#include "operator/sparse_product.hpp"
#include "statics/mesh_coarsening.hpp"
#include "statics/mesh_matrix.hpp"
#include "statics/transposed_product.hpp"

namespace rumble::fem {

class AmgPreconditioner {
 public:
  /// y = A x on the mesh's level, by another kernel than Eigen's scalar rows.
  using Product = std::function<void(const Eigen::VectorXd&, Eigen::VectorXd&)>;

  /// a: a symmetric positive definite matrix over 3 DOFs per node, whole (as full_combination
  /// gives); nodes: their coordinates [m] (3 x nodes). Rows that are
  /// identity (fixed DOFs) are handled: the rigid-body modes vanish there. fine_product, when
  /// given, takes the V-cycle's products on the mesh's level (the soil operator's threaded
  /// rows, with K in the step's precision: a symmetric operator within 6e-8 of A, which keeps
  /// the V-cycle a fixed symmetric preconditioner); that level's own copy of A is then freed
  /// after the set-up. It must agree with A on the free DOFs and give 0 or x on fixed ones
  /// (their residual, and so their correction, is 0 either way).
  /// threads: the set-up's Galerkin products and the V-cycle's products below the mesh's level
  /// (sparse_product.hpp) share them.
  AmgPreconditioner(RowSparse a, const Eigen::Matrix3Xd& nodes, Product fine_product = {},
                    unsigned threads = 1);
  /// The same hierarchy and V-cycle, to the bit, from the mesh's matrix in K's own blocks
  /// (mesh_matrix.hpp), taken and freed on the way: the mesh's level is coarsened a chunk of
  /// aggregates at a time (mesh_coarsening.hpp), without A P, P and R whole in double, and its
  /// restriction runs on P's rows (transposed_product.hpp); docs/fem-soil.md section 7.2 has
  /// the memory this saves. fine_product is needed. chunk_nodes: the mesh's nodes per chunk
  /// (a test makes it small).
  AmgPreconditioner(MeshMatrix a, const Eigen::Matrix3Xd& nodes, Product fine_product,
                    unsigned threads = 1, std::int64_t chunk_nodes = kMeshChunkNodes);
  ~AmgPreconditioner();
  AmgPreconditioner(const AmgPreconditioner&) = delete;
  AmgPreconditioner& operator=(const AmgPreconditioner&) = delete;

  /// z = M^-1 r: one V-cycle from z = 0. Uses the preconditioner's own scratch (not reentrant).
  void apply(const Eigen::VectorXd& r, Eigen::VectorXd& z) const;

  int levels() const { return static_cast<int>(levels_.size()); }
  /// Memory the V-cycle keeps [bytes]: its float matrices, vectors and the coarsest factor.
  std::size_t bytes() const;
  /// DOFs of level l (0 = the mesh).
  Eigen::Index dofs(int level) const;
  /// Nonzeros of all levels' matrices over the mesh's: the V-cycle's work per fine SpMV.
  double operator_complexity() const;

 private:
  struct Level {
    RowSparse A;  // this level's matrix (full, symmetric), during the set-up
    // What the V-cycle streams, in float: the matrix (none on the mesh's level when the fine
    // product takes it), the prolongator from the next level and its transpose.
    RowSparseFloat cycle_A, P, R;
    TransposedProduct restriction;  // R's product from P's rows where R is not stored (the mesh's)
    Eigen::Index rows = 0, nonzeros = 0;
    Eigen::VectorXd scaled_inverse_diagonal;  // (4/3) / (lambda_max(D^-1 A) d_i)
    mutable Eigen::VectorXd x, b, r;          // scratch of the V-cycle (sized at its first)
  };
  struct Coarse;
  void cycle(std::size_t l) const;
  /// The next level below L: its matrix into A, its modes into B, its nodes' DOFs into start;
  /// false (nothing changed) when aggregation no longer coarsens enough.
  bool coarsen(Level& L, RowSparse& A, Eigen::MatrixXd& B, std::vector<Eigen::Index>& start,
               unsigned threads);
  /// The same from the mesh's matrix (taken when it coarsens; left as it was when not).
  bool coarsen_mesh(Level& L, MeshMatrix& a, RowSparse& A, Eigen::MatrixXd& B,
                    std::vector<Eigen::Index>& start, std::int64_t chunk_nodes);
  /// Levels from A down (A, B and start as coarsen leaves them), factored and kept.
  void build_levels(RowSparse& A, Eigen::MatrixXd& B, std::vector<Eigen::Index>& start);
  void factor_coarsest();  // the coarsest level's Cholesky factor (throws when indefinite)
  void keep_cycle_matrix(std::size_t level);  // its V-cycle's float matrix; the double freed

  std::vector<Level> levels_;
  std::unique_ptr<Coarse> coarse_;
  Product fine_product_;  // empty: level 0 uses its A
  unsigned threads_;      // the V-cycle's products below the mesh's
};

}  // namespace rumble::fem
