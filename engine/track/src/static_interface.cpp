#include "track/static_interface.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

#include "core/errors.hpp"
#include "core/interrupt.hpp"

namespace rumble {
namespace {

// Finite-difference step of the track's Jacobian [m]: settlements are 1e-5..1e-2 m and the track
// is linear in them but for the Hertz contacts (approach ~1e-4 m), so 1e-6 m is in the linear
// range, and gives force changes (2 k_ballast 1e-6 m: 80 N for the paper's 4e7 N/m) far above
// the Newton noise of the track's own solve (1e-10 of the wheel load, ~1e-5 N).
constexpr double kJacobianStep = 1e-6;
// Chord-Newton iterations on the surrogate problem (track evaluations only); it converges
// linearly at the rate of the track's non-linearity over one outer step: a few iterations.
constexpr int kMaxSurrogateIterations = 30;
// A difference column whose part outside the others is below this fraction of its norm is
// dropped from the surrogate's least squares (as the QR2 filter of IQN-ILS).
constexpr double kRankThreshold = 1e-10;

Eigen::Map<const Eigen::VectorXd> view(const std::vector<double>& v) {
  return {v.data(), static_cast<Eigen::Index>(v.size())};
}

double largest_magnitude(const Eigen::VectorXd& v) {
  return v.size() == 0 ? 0.0 : v.cwiseAbs().maxCoeff();
}

/// S~ of the header: affine, S~ x = L x + offset, rebuilt after every soil solve.
class SoilSurrogate {
 public:
  explicit SoilSurrogate(const Eigen::MatrixXd& shape) : shape_(shape) {}

  /// A soil solve: u = S(f) [m] under f [N]. The first one fits the prior. Throws RunError when
  /// the soil settles against its load.
  void add(const Eigen::VectorXd& f, const Eigen::VectorXd& u) {
    if (forces_.empty()) fit_prior(f, u);
    forces_.push_back(f);
    settlements_.push_back(u);
    rebuild();
  }
  const Eigen::MatrixXd& linear() const { return linear_; }
  Eigen::VectorXd operator()(const Eigen::VectorXd& f) const { return linear_ * f + offset_; }

 private:
  /// prior_ = a I + b shape_, a [m/N] and b [m^2/N] >= 0, from the first solve by least squares: a
  /// local (Winkler-like) flexibility and a half-space one, so that either kind of soil is met.
  void fit_prior(const Eigen::VectorXd& f, const Eigen::VectorXd& u) {
    const Eigen::VectorXd g = shape_ * f;
    Eigen::Matrix2d normal;
    normal << f.dot(f), f.dot(g), f.dot(g), g.dot(g);
    Eigen::Vector2d ab = normal.ldlt().solve(Eigen::Vector2d(f.dot(u), g.dot(u)));
    if (!(ab.minCoeff() >= 0.0) || !ab.allFinite()) {  // the better of the two alone
      const double a = f.dot(u) / f.dot(f), b = g.dot(u) / g.dot(g);
      ab = (u - a * f).squaredNorm() <= (u - b * g).squaredNorm() ? Eigen::Vector2d(a, 0.0)
                                                                  : Eigen::Vector2d(0.0, b);
    }
    if (!(ab.maxCoeff() > 0.0) || !ab.allFinite()) {
      std::ostringstream m;
      m << "track/soil statics: the soil settles against its load (mean flexibility "
        << f.dot(u) / f.dot(f)
        << " m/N under the track's footprint forces): a soil must move with the load that "
           "presses it; check the sign of the soil plugin's initialize and its stiffness "
           "parameters";
      throw RunError(m.str());
    }
    prior_ = ab[1] * shape_;
    prior_.diagonal().array() += ab[0];
  }

  void rebuild() {
    const Eigen::Index n = forces_.back().size();
    const auto k = static_cast<Eigen::Index>(forces_.size()) - 1;
    const Eigen::VectorXd& f_k = forces_.back();
    const Eigen::VectorXd& u_k = settlements_.back();
    linear_ = prior_;
    if (k > 0) {
      // Differences from the latest solve, each scaled to a unit force difference so that the
      // rank decision is about directions, not sizes (the late differences are 1e-9 of the first).
      Eigen::MatrixXd dF(n, k), dU(n, k);
      for (Eigen::Index j = 0; j < k; ++j) {
        const auto i = static_cast<std::size_t>(j);
        dF.col(j) = forces_[i] - f_k;
        dU.col(j) = settlements_[i] - u_k;
        const double norm = dF.col(j).norm();
        if (norm > 0.0) {
          dF.col(j) /= norm;
          dU.col(j) /= norm;
        }
      }
      Eigen::CompleteOrthogonalDecomposition<Eigen::MatrixXd> cod;
      cod.setThreshold(kRankThreshold);
      cod.compute(dF);
      linear_ += (dU - prior_ * dF) * cod.pseudoInverse();
    }
    offset_ = u_k - linear_ * f_k;
  }

  Eigen::MatrixXd shape_;                              // 1/m
  Eigen::MatrixXd prior_;                              // m/N
  std::vector<Eigen::VectorXd> forces_, settlements_;  // N, m: every soil solve so far
  Eigen::MatrixXd linear_;                             // m/N
  Eigen::VectorXd offset_;                             // m
};

void require_finite(const Eigen::VectorXd& v, const char* what) {
  if (!v.allFinite()) {
    throw RunError(std::string("track/soil statics: the ") + what + " returned a non-finite value");
  }
}

}  // namespace

InterfaceStatics solve_interface_statics(const InterfaceMap& track, const InterfaceMap& soil,
                                         const Eigen::MatrixXd& shape, std::vector<double>& u,
                                         std::vector<double>& force,
                                         const InterfaceTolerances& tol) {
  InterfaceStatics stats;
  const std::size_t n = u.size();
  const auto ni = static_cast<Eigen::Index>(n);
  std::vector<double> settled(n);
  const auto evaluate_track = [&](const Eigen::VectorXd& at) {
    // Ctrl-C and SIGTERM stop the statics here: its Jacobian takes n track solves, minutes at
    // thousands of sleepers (issue #30 item 2).
    if (interrupt_requested()) throw Interrupted("interrupted while the static state was solved");
    std::copy(at.begin(), at.end(), u.begin());
    track(u, force);
    ++stats.track_evaluations;
    const Eigen::VectorXd f = view(force);
    require_finite(f, "track");
    return f;
  };

  // The track's Jacobian d force / d u [N/m] at `at`, by forward differences from f_at =
  // track(at) (the track's state is left at a shifted point).
  const auto track_jacobian = [&](const Eigen::VectorXd& at, const Eigen::VectorXd& f_at) {
    Eigen::MatrixXd jacobian(ni, ni);
    for (Eigen::Index j = 0; j < ni; ++j) {
      Eigen::VectorXd shifted = at;
      shifted[j] += kJacobianStep;
      jacobian.col(j) = (evaluate_track(shifted) - f_at) / kJacobianStep;
    }
    return jacobian;
  };

  Eigen::VectorXd x = Eigen::VectorXd::Zero(ni);    // m: the current settlements
  Eigen::VectorXd f = evaluate_track(x);            // N: track(x)
  Eigen::MatrixXd jacobian = track_jacobian(x, f);  // kept while the chord steps shrink
  f = evaluate_track(x);
  const Eigen::MatrixXd identity = Eigen::MatrixXd::Identity(ni, ni);

  SoilSurrogate surrogate(shape);
  for (stats.soil_solves = 1; stats.soil_solves <= tol.max_soil_solves; ++stats.soil_solves) {
    soil(force, settled);
    const Eigen::VectorXd s = view(settled);
    require_finite(s, "soil");
    const double change = largest_magnitude(s - x), scale = largest_magnitude(s);
    if (change <= tol.relative * scale + tol.absolute) {
      evaluate_track(s);  // the track's state and force at the soil's settlement
      return stats;
    }
    surrogate.add(f, s);
    // The surrogate coupled problem x = S~(track(x)) by chord Newton from the soil's settlement;
    // the Jacobian is refreshed where a step fails to halve (a strongly non-linear track).
    x = s;
    f = evaluate_track(x);
    Eigen::PartialPivLU<Eigen::MatrixXd> newton(identity - surrogate.linear() * jacobian);
    const double inner_tolerance = 0.1 * tol.relative * scale + tol.absolute;
    double last = std::numeric_limits<double>::infinity();  // m: the last step's size
    for (int it = 0; it < kMaxSurrogateIterations; ++it) {
      Eigen::VectorXd step = newton.solve(x - surrogate(f));
      if (largest_magnitude(step) > 0.5 * last) {
        jacobian = track_jacobian(x, f);
        newton.compute(identity - surrogate.linear() * jacobian);
        step = newton.solve(x - surrogate(f));
      }
      last = largest_magnitude(step);
      x -= step;
      f = evaluate_track(x);
      if (last <= inner_tolerance) break;
    }
  }
  std::ostringstream m;
  m << "track/soil statics: track and soil did not reach a consistent static state in "
    << tol.max_soil_solves
    << " soil solves; this iteration needs a linear soil statics (the same footprint forces "
       "always give the same settlements, proportional to them) and wheels that stay on the "
       "rail at rest: check the soil plugin's initialize and the vehicles' static loads";
  throw RunError(m.str());
}

}  // namespace rumble
