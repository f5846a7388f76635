// The implicit coupler's accelerators (plugins/couplers/implicit/acceleration.hpp) on linear
// fixed-point problems x = G(x) = A x + b with known solutions: constant relaxation is the
// formula, Aitken is exact at its second update in one dimension (a secant step), IQN-ILS
// converges in at most n + 1 evaluations on n unknowns even where plain iteration diverges,
// reuses columns across steps (one update then suffices), forgets them when the step length
// changes or nothing is to be reused, and its QR filter leaves out a nearly dependent column.
#include "acceleration.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

namespace {

using rumble_implicit::AccelerationSettings;
using rumble_implicit::Accelerator;
using rumble_implicit::Method;

using Vector = std::vector<double>;

/// G(x) = A x + b, A dense row-major n x n.
struct Linear {
  std::size_t n;
  Vector a, b;
  Vector operator()(const Vector& x) const {
    Vector y(b);
    for (std::size_t i = 0; i < n; ++i)
      for (std::size_t j = 0; j < n; ++j) y[i] += a[i * n + j] * x[j];
    return y;
  }
  double residual(const Vector& x) const {
    const Vector y = (*this)(x);
    double s = 0.0;
    for (std::size_t i = 0; i < n; ++i) s += (y[i] - x[i]) * (y[i] - x[i]);
    return std::sqrt(s);
  }
};

/// A non-symmetric 5 x 5 map whose plain iteration diverges (eigenvalues up to -1.6 and 1.3),
/// as a soft massless soil's loop does (docs/decisions/0004).
Linear divergent_map() {
  Linear g{5, Vector(25, 0.0), {1.0, -2.0, 0.5, 3.0, -1.0}};
  const double diag[5] = {-1.6, -0.9, 0.4, 1.3, -0.2};
  for (std::size_t i = 0; i < 5; ++i) {
    g.a[i * 5 + i] = diag[i];
    if (i + 1 < 5) g.a[i * 5 + i + 1] = 0.3;  // upper band: not symmetric
  }
  return g;
}

/// Iterates one step from x0 until |G(x) - x| <= tol |G(x0) - x0|; returns the evaluations.
int solve_step(Accelerator& acc, const Linear& g, Vector& x, double tol, int max = 100) {
  const double r0 = g.residual(x);
  Vector next;
  for (int k = 1; k <= max; ++k) {
    const Vector y = g(x);
    if (g.residual(x) <= tol * r0) {
      acc.end_step();
      return k;
    }
    acc.next(x, y, next);
    x = next;
  }
  acc.end_step();
  return max + 1;
}

TEST(Acceleration, ConstantRelaxationIsTheFormula) {
  AccelerationSettings s;
  s.method = Method::kConstant;
  s.omega = 0.25;
  Accelerator acc(s, 2);
  acc.begin_step(1e-3);
  Vector next;
  acc.next({1.0, 2.0}, {3.0, -2.0}, next);  // x + 0.25 (x~ - x)
  EXPECT_DOUBLE_EQ(next[0], 1.5);
  EXPECT_DOUBLE_EQ(next[1], 1.0);
  EXPECT_DOUBLE_EQ(acc.omega(), 0.25);
}

TEST(Acceleration, AitkenIsExactAtItsSecondUpdateInOneDimension) {
  AccelerationSettings s;
  s.method = Method::kAitken;
  const Linear g{1, {-3.0}, {8.0}};  // x* = 2; plain iteration diverges (|a| > 1)
  Accelerator acc(s, 1);
  acc.begin_step(1e-3);
  Vector x{0.0}, next;
  acc.next(x, g(x), next);  // w = 0.5
  EXPECT_DOUBLE_EQ(acc.omega(), 0.5);
  x = next;
  acc.next(x, g(x), next);  // w = 1 / (1 - a)
  EXPECT_NEAR(acc.omega(), 0.25, 1e-15);
  EXPECT_NEAR(next[0], 2.0, 1e-14);
}

TEST(Acceleration, AitkenStartsAStepFromTheLastFactorBoundedByTheInitial) {
  AccelerationSettings s;
  s.method = Method::kAitken;
  s.omega = 0.5;
  const Linear g{1, {-0.2}, {1.2}};  // optimal w = 1 / 1.2
  Accelerator acc(s, 1);
  acc.begin_step(1e-3);
  Vector x{0.0};
  solve_step(acc, g, x, 1e-12);
  EXPECT_GT(acc.omega(), 0.5);
  acc.begin_step(1e-3);
  Vector next;
  acc.next(x, g(x), next);
  EXPECT_DOUBLE_EQ(acc.omega(), 0.5);  // min(w_init, |w_prev|)
}

TEST(Acceleration, IqnIlsSolvesALinearMapInAtMostNPlusOneEvaluations) {
  const Linear g = divergent_map();
  AccelerationSettings s;
  s.filter_epsilon = 1e-12;  // keep every column: the linear theory needs all of them
  Accelerator acc(s, g.n);
  acc.begin_step(1e-3);
  Vector x(g.n, 0.0);
  const int evaluations = solve_step(acc, g, x, 1e-10);
  EXPECT_LE(evaluations, static_cast<int>(g.n) + 2) << "x = " << x[0];
  // Plain relaxation with the same factor does not converge at all.
  AccelerationSettings c;
  c.method = Method::kConstant;
  Accelerator constant(c, g.n);
  constant.begin_step(1e-3);
  Vector xc(g.n, 0.0);
  EXPECT_GT(solve_step(constant, g, xc, 1e-10, 200), 200);
}

TEST(Acceleration, IqnIlsReusesColumnsOfPastSteps) {
  Linear g = divergent_map();
  AccelerationSettings s;
  s.filter_epsilon = 1e-12;
  Accelerator acc(s, g.n);
  acc.begin_step(1e-3);
  Vector x(g.n, 0.0);
  solve_step(acc, g, x, 1e-10);
  EXPECT_GE(acc.columns(), g.n);
  // The next step: another right-hand side, the same Jacobian. The columns span the space, so
  // the first update is the solution.
  g.b = {0.5, 1.0, -2.0, 1.0, 0.0};
  acc.begin_step(1e-3);
  EXPECT_EQ(solve_step(acc, g, x, 1e-8), 2);
  // Without reuse it starts from nothing again.
  AccelerationSettings none = s;
  none.reused_steps = 0;
  Accelerator fresh(none, g.n);
  fresh.begin_step(1e-3);
  Vector y(g.n, 0.0);
  solve_step(fresh, g, y, 1e-10);
  EXPECT_EQ(fresh.columns(), 0u);
}

TEST(Acceleration, IqnIlsForgetsColumnsWhenTheStepLengthChanges) {
  const Linear g = divergent_map();
  AccelerationSettings s;
  Accelerator acc(s, g.n);
  acc.begin_step(1e-3);
  Vector x(g.n, 0.0), next;
  solve_step(acc, g, x, 1e-10);
  ASSERT_GT(acc.columns(), 0u);
  acc.begin_step(0.5e-3);  // a refused step taken as halves: G is another map
  EXPECT_GT(acc.columns(),
            0u);  // nothing dropped before an update is made (a refusal leaves no trace)
  acc.next(x, g(x), next);
  EXPECT_EQ(acc.columns(), 0u);
  EXPECT_EQ(acc.columns_used(), 0u);
  EXPECT_DOUBLE_EQ(acc.omega(), s.omega);  // relaxed
}

TEST(Acceleration, IqnIlsFilterLeavesOutANearlyDependentColumn) {
  // Residual differences (1, 0, 0), then (1, 1e-4, 0): nearly parallel.
  for (const double epsilon : {1e-2, 1e-6}) {
    AccelerationSettings s;
    s.filter_epsilon = epsilon;
    Accelerator acc(s, 3);
    acc.begin_step(1e-3);
    Vector next;
    acc.next({0, 0, 0}, {1, 0, 0}, next);     // r0 = (1, 0, 0)
    acc.next({0, 0, 0}, {2, 0, 0}, next);     // r1 = (2, 0, 0): column (1, 0, 0)
    acc.next({0, 0, 0}, {3, 1e-4, 0}, next);  // r2: column (1, 1e-4, 0)
    EXPECT_EQ(acc.columns(), 2u);
    EXPECT_EQ(acc.columns_used(), epsilon > 1e-4 ? 1u : 2u) << "epsilon " << epsilon;
  }
}

TEST(Acceleration, ARetriedStepDropsItsOwnColumns) {
  const Linear g = divergent_map();
  AccelerationSettings s;
  s.reused_steps = 0;
  Accelerator acc(s, g.n);
  acc.begin_step(1e-3);
  Vector x(g.n, 0.0), next;
  for (int k = 0; k < 3; ++k) {
    acc.next(x, g(x), next);
    x = next;
  }
  EXPECT_EQ(acc.columns(), 2u);
  acc.begin_step(0.5e-3);  // refused in the middle: taken again
  EXPECT_EQ(acc.columns(), 0u);
}

TEST(Acceleration, UnknownMethodIsNamed) {
  EXPECT_THROW(rumble_implicit::method_from_name("anderson"), std::invalid_argument);
  EXPECT_EQ(rumble_implicit::method_from_name("aitken"), Method::kAitken);
}

}  // namespace
