// What `rumble mesh --ranks N` and a run on ranks estimate before any split
// (plugins/soils/fem/distributed/rank_plan.hpp; docs/fem-soil.md, "Planning the ranks"), and the
// names of a field snapshot's pieces (output/pvtu_writer.hpp; rumble/abi.h, write_fields). The
// estimate against actual splits is tests/mpi's (fem_rank_plan_check, fem_same_on_N_ranks).
#include "distributed/rank_plan.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>
#include <string>

#include "memory_model.hpp"
#include "output/pvtu_writer.hpp"

namespace {

using rumble::fem::NodeShare;
using rumble::fem::plan_ranks;
using rumble::fem::RankPlan;

TEST(FieldPieces, ArePathsBesideTheIndexNumberedByRank) {
  EXPECT_EQ(rumble::fem::piece_path("out/fields/soil_000003.pvtu", 0),
            "out/fields/soil_000003_0.vtu");
  EXPECT_EQ(rumble::fem::piece_path("soil_000003.pvtu", 12), "soil_000003_12.vtu");
  EXPECT_THROW(rumble::fem::piece_path("soil_000003.vtu", 0), std::invalid_argument);
  EXPECT_THROW(rumble::fem::piece_path(".pvtu", 0), std::invalid_argument);
}

TEST(RankPlan, OneRankIsOneProcessWithoutHalo) {
  const RankPlan p = plan_ranks(1e5, 1);
  EXPECT_EQ(p.ghosts, 0.0);
  EXPECT_EQ(p.largest_nodes, 1e5);
  EXPECT_DOUBLE_EQ(p.root_bytes, rumble::fem::memory::run_peak_bytes(3e5));
}

TEST(RankPlan, HaloGrowsAsTheSurfacesOfRecursiveBisection) {
  const double n = 1e6;  // (n^(2/3) = 1e4)
  const RankPlan two = plan_ranks(n, 2), eight = plan_ranks(n, 8);
  EXPECT_NEAR(two.ghosts, rumble::fem::kHaloSurface * 1e4, 1e-6);
  // 8 parts: the cuts of 1, 2 and 4 parts of n, n/2, n/4 nodes: 1 + 2^(1/3) + 2^(2/3) planes.
  EXPECT_NEAR(eight.ghosts / two.ghosts, 1.0 + std::cbrt(2.0) + std::cbrt(4.0), 1e-12);
  EXPECT_DOUBLE_EQ(two.halo_bytes, 48.0 * two.ghosts);
  EXPECT_DOUBLE_EQ(eight.largest_nodes, (n + eight.ghosts) / 8.0);
  EXPECT_GT(eight.root_bytes, eight.rank_bytes);  // (rank 0 holds the whole mesh today)
}

// Rank 0 meshes and splits the whole mesh before any rank builds its share: at 1.2e6 DOFs that
// is its peak (memory_model.hpp, root_split_bytes). With mesh.refine on the ranks it meshes,
// splits and keeps the coarse mesh, 8^-refine of it: then its peak is its share's, as every
// rank's, and the coarse mesh's 40 B per DOF (docs/fem-soil.md §8).
TEST(RankPlan, RefinedOnTheRanksRankZeroHoldsTheCoarseMesh) {
  namespace memory = rumble::fem::memory;
  const double n = 4e5;  // (1.2e6 DOFs: above the factor limit, the statics on the ranks)
  // (The aggregation multigrid, auto's without mesh.refine: nothing beyond a share's 800 B per
  // DOF; GAMG's 18 B per nonzero of a share would outweigh the split on 2 ranks.)
  const RankPlan whole = plan_ranks(n, 2, {.aggregation = true}),
                 refined = plan_ranks(n, 2, {.refine = 1, .aggregation = true});
  EXPECT_DOUBLE_EQ(whole.root_bytes, memory::root_split_bytes(3.0 * n, 2));
  EXPECT_NEAR(refined.root_bytes - refined.rank_bytes, memory::kMeshBytesPerDof * 3.0 * n / 8.0,
              1e-3);
  EXPECT_GT(refined.root_bytes, memory::root_split_bytes(3.0 * n / 8.0, 2));
  EXPECT_EQ(whole.rank_bytes, refined.rank_bytes);
  EXPECT_NE(rumble::fem::describe(refined, "the mesh")
                .find("on rank 0 (it meshes, splits and holds the coarse mesh"),
            std::string::npos);
  EXPECT_NE(rumble::fem::describe(whole, "the mesh")
                .find("on rank 0 (it meshes, splits and holds the whole mesh)"),
            std::string::npos);
}

// statics.solver geometric on the ranks: its statics at kGeometricRankBytesPerNonzero per
// nonzero of a share, GAMG's at kGamgBytesPerNonzero (memory_model.hpp; docs/fem-soil.md §8, "The
// geometric multigrid on the ranks"), on the ranks at any size when named (below the factor limit
// too, where rank 0 would factor); auto's below the limit is rank 0's factor.
TEST(RankPlan, TheGeometricMultigridOnTheRanksCostsItsOwnStatics) {
  namespace memory = rumble::fem::memory;
  const double n = 4e5;  // (1.2e6 DOFs: above the factor limit)
  const RankPlan gamg = plan_ranks(n, 2, {.named = true, .refine = 1}),
                 geometric = plan_ranks(n, 2, {.refine = 1, .geometric = true});
  const double nonzeros = memory::kNonzerosPerDof * 3.0 * gamg.largest_nodes;
  EXPECT_NEAR(gamg.rank_bytes - geometric.rank_bytes,
              (memory::kGamgBytesPerNonzero - memory::kGeometricRankBytesPerNonzero) * nonzeros,
              1e-3);
  EXPECT_NEAR(gamg.root_bytes - geometric.root_bytes, gamg.rank_bytes - geometric.rank_bytes, 1e-3);
  const double small = 2e4;  // (6e4 DOFs: below the factor limit)
  const RankPlan factored = plan_ranks(small, 2, {.refine = 1}),
                 on_ranks = plan_ranks(small, 2, {.named = true, .refine = 1, .geometric = true}),
                 auto_geometric = plan_ranks(small, 2, {.refine = 1, .geometric = true});
  EXPECT_EQ(auto_geometric.rank_bytes, factored.rank_bytes);
  EXPECT_EQ(auto_geometric.root_bytes, factored.root_bytes);
  EXPECT_NEAR(on_ranks.rank_bytes - factored.rank_bytes,
              memory::kGeometricRankBytesPerNonzero * memory::kNonzerosPerDof * 3.0 *
                  on_ranks.largest_nodes,
              1e-3);
}

// integrator.scheme implicit on the ranks: each rank holds its share of the steps' factor (MUMPS,
// memory_model.hpp's rank_factor_bytes, fitted on 2 ranks: docs/fem-soil.md §8) once the statics
// are done, rank 0 beside the whole mesh; fewer each on more ranks.
TEST(RankPlan, TheImplicitSchemeCostsEachRankItsShareOfTheFactor) {
  namespace memory = rumble::fem::memory;
  const double n = 2e4;  // (6e4 DOFs: below the factor limit, rank 0 factors the statics)
  const RankPlan explicit_two = plan_ranks(n, 2),
                 implicit_two = plan_ranks(n, 2, {.implicit = true});
  const double share = memory::rank_factor_bytes(3.0 * n, 2);
  EXPECT_NEAR(implicit_two.rank_bytes - explicit_two.rank_bytes, share, 1e-3);
  EXPECT_GT(share, 100e6);  // (17.5 B per nonzero of half of 4.7 n^1.45 nonzeros: 0.35 GB)
  EXPECT_LT(share, 1e9);
  // Rank 0's statics factor (one process's, whole) is larger than its share of the steps'.
  EXPECT_EQ(implicit_two.root_bytes, explicit_two.root_bytes);
  const RankPlan implicit_four = plan_ranks(n, 4, {.implicit = true});
  EXPECT_LT(implicit_four.rank_bytes - plan_ranks(n, 4).rank_bytes, 0.55 * share);
}

TEST(RankPlan, AMachineTooSmallForItsRanksIsRefusedWithTheNumbers) {
  const RankPlan p = plan_ranks(1e6, 4);
  const double root_machine = p.root_bytes + p.rank_bytes;  // rank 0 and one more
  EXPECT_NO_THROW(rumble::fem::check_node_memory(
      p, {{2, true, 1.01 * root_machine}, {2, false, 2.01 * p.rank_bytes}}, 50.0));
  try {
    rumble::fem::check_node_memory(
        p, {{2, true, 1.01 * root_machine}, {2, false, 1.99 * p.rank_bytes}}, 50.0);
    FAIL() << "a machine of too little memory for its 2 ranks was accepted";
  } catch (const std::invalid_argument& e) {
    const std::string said = e.what();
    EXPECT_NE(said.find("fem: params/mesh: on 4 ranks a mesh of about 1e+06 nodes (mesh.f_max "
                        "50 Hz)"),
              std::string::npos)
        << said;
    EXPECT_NE(said.find("for the 2 rank(s) on one machine"), std::string::npos) << said;
    EXPECT_NE(said.find("start fewer ranks on each machine"), std::string::npos) << said;
  }
  EXPECT_THROW(rumble::fem::check_node_memory(p, {{2, true, 0.99 * root_machine}}, 50.0),
               std::invalid_argument);
}

}  // namespace
