// The default scene as JSON (scene_defaults.hpp).
#include "scene/scene_defaults.hpp"

#include "dynamics/integrator.hpp"
#include "scene/scene.hpp"

#include <string>

namespace hofem {

namespace {

nlohmann::json array3(const Eigen::Vector3d& v) { return {v.x(), v.y(), v.z()}; }
nlohmann::json array3(const Eigen::Vector3i& v) { return {v.x(), v.y(), v.z()}; }

}  // namespace

nlohmann::json default_scene_json() {
  const Scene s;
  const DynamicsOptions& d = s.dynamics;
  const DistributedSolverOptions& dist = d.solver.distributed;
  nlohmann::json j;
  j["mesh"] = {{"box", {{"min", array3(s.mesh.box_min)}, {"max", array3(s.mesh.box_max)}, {"cells", array3(s.mesh.cells)}}},
               {"cell", s.cell == CellType::Hexahedron ? "hex" : "tet"},
               {"order", s.order}};
  j["material"] = {{"model", s.material}, {"young", s.young}, {"poisson", s.poisson}, {"density", s.density}};
  j["integrator"] = s.is_static ? std::string("static") : std::string(integrator_name(d.integrator));
  j["dt"] = d.dt;
  j["duration"] = s.duration;
  j["solver"] = {{"linear", d.solver.name()},
                 {"krylov_max_iterations", d.solver.krylov.max_iterations},
                 {"newton_rtol", d.newton.rtol},
                 {"newton_max_iterations", d.newton.max_iterations},
                 {"eisenstat_walker", d.newton.eisenstat_walker},
                 {"hessian", d.newton.project_psd ? "projected" : "as-assembled"},
                 {"distributed",
                  {{"krylov", dist.krylov},
                   {"amg", dist.amg},
                   {"rigid_body_modes", dist.rigid_body_modes},
                   {"gmres_restart", dist.gmres_restart}}}};
  j["gravity"] = array3(d.gravity);
  j["damping"] = {{"alpha", d.rayleigh_alpha}, {"beta", d.rayleigh_beta}};
  j["boundary"] = nlohmann::json::array();
  j["initial_velocity"] = array3(s.initial_velocity);
  j["output"] = {{"every", s.output_every}};
  return j;
}

}  // namespace hofem
