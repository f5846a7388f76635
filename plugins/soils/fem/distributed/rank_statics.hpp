// The static state solved on the ranks (issue #33; docs/fem-soil.md §8): what the soil on the
// ranks (distributed_soil.hpp) asks of either solver, PETSc's CG with GAMG on the assembled
// operator (distributed_statics.hpp, statics.solver gamg or above the factor limit) or with the
// geometric multigrid of mesh.refine's nested meshes (geometric_rank_statics.hpp, statics.solver
// geometric). Every call is collective.
#pragma once

#include <Eigen/Core>
#include <functional>
#include <string>

namespace rumble::fem {

class RankStatics {
 public:
  virtual ~RankStatics() = default;
  /// u on every node of the part, owned and ghost: (K + S) u = f on the free DOFs, 0 on fixed
  /// ones; f: each owned node's whole load [N] (the ghosts' are not read). Throws on every rank
  /// when CG does not converge.
  virtual Eigen::VectorXd solve(const Eigen::VectorXd& f) = 0;
  /// The method's name in the log ("CG with GAMG", ...).
  virtual const char* method() const = 0;
  /// CG's stop: the true residual against this share of the load.
  virtual double tolerance() const = 0;
  /// Called between CG's iterations (rank 0's asks the host: Ctrl-C); when it throws on any
  /// rank, every rank leaves CG at that iteration and solve() throws there (statics/
  /// petsc_cg.hpp). Unset: none.
  virtual void set_stop_check(std::function<void()> check) = 0;
  int last_iterations() const { return iterations_; }
  /// The multigrid's levels.
  int levels() const { return levels_; }
  /// What the log adds after the levels' count ("" for nothing more).
  virtual std::string levels_detail() const { return ""; }
  /// Seconds the solver took to build.
  double setup_seconds() const { return setup_seconds_; }

 protected:
  int iterations_ = 0, levels_ = 0;
  double setup_seconds_ = 0.0;
};

}  // namespace rumble::fem
