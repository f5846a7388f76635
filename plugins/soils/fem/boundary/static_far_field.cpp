#include "boundary/static_far_field.hpp"

#include <algorithm>
#include <array>

#include "boussinesq_field.hpp"

namespace rumble::fem {

void add_load_points(const Footprint& footprint, double share, std::vector<LoadPoint>& points) {
  static constexpr std::array<double, 2> kAcross = {-0.5773502691896257, 0.5773502691896257};
  static constexpr std::array<double, 4> kAlong = {-0.8611363115940526, -0.3399810435848563,
                                                   0.3399810435848563, 0.8611363115940526};
  static constexpr std::array<double, 4> kWeights = {0.3478548451374538, 0.6521451548625461,
                                                     0.6521451548625461, 0.3478548451374538};
  for (double a : kAcross)
    for (std::size_t k = 0; k < kAlong.size(); ++k)
      points.push_back({{footprint.x + 0.5 * footprint.width * a,
                         footprint.y + 0.5 * footprint.length * kAlong[k], 0.0},
                        share * 0.5 * 0.5 * kWeights[k]});
}

HeldField half_space_field(const Eigen::Vector3d& x, const Eigen::Vector3d& n,
                           const std::vector<LoadPoint>& loads, double G, double nu) {
  HeldField held;
  for (const LoadPoint& p : loads) {
    if ((x - p.at).norm() < 1e-9) continue;  // (a node on a load point: the field is singular)
    const soils::HalfSpacePoint field = soils::boussinesq_point_load(x - p.at, p.share, G, nu);
    held.displacement += field.displacement;
    held.spring_force -= field.stress * n;
  }
  return held;
}

bool static_far_field_applies(const FemSettings& settings) {
  const BoundaryRequest& b = settings.boundary;
  return (b.kind == BoundaryKind::kViscousSpring || b.kind == BoundaryKind::kDashpot) &&
         b.spring_model == SpringModel::kHalfSpace && settings.layers.empty();
}

StaticFarField::StaticFarField(const TetMesh& mesh, const FemSettings& settings,
                               const std::vector<Footprint>& footprints,
                               const std::vector<BoundaryNode>& boundary)
    : loads_(3 * static_cast<Eigen::Index>(boundary.size()),
             static_cast<Eigen::Index>(footprints.size())) {
  nodes_.reserve(boundary.size());
  for (const BoundaryNode& b : boundary) nodes_.push_back(b.node);
  Eigen::Vector3d centre = Eigen::Vector3d::Zero();
  for (const Footprint& f : footprints) centre += Eigen::Vector3d(f.x, f.y, 0.0);
  if (!footprints.empty()) centre /= static_cast<double>(footprints.size());
  for (const BoundaryNode& b : boundary) mean_distance_ += (mesh.node(b.node) - centre).norm();
  if (!boundary.empty()) mean_distance_ /= static_cast<double>(boundary.size());
  const soils::SoilProperties& p = settings.properties_at(0.0);  // (homogeneous)
  for (std::size_t j = 0; j < footprints.size(); ++j) {
    std::vector<LoadPoint> points;
    add_load_points(footprints[j], 1.0, points);
    for (std::size_t k = 0; k < boundary.size(); ++k) {
      const BoundaryNode& b = boundary[k];
      const HeldField held =
          half_space_field(mesh.node(b.node), b.normal, points, p.shear_modulus(), p.nu);
      loads_.block<3, 1>(3 * static_cast<Eigen::Index>(k), static_cast<Eigen::Index>(j)) =
          b.spring * held.displacement - b.area * held.spring_force;
    }
  }
}

void StaticFarField::product(const double* F, Eigen::VectorXd& g, unsigned threads) const {
  const Eigen::Index rows = loads_.rows(), footprints = loads_.cols();
  g.resize(rows);
  // (G's columns read once, a block of rows at a time, so that the block of g stays in the
  // first-level cache: 512 rows, 4 kB)
  constexpr Eigen::Index kRows = 512;
  const Eigen::Index blocks = (rows + kRows - 1) / kRows;
#pragma omp parallel for num_threads(threads < 1 ? 1 : threads) schedule(static)
  for (Eigen::Index b = 0; b < blocks; ++b) {
    const Eigen::Index begin = b * kRows, end = std::min(rows, begin + kRows);
    double* out = g.data();
    std::fill(out + begin, out + end, 0.0);
    for (Eigen::Index j = 0; j < footprints; ++j) {
      const double* column = loads_.col(j).data();
      const double Fj = F[j];
      for (Eigen::Index r = begin; r < end; ++r) out[r] += column[r] * Fj;
    }
  }
}

void StaticFarField::add(const double* F, Eigen::VectorXd& f, unsigned threads) const {
  product(F, g_, threads);
  for (std::size_t k = 0; k < nodes_.size(); ++k)
    f.segment<3>(3 * static_cast<Eigen::Index>(nodes_[k])) +=
        g_.segment<3>(3 * static_cast<Eigen::Index>(k));
}

void StaticFarField::follow(const double* before, const double* now, Eigen::VectorXd& f,
                            Eigen::VectorXd& jump, unsigned threads) {
  const auto footprints = static_cast<std::size_t>(loads_.cols());
  if (held_.size() != footprints || !std::equal(held_.begin(), held_.end(), before)) {
    product(before, held_g_, threads);
    held_.assign(before, before + footprints);
  }
  product(now, g_, threads);
  for (std::size_t k = 0; k < nodes_.size(); ++k) {
    const auto row = 3 * static_cast<Eigen::Index>(k),
               dof = 3 * static_cast<Eigen::Index>(nodes_[k]);
    f.segment<3>(dof) = g_.segment<3>(row);
    jump.segment<3>(dof) = g_.segment<3>(row) - held_g_.segment<3>(row);
  }
  std::swap(g_, held_g_);
  held_.assign(now, now + footprints);
}

void StaticFarField::set_column(std::size_t j, double F_j, Eigen::VectorXd& f) const {
  const auto column = loads_.col(static_cast<Eigen::Index>(j));
  for (std::size_t k = 0; k < nodes_.size(); ++k)
    f.segment<3>(3 * static_cast<Eigen::Index>(nodes_[k])) =
        F_j * column.segment<3>(3 * static_cast<Eigen::Index>(k));
}

void StaticFarField::add_columns(std::complex<double> factor, Eigen::MatrixXcd& rhs) const {
  for (std::size_t k = 0; k < nodes_.size(); ++k)
    rhs.middleRows<3>(3 * static_cast<Eigen::Index>(nodes_[k])) +=
        factor *
        loads_.middleRows<3>(3 * static_cast<Eigen::Index>(k)).cast<std::complex<double>>();
}

}  // namespace rumble::fem
