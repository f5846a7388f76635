#include "statics/amg_preconditioner.hpp"

#include <Eigen/QR>
#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "operator/sparse_product.hpp"
#include "statics/mesh_coarsening.hpp"

namespace rumble::fem {

namespace {

constexpr Eigen::Index kCoarsestDofs = 4000;  // factored directly (a dense-ish 4000^2: < 1 s)
constexpr std::size_t kMaxLevels = 12;
// Damped Jacobi sweeps before and after the coarse correction: two took 36 CG iterations instead
// of 50 on the 68k-DOF mesh of bench/fem/fem_static_bench.cpp, in the same time.
constexpr int kSweeps = 1;

using Triplet = Eigen::Triplet<double, int>;

/// The six rigid-body modes (3 translations, 3 rotations about the centroid) at each DOF.
/// Rows of DOFs that are decoupled identities (fixed: held(row)) are zero.
template <class Held>
Eigen::MatrixXd rigid_body_modes(Eigen::Index rows, const Eigen::Matrix3Xd& nodes, Held held) {
  const Eigen::Vector3d centre = nodes.rowwise().mean();
  Eigen::MatrixXd B = Eigen::MatrixXd::Zero(rows, 6);
  for (Eigen::Index i = 0; i < nodes.cols(); ++i) {
    const Eigen::Vector3d p = nodes.col(i) - centre;
    for (int c = 0; c < 3; ++c) B(3 * i + c, c) = 1.0;
    B.block<3, 3>(3 * i, 3) << 0.0, p.z(), -p.y(),  // rows x, y, z of e_k x p, k = x, y, z
        -p.z(), 0.0, p.x(),                         //
        p.y(), -p.x(), 0.0;
  }
  for (Eigen::Index r = 0; r < rows; ++r)
    if (held(r)) B.row(r).setZero();
  return B;
}

/// A RowSparse read as MeshMatrix is read: visit(column, value) along a row.
struct SparseRows {
  const RowSparse& a;
  template <class Visit>
  void for_each_in_row(Eigen::Index row, Visit&& visit) const {
    for (RowSparse::InnerIterator it(a, row); it; ++it) visit(it.col(), it.value());
  }
};

/// Each node's first DOF on the mesh (3 per node), then the count.
std::vector<Eigen::Index> mesh_dofs(Eigen::Index nodes) {
  std::vector<Eigen::Index> start(static_cast<std::size_t>(nodes) + 1);
  for (std::size_t k = 0; k < start.size(); ++k) start[k] = 3 * static_cast<Eigen::Index>(k);
  return start;
}

/// Each DOF's node at a level whose node k owns DOFs [start[k], start[k + 1]).
std::vector<std::int32_t> node_of_dof(const std::vector<Eigen::Index>& start) {
  std::vector<std::int32_t> node(static_cast<std::size_t>(start.back()));
  for (std::size_t k = 0; k + 1 < start.size(); ++k)
    std::fill(node.begin() + start[k], node.begin() + start[k + 1], static_cast<std::int32_t>(k));
  return node;
}

/// Greedy aggregation over the node graph of A (a RowSparse as SparseRows, or the MeshMatrix):
/// returns each node's aggregate and the count.
template <class Matrix>
std::pair<std::vector<std::int32_t>, std::int32_t> aggregate(
    const Matrix& A, const std::vector<Eigen::Index>& start) {
  const std::size_t nodes = start.size() - 1;
  const std::vector<std::int32_t> node = node_of_dof(start);
  std::vector<std::int64_t> neighbour_start(nodes + 1, 0);
  std::vector<std::int32_t> neighbour, mark(nodes, -1);
  for (std::size_t i = 0; i < nodes; ++i) {
    for (Eigen::Index r = start[i]; r < start[i + 1]; ++r)
      A.for_each_in_row(r, [&](Eigen::Index column, double value) {
        const std::int32_t j = node[static_cast<std::size_t>(column)];
        if (j != static_cast<std::int32_t>(i) &&
            mark[static_cast<std::size_t>(j)] != static_cast<std::int32_t>(i) && value != 0.0) {
          mark[static_cast<std::size_t>(j)] = static_cast<std::int32_t>(i);
          neighbour.push_back(j);
        }
      });
    neighbour_start[i + 1] = static_cast<std::int64_t>(neighbour.size());
  }
  std::vector<std::int32_t> agg(nodes, -1);
  std::int32_t count = 0;
  const auto neighbours_of = [&](std::size_t i) {
    return std::pair{neighbour.begin() + neighbour_start[i],
                     neighbour.begin() + neighbour_start[i + 1]};
  };
  // 1: a root whose neighbours are all free takes them.
  for (std::size_t i = 0; i < nodes; ++i) {
    if (agg[i] >= 0) continue;
    const auto [b, e] = neighbours_of(i);
    if (std::any_of(b, e, [&](std::int32_t j) { return agg[static_cast<std::size_t>(j)] >= 0; }))
      continue;
    agg[i] = count;
    for (auto j = b; j != e; ++j) agg[static_cast<std::size_t>(*j)] = count;
    ++count;
  }
  // 2: the rest join a neighbouring aggregate; 3: what has none starts its own.
  for (std::size_t i = 0; i < nodes; ++i) {
    if (agg[i] >= 0) continue;
    const auto [b, e] = neighbours_of(i);
    const auto j =
        std::find_if(b, e, [&](std::int32_t k) { return agg[static_cast<std::size_t>(k)] >= 0; });
    agg[i] = j != e ? agg[static_cast<std::size_t>(*j)] : count++;
  }
  return {std::move(agg), count};
}

/// Largest eigenvalue of D^-1 A by power iteration, with a 10 % margin (an underestimate would
/// make the damped Jacobi steps amplify the top of the spectrum).
/// times: y = A x.
double largest_eigenvalue(
    const std::function<void(const Eigen::VectorXd&, Eigen::VectorXd&)>& times,
    const Eigen::VectorXd& inverse_diagonal) {
  const Eigen::Index n = inverse_diagonal.size();
  Eigen::VectorXd x = Eigen::VectorXd::Ones(n), y(n);
  for (Eigen::Index i = 0; i < x.size(); i += 7) x[i] = -0.5;  // not an eigenvector by chance
  double lambda = 0.0;
  for (int k = 0; k < 20; ++k) {
    times(x, y);
    y.array() *= inverse_diagonal.array();
    lambda = y.norm() / x.norm();
    x = y / y.norm();
  }
  return 1.1 * lambda;
}

/// P = P0 - W A P0 (W: the scaled inverse diagonal), built in the storage of A P0: P0's pattern
/// lies within A P0's, as A's diagonal is nonzero.
RowSparse smoothed_prolongator(const RowSparse& A, const RowSparse& P0, const Eigen::VectorXd& w,
                               unsigned threads) {
  RowSparse P = sparse_product(A, P0, threads);
  for (int i = 0; i < P.rows(); ++i) {
    int* first = P.innerIndexPtr() + P.outerIndexPtr()[i];
    int* last = P.innerIndexPtr() + P.outerIndexPtr()[i + 1];
    double* value = P.valuePtr() + P.outerIndexPtr()[i];
    for (int* k = first; k != last; ++k) value[k - first] *= -w[i];
    for (RowSparse::InnerIterator it(P0, i); it; ++it) {
      int* k = std::lower_bound(first, last, static_cast<int>(it.col()));
      if (k == last || *k != it.col())
        throw std::logic_error("multigrid: a zero on the stiffness' diagonal");
      value[k - first] += it.value();
    }
  }
  return P;
}

// The tentative prolongator of one level: the DOFs of each aggregate, and on each a QR of the
// modes B restricted to them, whose Q is the prolongator's block and whose R the coarse modes.
struct Tentative {
  std::vector<Triplet> p0;
  std::vector<Eigen::Index> coarse_start{0};  // each aggregate's first coarse DOF, then the count
  std::vector<Eigen::MatrixXd> coarse_modes;  // per aggregate
};

Tentative tentative_prolongator(const Eigen::MatrixXd& B, const std::vector<Eigen::Index>& start,
                                const std::vector<std::int32_t>& agg, std::int32_t count) {
  std::vector<std::vector<Eigen::Index>> dofs(static_cast<std::size_t>(count));
  for (std::size_t i = 0; i + 1 < start.size(); ++i)
    for (Eigen::Index r = start[i]; r < start[i + 1]; ++r)
      dofs[static_cast<std::size_t>(agg[i])].push_back(r);
  Tentative t;
  for (const std::vector<Eigen::Index>& d : dofs) {
    const auto m = static_cast<Eigen::Index>(d.size());
    Eigen::MatrixXd local(m, B.cols());
    for (Eigen::Index k = 0; k < m; ++k) local.row(k) = B.row(d[static_cast<std::size_t>(k)]);
    Eigen::ColPivHouseholderQR<Eigen::MatrixXd> qr(local);
    qr.setThreshold(1e-10);
    const Eigen::Index rank = qr.rank();
    if (rank == 0) {  // held nodes only: no coarse DOFs, the smoother alone (identity rows)
      t.coarse_modes.emplace_back(0, B.cols());
      t.coarse_start.push_back(t.coarse_start.back());
      continue;
    }
    const Eigen::MatrixXd q = qr.householderQ() * Eigen::MatrixXd::Identity(m, rank);
    const Eigen::MatrixXd upper = qr.matrixR().topRows(rank).triangularView<Eigen::Upper>();
    t.coarse_modes.push_back(upper * qr.colsPermutation().transpose());
    const Eigen::Index offset = t.coarse_start.back();
    for (Eigen::Index k = 0; k < m; ++k)
      for (Eigen::Index c = 0; c < rank; ++c)
        t.p0.emplace_back(static_cast<int>(d[static_cast<std::size_t>(k)]),
                          static_cast<int>(offset + c), q(k, c));
    t.coarse_start.push_back(offset + rank);
  }
  return t;
}

/// a in float, its storage sized once: Eigen's cast grows the result by reallocations, which at
/// 1e6 DOFs held 0.5 GB more than the two matrices for a moment (the first coarse level's).
void to_float(const RowSparse& a, RowSparseFloat& out) {
  RowSparseFloat f(a.rows(), a.cols());
  f.resizeNonZeros(a.nonZeros());
  std::copy_n(a.outerIndexPtr(), a.outerSize() + 1, f.outerIndexPtr());
  std::copy_n(a.innerIndexPtr(), a.nonZeros(), f.innerIndexPtr());
  for (Eigen::Index k = 0; k < a.nonZeros(); ++k)
    f.valuePtr()[k] = static_cast<float>(a.valuePtr()[k]);
  out.swap(f);
}

/// The next level's rigid-body modes into B (the aggregates' R factors, stacked).
void coarse_modes(const Tentative& t, Eigen::MatrixXd& B) {
  B.resize(t.coarse_start.back(), B.cols());
  for (std::size_t g = 0; g < t.coarse_modes.size(); ++g)
    B.middleRows(t.coarse_start[g], t.coarse_start[g + 1] - t.coarse_start[g]) = t.coarse_modes[g];
}

/// The mesh's matrix in compressed rows (a mesh small enough to be the coarsest level).
RowSparse whole(const MeshMatrix& a) {
  RowSparse A(a.rows(), a.rows());
  std::vector<int> count(static_cast<std::size_t>(a.rows()), 0);
  for (Eigen::Index r = 0; r < a.rows(); ++r)
    a.for_each_in_row(r, [&](Eigen::Index, double) { ++count[static_cast<std::size_t>(r)]; });
  A.reserve(count);
  for (Eigen::Index r = 0; r < a.rows(); ++r)
    a.for_each_in_row(r, [&](Eigen::Index c, double v) {
      A.insert(static_cast<int>(r), static_cast<int>(c)) = v;
    });
  A.makeCompressed();
  return A;
}

}  // namespace

struct AmgPreconditioner::Coarse {
  Eigen::CholmodSupernodalLLT<Eigen::SparseMatrix<double>, Eigen::Lower> llt;
};

AmgPreconditioner::AmgPreconditioner(RowSparse a, const Eigen::Matrix3Xd& nodes,
                                     Product fine_product, unsigned threads)
    : coarse_(std::make_unique<Coarse>()),
      fine_product_(std::move(fine_product)),
      threads_(threads < 1 ? 1 : threads) {
  if (a.rows() != 3 * nodes.cols())
    throw std::invalid_argument("AmgPreconditioner: the matrix is not 3 DOFs per node");
  levels_.reserve(kMaxLevels);  // (a reallocation would copy the levels' matrices)
  if (!a.isCompressed()) a.makeCompressed();
  // (Eigen 3.4's SparseMatrix has no move constructor nor move assignment: std::move and the
  // assignment of a returned matrix copy it, at the mesh's level a GB of fresh pages. Swaps.)
  RowSparse A;
  A.swap(a);
  Eigen::MatrixXd B = rigid_body_modes(A.rows(), nodes, [&](Eigen::Index r) {
    return A.outerIndexPtr()[r + 1] - A.outerIndexPtr()[r] == 1;
  });
  std::vector<Eigen::Index> start = mesh_dofs(nodes.cols());
  build_levels(A, B, start);
}

AmgPreconditioner::AmgPreconditioner(MeshMatrix a, const Eigen::Matrix3Xd& nodes,
                                     Product fine_product, unsigned threads,
                                     std::int64_t chunk_nodes)
    : coarse_(std::make_unique<Coarse>()),
      fine_product_(std::move(fine_product)),
      threads_(threads < 1 ? 1 : threads) {
  if (a.rows() != 3 * nodes.cols())
    throw std::invalid_argument("AmgPreconditioner: the matrix is not 3 DOFs per node");
  if (!fine_product_)
    throw std::invalid_argument("AmgPreconditioner: the mesh's matrix needs the mesh's product");
  levels_.reserve(kMaxLevels);
  Eigen::MatrixXd B =
      rigid_body_modes(a.rows(), nodes, [&](Eigen::Index r) { return a.held(r / 3); });
  std::vector<Eigen::Index> start = mesh_dofs(nodes.cols());
  Level& L = levels_.emplace_back();
  L.rows = a.rows();
  L.nonzeros = a.nonzeros();
  RowSparse A;
  if (L.rows > kCoarsestDofs && coarsen_mesh(L, a, A, B, start, chunk_nodes)) {
    build_levels(A, B, start);
    return;
  }
  // The mesh is the coarsest level (a few thousand DOFs): its matrix whole, factored.
  RowSparse matrix = whole(a);
  L.A.swap(matrix);
  factor_coarsest();
}

void AmgPreconditioner::build_levels(RowSparse& A, Eigen::MatrixXd& B,
                                     std::vector<Eigen::Index>& start) {
  for (;;) {
    Level& L = levels_.emplace_back();
    L.A.swap(A);
    L.rows = L.A.rows();
    L.nonzeros = L.A.nonZeros();
    if (L.rows <= kCoarsestDofs || levels_.size() == kMaxLevels) break;
    if (!coarsen(L, A, B, start, threads_)) break;  // no coarsening left: factor this level
    keep_cycle_matrix(levels_.size() - 1);          // (its double matrix is done with)
  }
  factor_coarsest();
}

bool AmgPreconditioner::coarsen_mesh(Level& L, MeshMatrix& a, RowSparse& A, Eigen::MatrixXd& B,
                                     std::vector<Eigen::Index>& start, std::int64_t chunk_nodes) {
  const Eigen::Index n = a.rows();
  auto [agg, count] = aggregate(a, start);
  Tentative t = tentative_prolongator(B, start, agg, count);
  const Eigen::Index nc = t.coarse_start.back();
  if (nc == 0 || nc > n * 7 / 10) return false;
  Eigen::VectorXd inverse_diagonal(n);
  for (Eigen::Index r = 0; r < n; ++r) inverse_diagonal[r] = 1.0 / a.diagonal(r);
  const double lambda = largest_eigenvalue(fine_product_, inverse_diagonal);
  inverse_diagonal *= 4.0 / 3.0 / lambda;  // (in place: a vector of the mesh's size less)
  L.scaled_inverse_diagonal.swap(inverse_diagonal);
  RowSparse P0(n, nc);
  P0.setFromTriplets(t.p0.begin(), t.p0.end());
  std::vector<Triplet>().swap(t.p0);
  coarse_modes(t, B);
  const MeshAggregates aggregates{std::move(agg), t.coarse_start};
  coarsen_mesh_matrix(std::move(a), P0, L.scaled_inverse_diagonal, aggregates, threads_, A, L.P,
                      chunk_nodes);
  L.restriction = TransposedProduct(L.P, threads_);
  start = std::move(t.coarse_start);
  return true;
}

bool AmgPreconditioner::coarsen(Level& L, RowSparse& A, Eigen::MatrixXd& B,
                                std::vector<Eigen::Index>& start, unsigned threads) {
  const Eigen::Index n = L.A.rows();
  const auto [agg, count] = aggregate(SparseRows{L.A}, start);
  Tentative t = tentative_prolongator(B, start, agg, count);
  const Eigen::Index nc = t.coarse_start.back();
  if (nc == 0 || nc > n * 7 / 10) return false;

  Eigen::VectorXd inverse_diagonal = L.A.diagonal().cwiseInverse();
  // (On the mesh's level by the fine product where there is one: the same operator as the
  // smoother's, threaded.)
  const double lambda = largest_eigenvalue(
      [&](const Eigen::VectorXd& x, Eigen::VectorXd& y) {
        if (levels_.size() == 1 && fine_product_)
          fine_product_(x, y);
        else
          multiply(L.A, x, y, threads_);
      },
      inverse_diagonal);
  L.scaled_inverse_diagonal = (4.0 / 3.0 / lambda) * inverse_diagonal;
  RowSparse P0(n, nc);
  P0.setFromTriplets(t.p0.begin(), t.p0.end());
  std::vector<Triplet>().swap(t.p0);
  const RowSparse P = smoothed_prolongator(L.A, P0, L.scaled_inverse_diagonal, threads);
  const RowSparse R = P.transpose();
  RowSparse coarse = sparse_product(R, sparse_product(L.A, P, threads), threads);
  A.swap(coarse);
  to_float(P, L.P);
  to_float(R, L.R);

  coarse_modes(t, B);
  start = std::move(t.coarse_start);
  return true;
}

void AmgPreconditioner::factor_coarsest() {
  Level& last = levels_.back();
  const Eigen::SparseMatrix<double> lower = last.A.triangularView<Eigen::Lower>();
  coarse_->llt.compute(lower);
  if (coarse_->llt.info() != Eigen::Success)
    throw std::runtime_error(
        "fem: the static stiffness is not positive definite (multigrid's coarsest level); the "
        "mesh floats: give the boundary springs or a fixed boundary");
  RowSparse().swap(last.A);  // (the factor's now; assigning an empty matrix keeps the storage)
}

void AmgPreconditioner::keep_cycle_matrix(std::size_t l) {
  // The V-cycle's matrix in float, as soon as the level below is built (its double is then done
  // with: at 1e6 DOFs the first coarse level's double and float were 0.6 GB together). The mesh's
  // level's is the fine product's when there is one, and the coarsest level's is the factor's.
  Level& L = levels_[l];
  if (!(l == 0 && fine_product_)) to_float(L.A, L.cycle_A);
  RowSparse().swap(L.A);
}

AmgPreconditioner::~AmgPreconditioner() = default;

Eigen::Index AmgPreconditioner::dofs(int level) const {
  return levels_.at(static_cast<std::size_t>(level)).rows;
}

std::size_t AmgPreconditioner::bytes() const {
  const auto stored = [](const RowSparseFloat& m) {
    return static_cast<std::size_t>(m.nonZeros()) * 8 + static_cast<std::size_t>(m.outerSize()) * 4;
  };
  std::size_t b = coarse_->llt.cholmod().memory_inuse;
  for (const Level& L : levels_)
    b += stored(L.cycle_A) + stored(L.P) + stored(L.R) + L.restriction.bytes() +
         static_cast<std::size_t>(L.scaled_inverse_diagonal.size() + L.x.size() + L.b.size() +
                                  L.r.size()) *
             8;
  return b;
}

double AmgPreconditioner::operator_complexity() const {
  const auto fine = static_cast<double>(levels_.front().nonzeros);
  double total = fine;
  for (std::size_t l = 1; l < levels_.size(); ++l)
    total += static_cast<double>(levels_[l].nonzeros);
  return total / fine;
}

void AmgPreconditioner::cycle(std::size_t l) const {
  const Level& L = levels_[l];
  if (l + 1 == levels_.size()) {
    L.x = coarse_->llt.solve(L.b);
    return;
  }
  const auto residual_product = [&] {  // L.r = A x
    if (l == 0 && fine_product_)
      fine_product_(L.x, L.r);
    else
      multiply(L.cycle_A, L.x, L.r, threads_);
  };
  const auto smooth = [&] {
    residual_product();
    L.x.array() += L.scaled_inverse_diagonal.array() * (L.b - L.r).array();
  };
  L.x = L.scaled_inverse_diagonal.cwiseProduct(L.b);  // the first sweep, from x = 0
  for (int s = 1; s < kSweeps; ++s) smooth();
  residual_product();
  const Level& C = levels_[l + 1];
  L.r = L.b - L.r;
  if (L.R.nonZeros() > 0)
    multiply(L.R, L.r, C.b, threads_);
  else
    L.restriction.multiply(L.P, L.r, C.b);
  cycle(l + 1);
  multiply_add(L.P, C.x, L.x, threads_);
  for (int s = 0; s < kSweeps; ++s) smooth();
}

void AmgPreconditioner::apply(const Eigen::VectorXd& r, Eigen::VectorXd& z) const {
  levels_.front().b = r;
  cycle(0);
  z = levels_.front().x;
}

}  // namespace rumble::fem
