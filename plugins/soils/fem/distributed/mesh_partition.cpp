#include "distributed/mesh_partition.hpp"

#include <petscdmplex.h>
#include <petscsf.h>
#include <scotch.h>

#include <algorithm>
#include <array>
#include <cstdlib>
#include <map>
#include <optional>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <utility>

#include "statics/node_aggregates.hpp"
#include "statics/petsc_session.hpp"

namespace rumble::fem {

// FaceGraph's rows go to PETSc as they are (Debian's PETSc: 32-bit indices).
static_assert(std::is_same_v<PetscInt, std::int32_t>, "PetscInt is not std::int32_t");

namespace {

// What travels with each point of the DMPlex from rank 0 to the rank that receives it: its
// number in rank 0's DMPlex and, for a tetrahedron, its nodes in rank 0's mesh, its layer and
// its faces on the surfaces (face_codes) with its ground face's index among rank 0's ground faces
// (-1: none; a tetrahedron has at most one face on the plane z = 0), and, when the ranks refine
// their parts (mesh/numbered_refinement.hpp), its 6 edges' and 4 faces' numbers in rank 0's mesh.
// The DMPlex of rank 0's mesh numbers its tetrahedra first (0 .. T - 1), then its nodes (T + g).
constexpr int kPointInts = 8;  // point, 4 nodes, layer, surface faces, ground face
constexpr int kNamedPointInts = kPointInts + 10;  // and the edges' and faces' numbers

// A tetrahedron's faces on the ground or the truncation surface in one int, a byte per face
// (at most 4): the surface (1 ground, 2 truncation) in bits 6-7 and the face's three nodes as
// positions 0-3 in the tetrahedron, in the face's own order (its normal's), in bits 4-5, 2-3
// and 0-1; 0: no more faces.
constexpr unsigned kGround = 1, kTruncation = 2;

// Per tetrahedron: its packed surface faces, and the index of its ground face (-1: none).
std::pair<std::vector<unsigned>, std::vector<int>> face_codes(const TetMesh& whole) {
  std::vector<char> on_surface(static_cast<std::size_t>(whole.node_count()), 0);
  struct Face {
    unsigned kind;
    Triangle nodes;
    int index;  // in its list
  };
  std::map<std::array<std::int32_t, 3>, Face> faces;
  for (const auto& [kind, list] :
       {std::pair{kGround, &whole.ground}, std::pair{kTruncation, &whole.truncation}})
    for (std::size_t k = 0; k < list->size(); ++k) {
      const Triangle& f = (*list)[k];
      for (std::int32_t v : f) on_surface[v] = 1;
      std::array<std::int32_t, 3> key = f;
      std::sort(key.begin(), key.end());
      faces.emplace(key, Face{kind, f, static_cast<int>(k)});
    }
  std::vector<unsigned> codes(whole.tets.size(), 0);
  std::vector<int> ground(whole.tets.size(), -1);
  for (std::size_t e = 0; e < whole.tets.size(); ++e) {
    const Tetrahedron& t = whole.tets[e];
    int slot = 0;
    for (int opposite = 0; opposite < 4; ++opposite) {
      std::array<std::int32_t, 3> key{};
      for (int a = 0, k = 0; a < 4; ++a)
        if (a != opposite) key[k++] = t[a];
      if (!on_surface[key[0]] || !on_surface[key[1]] || !on_surface[key[2]]) continue;
      std::sort(key.begin(), key.end());
      const auto it = faces.find(key);
      if (it == faces.end()) continue;
      unsigned code = it->second.kind << 6;
      for (int m = 0; m < 3; ++m) {
        const auto at = std::find(t.begin(), t.end(), it->second.nodes[m]) - t.begin();
        code |= static_cast<unsigned>(at) << (4 - 2 * m);
      }
      codes[e] |= code << (8 * slot++);
      if (it->second.kind == kGround) ground[e] = it->second.index;
    }
  }
  return {codes, ground};
}

// The faces face_codes() packed for tetrahedron t (local nodes) added to the part's surfaces,
// its ground face with its index among rank 0's.
void add_faces(unsigned codes, int ground, const Tetrahedron& t, MeshPartition& part) {
  for (; codes != 0; codes >>= 8) {
    const unsigned code = codes & 0xFFu;
    const Triangle f{t[(code >> 4) & 3u], t[(code >> 2) & 3u], t[code & 3u]};
    if ((code >> 6) != kGround) {
      part.mesh.truncation.push_back(f);
      continue;
    }
    part.mesh.ground.push_back(f);
    part.ground_global.push_back(ground);
  }
}

struct PlexPoints {
  int width = kPointInts;  // ints per point
  std::vector<int> ints;   // `width` per point of the distributed DMPlex
};

// Rank 0's mesh as a DMPlex on comm, every point on rank 0 (not interpolated: tetrahedra and
// nodes alone, which is what the partition needs).
DM whole_plex(MPI_Comm comm, const TetMesh* whole) {
  std::vector<PetscInt> cells;
  PetscInt tets = 0, nodes = 0;
  if (whole != nullptr) {
    tets = static_cast<PetscInt>(whole->tets.size());
    nodes = static_cast<PetscInt>(whole->node_count());
    cells.reserve(4 * whole->tets.size());
    for (const Tetrahedron& t : whole->tets) cells.insert(cells.end(), t.begin(), t.end());
  }
  DM dm = nullptr;
  petsc_check(DMPlexCreateFromCellListPetsc(comm, 3, tets, nodes, 4, PETSC_FALSE,
                                            whole ? cells.data() : nullptr, 3,
                                            whole ? whole->nodes.data() : nullptr, &dm),
              "DMPlexCreateFromCellListPetsc");
  return dm;
}

// Each point's data on rank 0, sent along the migration star forest to where DMPlex put it.
PlexPoints migrate_points(PetscSF migration, const TetMesh* whole, const CoarseNames* names,
                          int width, PetscInt points) {
  std::vector<int> root_ints;
  if (whole != nullptr) {
    const auto tets = static_cast<std::int64_t>(whole->tets.size());
    const std::int64_t all = tets + whole->node_count();
    root_ints.assign(static_cast<std::size_t>(width * all), -1);
    for (std::int64_t p = 0; p < all; ++p) root_ints[width * p] = static_cast<int>(p);
    const auto [faces, ground] = face_codes(*whole);
    for (std::int64_t e = 0; e < tets; ++e) {
      int* cell = root_ints.data() + width * e;
      for (int a = 0; a < 4; ++a) cell[1 + a] = whole->tets[e][a];
      cell[5] = whole->layer[e];
      cell[6] = static_cast<int>(faces[e]);
      cell[7] = ground[e];
      if (names == nullptr) continue;
      std::copy_n(names->edge[e].begin(), 6, cell + kPointInts);
      std::copy_n(names->face[e].begin(), 4, cell + kPointInts + 6);
    }
  }
  PlexPoints out{width, std::vector<int>(static_cast<std::size_t>(width * points), -1)};
  MPI_Datatype ints = MPI_DATATYPE_NULL;
  MPI_Type_contiguous(width, MPI_INT, &ints);
  MPI_Type_commit(&ints);
  petsc_check(PetscSFBcastBegin(migration, ints, root_ints.data(), out.ints.data(), MPI_REPLACE),
              "PetscSFBcastBegin");
  petsc_check(PetscSFBcastEnd(migration, ints, root_ints.data(), out.ints.data(), MPI_REPLACE),
              "PetscSFBcastEnd");
  MPI_Type_free(&ints);
  return out;
}

// A node of this rank's part: its DMPlex point, its node in rank 0's mesh, and its owner.
struct PartNode {
  PetscInt point = 0;
  std::int32_t global = 0;
  int owner = 0;
  PetscInt owner_point = 0;  // its point on the owner's DMPlex
  bool shared = false;
};

// The part's nodes from the distributed DMPlex's point star forest (leaves: points owned
// elsewhere; roots with leaves: owned points other ranks copy), shared ones first, each group
// in rank 0's node order.
std::vector<PartNode> part_nodes(DM dist, const PlexPoints& data, std::int64_t tets, int rank) {
  PetscInt start = 0, end = 0;
  petsc_check(DMPlexGetChart(dist, &start, &end), "DMPlexGetChart");
  std::vector<PartNode> nodes;
  std::vector<std::int32_t> node_of(static_cast<std::size_t>(end - start), -1);
  for (PetscInt p = start; p < end; ++p) {
    const int original = data.ints[data.width * (p - start)];
    if (original < tets) continue;  // a tetrahedron
    node_of[p - start] = static_cast<std::int32_t>(nodes.size());
    nodes.push_back({p, static_cast<std::int32_t>(original - tets), rank, p, false});
  }
  PetscSF points = nullptr;
  petsc_check(DMGetPointSF(dist, &points), "DMGetPointSF");
  PetscInt roots = 0, leaves = 0;
  const PetscInt* local = nullptr;
  const PetscSFNode* remote = nullptr;
  petsc_check(PetscSFGetGraph(points, &roots, &leaves, &local, &remote), "PetscSFGetGraph");
  for (PetscInt k = 0; k < leaves; ++k) {
    const PetscInt p = local ? local[k] : k;
    if (const std::int32_t n = node_of[p - start]; n >= 0) {
      nodes[n].owner = static_cast<int>(remote[k].rank);
      nodes[n].owner_point = remote[k].index;
      nodes[n].shared = true;
    }
  }
  const PetscInt* degree = nullptr;  // (collective: every rank asks)
  petsc_check(PetscSFComputeDegreeBegin(points, &degree), "PetscSFComputeDegreeBegin");
  petsc_check(PetscSFComputeDegreeEnd(points, &degree), "PetscSFComputeDegreeEnd");
  for (PartNode& n : nodes)
    if (n.point - start < roots && degree[n.point - start] > 0) n.shared = true;
  std::stable_sort(nodes.begin(), nodes.end(), [](const PartNode& a, const PartNode& b) {
    return a.shared != b.shared ? a.shared : a.global < b.global;
  });
  return nodes;
}

// The halo's leaves: each ghost and its owner's local number of it, which the owner sends along
// the DMPlex's point star forest.
std::vector<ForestLeaf> halo_leaves(DM dist, const std::vector<PartNode>& nodes, int rank) {
  PetscInt start = 0, end = 0;
  petsc_check(DMPlexGetChart(dist, &start, &end), "DMPlexGetChart");
  std::vector<PetscInt> mine(static_cast<std::size_t>(end - start), -1),
      theirs(static_cast<std::size_t>(end - start), -1);
  for (std::size_t k = 0; k < nodes.size(); ++k)
    if (nodes[k].owner == rank) mine[nodes[k].point - start] = static_cast<PetscInt>(k);
  PetscSF points = nullptr;
  petsc_check(DMGetPointSF(dist, &points), "DMGetPointSF");
  petsc_check(PetscSFBcastBegin(points, MPIU_INT, mine.data(), theirs.data(), MPI_REPLACE),
              "PetscSFBcastBegin");
  petsc_check(PetscSFBcastEnd(points, MPIU_INT, mine.data(), theirs.data(), MPI_REPLACE),
              "PetscSFBcastEnd");
  std::vector<ForestLeaf> leaves;
  for (std::size_t k = 0; k < nodes.size(); ++k)
    if (nodes[k].owner != rank)
      leaves.push_back({static_cast<std::int32_t>(k), nodes[k].owner,
                        static_cast<std::int32_t>(theirs[nodes[k].point - start])});
  return leaves;
}

// The part's nodes' coordinates [m], as DMPlexDistribute moved them with their vertices (rank
// 0's own, copied: the same to the bit; sending them again with the points' data cost 24 B per
// point of the mesh on rank 0, tetrahedra included, and as much again for each part).
Eigen::Matrix3Xd part_coordinates(DM dist, const std::vector<PartNode>& nodes) {
  Vec local = nullptr;
  PetscSection section = nullptr;
  petsc_check(DMGetCoordinatesLocal(dist, &local), "DMGetCoordinatesLocal");
  petsc_check(DMGetCoordinateSection(dist, &section), "DMGetCoordinateSection");
  const PetscScalar* values = nullptr;
  petsc_check(VecGetArrayRead(local, &values), "VecGetArrayRead");
  Eigen::Matrix3Xd xyz(3, static_cast<Eigen::Index>(nodes.size()));
  for (std::size_t k = 0; k < nodes.size(); ++k) {
    PetscInt offset = 0;
    petsc_check(PetscSectionGetOffset(section, nodes[k].point, &offset), "PetscSectionGetOffset");
    for (int c = 0; c < 3; ++c) xyz(c, static_cast<Eigen::Index>(k)) = values[offset + c];
  }
  petsc_check(VecRestoreArrayRead(local, &values), "VecRestoreArrayRead");
  return xyz;
}

// The part's tetrahedra in rank 0's order, in local node numbers.
void part_mesh(const PlexPoints& data, std::int64_t tets, MeshPartition& part) {
  std::vector<std::array<int, kNamedPointInts>> cells;
  for (std::size_t p = 0; p < data.ints.size() / data.width; ++p)
    if (data.ints[data.width * p] < tets) {
      std::array<int, kNamedPointInts> c{};
      std::copy_n(data.ints.data() + data.width * p, data.width, c.begin());
      cells.push_back(c);
    }
  std::sort(cells.begin(), cells.end());
  for (const auto& c : cells) {
    Tetrahedron t{};
    for (int a = 0; a < 4; ++a) t[a] = part.local_of(c[1 + a]);
    if (*std::min_element(t.begin(), t.end()) < 0)
      throw std::logic_error("fem: a tetrahedron's node did not come with it to its rank");
    part.mesh.tets.push_back(t);
    part.mesh.layer.push_back(static_cast<std::uint16_t>(c[5]));
    part.tet_global.push_back(c[0]);
    add_faces(static_cast<unsigned>(c[6]), c[7], t, part);
    if (data.width == kPointInts) continue;
    std::array<std::int32_t, 6>& edges = part.names.edge.emplace_back();
    std::array<std::int32_t, 4>& faces = part.names.face.emplace_back();
    std::copy_n(c.begin() + kPointInts, 6, edges.begin());
    std::copy_n(c.begin() + kPointInts + 6, 4, faces.begin());
  }
}

// Scotch splits a graph on threads of its own, and its random generator starts from a seed of
// its own on each process (Debian builds it so): the same mesh was split differently run after
// run (3 ranks: 486-499 nodes on rank 0 in 6 runs). On one thread from a fixed seed every run
// on N ranks splits it alike, so that a run repeats bit for bit.
void seed_scotch() {
  setenv("SCOTCH_PTHREAD_NUMBER", "1", 1);
  SCOTCH_randomSeed(1);
  SCOTCH_randomReset();
}

void refuse_empty_part(MPI_Comm comm, const MeshPartition& part) {
  int size = 1;
  MPI_Comm_size(comm, &size);
  long long mine = static_cast<long long>(part.mesh.tets.size()), fewest = 0;
  MPI_Allreduce(&mine, &fewest, 1, MPI_LONG_LONG, MPI_MIN, comm);
  if (fewest > 0) return;
  throw std::runtime_error(
      "fem: the partition of the mesh's " + std::to_string(part.global_tetrahedra) +
      " tetrahedra over " + std::to_string(size) + " ranks left a rank without any (" +
      partitioner_name() +
      "); run on fewer ranks (mpirun -n with a smaller count) or refine the mesh");
}

}  // namespace

std::int32_t MeshPartition::local_of(std::int32_t g) const {
  const auto at = std::lower_bound(
      by_global.begin(), by_global.end(), g,
      [&](std::int32_t local, std::int32_t value) { return global[local] < value; });
  return at != by_global.end() && global[*at] == g ? *at : -1;
}

const char* partitioner_name() {
  return "PT-Scotch through PETSc's DMPlexDistribute";
}

namespace {

// PT-Scotch's split of whole's tetrahedra into `parts`, on this process alone, seeded (the same
// split run after run): each part's tetrahedra, ascending, part after part, and the parts' sizes.
void scotch_split(const TetMesh& whole, int parts, std::vector<PetscInt>& sizes,
                  std::vector<PetscInt>& points) {
  FaceGraph graph = face_graph(whole);
  PetscPartitioner partitioner = nullptr;
  PetscSection section = nullptr;
  IS order = nullptr;
  petsc_check(PetscPartitionerCreate(PETSC_COMM_SELF, &partitioner), "PetscPartitionerCreate");
  petsc_check(PetscPartitionerSetType(partitioner, PETSCPARTITIONERPTSCOTCH),
              "PetscPartitionerSetType");
  petsc_check(PetscSectionCreate(PETSC_COMM_SELF, &section), "PetscSectionCreate");
  seed_scotch();
  petsc_check(PetscPartitionerPartition(
                  partitioner, parts, static_cast<PetscInt>(whole.tets.size()), graph.start.data(),
                  graph.adjacent.data(), nullptr, nullptr, section, &order),
              "PetscPartitionerPartition");
  sizes.assign(static_cast<std::size_t>(parts), 0);
  for (int p = 0; p < parts; ++p)
    petsc_check(PetscSectionGetDof(section, p, &sizes[p]), "PetscSectionGetDof");
  const PetscInt* tets = nullptr;
  petsc_check(ISGetIndices(order, &tets), "ISGetIndices");
  points.assign(tets, tets + whole.tets.size());
  petsc_check(ISRestoreIndices(order, &tets), "ISRestoreIndices");
  ISDestroy(&order);
  PetscSectionDestroy(&section);
  PetscPartitionerDestroy(&partitioner);
}

// Rank 0's split of its tetrahedra for `ranks` ranks, as PetscPartitionerShellSetPartition
// takes it (the other ranks: none of theirs).
struct Split {
  std::vector<PetscInt> sizes, points;
};

Split split_on_rank_zero(MPI_Comm comm, const TetMesh* whole) {
  int ranks = 1;
  MPI_Comm_size(comm, &ranks);
  Split split{.sizes = std::vector<PetscInt>(static_cast<std::size_t>(ranks), 0), .points = {}};
  if (whole != nullptr) scotch_split(*whole, ranks, split.sizes, split.points);
  return split;
}

// Gives dm (rank 0's whole mesh, the DMPlex numbering its tetrahedra first) the split through a
// shell partitioner, which makes no graph of its own: DMPlexDistribute then migrates.
void hand_split(DM dm, Split& split) {
  PetscPartitioner partitioner = nullptr;
  petsc_check(DMPlexGetPartitioner(dm, &partitioner), "DMPlexGetPartitioner");
  petsc_check(PetscPartitionerSetType(partitioner, PETSCPARTITIONERSHELL),
              "PetscPartitionerSetType");
  petsc_check(
      PetscPartitionerShellSetPartition(partitioner, static_cast<PetscInt>(split.sizes.size()),
                                        split.sizes.data(), split.points.data()),
      "PetscPartitionerShellSetPartition");
  split = {};  // (the partitioner keeps a copy)
}

// The tetrahedron other than e on the face of e opposite its node k (-1: the face is on the
// surface), looked for among the tetrahedra around whichever of the face's three nodes has the
// fewest: the one that also holds the other two.
std::int32_t across(const TetMesh& m, const NodeGraph& tets, std::size_t e, int k) {
  const Tetrahedron& t = m.tets[e];
  std::array<std::int32_t, 3> face{t[(k + 1) % 4], t[(k + 2) % 4], t[(k + 3) % 4]};
  std::sort(face.begin(), face.end(),
            [&](std::int32_t a, std::int32_t b) { return tets.degree(a) < tets.degree(b); });
  const auto holds = [](const Tetrahedron& u, std::int32_t v) {
    return u[0] == v || u[1] == v || u[2] == v || u[3] == v;
  };
  for (std::int32_t q = 0; q < tets.degree(face[0]); ++q) {
    const std::int32_t f = tets.of(face[0])[q];
    if (static_cast<std::size_t>(f) != e && holds(m.tets[f], face[1]) && holds(m.tets[f], face[2]))
      return f;
  }
  return -1;
}

}  // namespace

FaceGraph face_graph(const TetMesh& m) {
  const NodeGraph tets = node_tetrahedra(m);
  FaceGraph g;
  g.start.assign(m.tets.size() + 1, 0);
  g.adjacent.reserve(4 * m.tets.size());
  for (std::size_t e = 0; e < m.tets.size(); ++e) {
    // PETSc's order: the neighbours that hold t[0] (across the faces opposite t[1], t[2], t[3])
    // ascending, as t[0]'s tetrahedra list them; then the one across the face opposite t[0].
    std::array<std::int32_t, 3> holding{across(m, tets, e, 1), across(m, tets, e, 2),
                                        across(m, tets, e, 3)};
    std::sort(holding.begin(), holding.end());
    for (const std::int32_t f : holding)
      if (f >= 0) g.adjacent.push_back(f);
    if (const std::int32_t f = across(m, tets, e, 0); f >= 0) g.adjacent.push_back(f);
    g.start[e + 1] = static_cast<std::int32_t>(g.adjacent.size());
  }
  return g;
}

MeshPartition partition_mesh(MPI_Comm comm, const TetMesh* whole, bool named) {
  int rank = 0;
  MPI_Comm_rank(comm, &rank);
  MeshPartition part;
  std::optional<CoarseNames> names;  // (rank 0's, when named)
  if (named && whole != nullptr) names = name_entities(*whole);
  long long counts[4] = {whole ? static_cast<long long>(whole->node_count()) : 0,
                         whole ? static_cast<long long>(whole->tets.size()) : 0,
                         names ? names->edges : 0, names ? names->faces : 0};
  MPI_Bcast(counts, 4, MPI_LONG_LONG, 0, comm);
  part.global_nodes = counts[0];
  part.global_tetrahedra = counts[1];
  DM dm = whole_plex(comm, whole);
  // (The split made after the DMPlex: made before, rank 0's peak at 1.0e6 DOFs on 2 ranks rose
  // from 0.67 to 0.76 GB, the heap's pages not reused.)
  Split split = split_on_rank_zero(comm, whole);
  hand_split(dm, split);
  DM dist = nullptr;
  PetscSF migration = nullptr;
  petsc_check(DMPlexDistribute(dm, 0, &migration, &dist), "DMPlexDistribute");
  if (dist == nullptr) throw std::logic_error("fem: partition_mesh on one rank");
  DMDestroy(&dm);
  PetscInt start = 0, end = 0;
  petsc_check(DMPlexGetChart(dist, &start, &end), "DMPlexGetChart");
  const PlexPoints data = migrate_points(migration, whole, names ? &*names : nullptr,
                                         named ? kNamedPointInts : kPointInts, end - start);
  names.reset();
  PetscSFDestroy(&migration);
  const std::vector<PartNode> nodes = part_nodes(dist, data, part.global_tetrahedra, rank);
  for (std::size_t k = 0; k < nodes.size(); ++k) {
    part.global.push_back(nodes[k].global);
    part.owner.push_back(nodes[k].owner);
    if (nodes[k].shared) part.shared = static_cast<std::int32_t>(k + 1);
  }
  part.mesh.nodes = part_coordinates(dist, nodes);
  part.by_global.resize(nodes.size());
  for (std::size_t k = 0; k < nodes.size(); ++k) part.by_global[k] = static_cast<std::int32_t>(k);
  std::sort(part.by_global.begin(), part.by_global.end(),
            [&](std::int32_t a, std::int32_t b) { return part.global[a] < part.global[b]; });
  part_mesh(data, part.global_tetrahedra, part);
  if (named)
    part.names = {.node = part.global,
                  .tet = part.tet_global,
                  .edge = std::move(part.names.edge),
                  .face = std::move(part.names.face),
                  .nodes = counts[0],
                  .edges = counts[2],
                  .faces = counts[3],
                  .tets = counts[1]};
  part.halo = std::make_unique<StarForest>(comm, part.shared, halo_leaves(dist, nodes, rank));
  part.halo->make_exchange_buffers();
  DMDestroy(&dist);
  std::vector<ForestLeaf> from_root(nodes.size());
  for (std::size_t k = 0; k < nodes.size(); ++k)
    from_root[k] = {static_cast<std::int32_t>(k), 0, nodes[k].global};
  part.from_root = std::make_unique<StarForest>(
      comm, whole ? static_cast<std::int32_t>(part.global_nodes) : 0, from_root);
  refuse_empty_part(comm, part);
  return part;
}

std::vector<int> partition_on_one_process(const TetMesh& whole, int parts) {
  std::vector<int> part_of(whole.tets.size(), 0);
  if (parts <= 1 || whole.tets.empty()) return part_of;
  std::vector<PetscInt> sizes, points;
  scotch_split(whole, parts, sizes, points);
  for (int p = 0, k = 0; p < parts; ++p)
    for (PetscInt n = 0; n < sizes[p]; ++n) part_of[static_cast<std::size_t>(points[k++])] = p;
  return part_of;
}

}  // namespace rumble::fem
