#pragma once
// The "amg..." preconditioners where the mesh is known: BoomerAMG
// (linalg/boomeramg.hpp) told which DOF each matrix row is - so that it can
// check the node-interleaved layout hypre's systems AMG assumes - and, for
// variants with interpolation vectors, the rigid rotations of the free nodes.
#include "assembly/mesh_view.hpp"
#include "linalg/boomeramg.hpp"

#include <string>
#include <utility>

namespace hofem {

class BoomerAmgOnMesh final : public BoomerAmgPreconditioner {
 public:
  explicit BoomerAmgOnMesh(const std::string& variant) : BoomerAmgPreconditioner(variant, boomeramg_options(variant)) {}
  /// Options of no registered variant (tests, measurements).
  BoomerAmgOnMesh(std::string name, const BoomerAmgOptions& options)
      : BoomerAmgPreconditioner(std::move(name), options) {}
  void set_mesh_view(const MeshView& d) override {
    if (!d.valid()) return;
    set_row_layout(d.dofs->free_dofs(), amg().options().interp_vec_variant > 0 ? rigid_rotations(d) : Eigen::MatrixXd());
  }
};

}  // namespace hofem
