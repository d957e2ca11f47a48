// Classes that keep a reference to a mesh, a DOF map, a material or a recorded
// run refuse temporaries at compile time (deleted rvalue overloads): a
// temporary bound there would dangle as soon as the statement ends. Checked
// here as type traits, so removing a deleted overload fails this build.
#include "assembly/assembler.hpp"
#include "dynamics/dynamic_elasticity.hpp"
#include "material/neo_hookean.hpp"
#include "mesh/box_mesh.hpp"
#include "problem/static_elasticity.hpp"
#include "scene/scene_embedding.hpp"
#include "solver/distributed_system.hpp"
#include "study/scene_error.hpp"

#include <gtest/gtest.h>

#include <type_traits>

namespace hofem {
namespace {

using Dirichlet = std::vector<DirichletCondition>;
using Motions = std::vector<PrescribedMotion>;

static_assert(std::is_constructible_v<Assembler, const Mesh&, const DofMap&>);
static_assert(!std::is_constructible_v<Assembler, Mesh&&, const DofMap&>);
static_assert(!std::is_constructible_v<Assembler, const Mesh&, DofMap&&>);
static_assert(!std::is_constructible_v<Assembler, Mesh&&, DofMap&&>);

static_assert(std::is_constructible_v<StaticElasticity, const Mesh&, const Material&, Dirichlet, VectorField>);
static_assert(!std::is_constructible_v<StaticElasticity, Mesh&&, const Material&, Dirichlet, VectorField>);
static_assert(!std::is_constructible_v<StaticElasticity, const Mesh&, NeoHookean&&, Dirichlet, VectorField>);
static_assert(!std::is_constructible_v<StaticElasticity, std::unique_ptr<DistributedMesh>, NeoHookean&&, Dirichlet,
                                       VectorField>);

static_assert(std::is_constructible_v<DynamicElasticity, const Mesh&, const Material&, Motions, DynamicsOptions>);
static_assert(!std::is_constructible_v<DynamicElasticity, Mesh&&, const Material&, Motions, DynamicsOptions>);
static_assert(!std::is_constructible_v<DynamicElasticity, const Mesh&, NeoHookean&&, Motions, DynamicsOptions>);

static_assert(std::is_constructible_v<SceneEmbedding, const Scene&, const Mesh&>);
static_assert(!std::is_constructible_v<SceneEmbedding, const Scene&, Mesh&&>);
static_assert(std::is_constructible_v<ReferenceMeasure, const RecordedRun&, int>);
static_assert(!std::is_constructible_v<ReferenceMeasure, RecordedRun&&, int>);
static_assert(std::is_constructible_v<DistributedLinearSystem, const DistributedDofs&>);
static_assert(!std::is_constructible_v<DistributedLinearSystem, DistributedDofs&&>);

// A DOF map's identity (the p-multigrid's cache key) is new for every map built
// and shared by copies, which hold the same map.
TEST(ReferenceMembers, DofMapIdentityIsNewPerMapAndSharedByCopies) {
  const DofMap a(4, {0}), b(4, {0});
  EXPECT_NE(a.identity(), 0u);
  EXPECT_NE(a.identity(), b.identity());
  const DofMap c = a;
  EXPECT_EQ(c.identity(), a.identity());
  EXPECT_EQ(DofMap().identity(), 0u);
}

// The constrained nodes of both problems come from node_set_union: sorted, each
// node once, and a bad id named with its set - out of range for a static
// problem's Dirichlet condition, shared by two prescribed motions of a dynamic one.
TEST(ReferenceMembers, ConstrainedNodesAreCheckedInOnePlace) {
  EXPECT_EQ(node_set_union({{4, 1}, {1, 0}}, 5, "set", false), (std::vector<int>{0, 1, 4}));
  EXPECT_THROW(node_set_union({{4, 1}, {1, 0}}, 5, "set", true), std::invalid_argument);
  const Mesh m = box_mesh(unit_cube(1), CellType::Tetrahedron, 1);
  const auto mat = make_material("linear", LameParameters::from_young_poisson(1.0, 0.3));
  try {
    StaticElasticity p(m, *mat, {{{0}, nullptr}, {{1, 99}, nullptr}}, nullptr);
    ADD_FAILURE() << "an out-of-range Dirichlet node was accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_EQ(std::string(e.what()), "static problem: Dirichlet condition 1: node 99 is out of range (the mesh has 8 nodes)");
  }
  try {
    DynamicElasticity d(m, *mat, {fixed_nodes({0, 1}), fixed_nodes({2, 1})}, DynamicsOptions{});
    ADD_FAILURE() << "a node in two prescribed motions was accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_EQ(std::string(e.what()), "prescribed motion 1: node 1 is already in prescribed motion 0");
  }
}

}  // namespace
}  // namespace hofem
