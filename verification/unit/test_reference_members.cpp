// Classes that keep a reference to a mesh, a DOF map, a material or a recorded
// run refuse temporaries at compile time (deleted rvalue overloads): a
// temporary bound there would dangle as soon as the statement ends. Checked
// here as type traits, so removing a deleted overload fails this build.
#include "assembly/assembler.hpp"
#include "dynamics/dynamic_elasticity.hpp"
#include "material/neo_hookean.hpp"
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

}  // namespace
}  // namespace hofem
