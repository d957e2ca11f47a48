#include "scene/scene_runner.hpp"

#include "material/material.hpp"
#include "mesh/vtu_writer.hpp"
#include "problem/static_elasticity.hpp"

#include <fmt/format.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <unistd.h>

namespace hofem {

namespace {

using json = nlohmann::json;
using Clock = std::chrono::steady_clock;

std::vector<PrescribedMotion> scene_motions(const Scene& s, const Mesh& mesh) {
  std::vector<PrescribedMotion> motions;
  for (size_t i = 0; i < s.boundary.size(); ++i) {
    const SceneBoundary& b = s.boundary[i];
    std::vector<int> nodes = boundary_nodes(s, mesh, i);
    if (b.motion == "translate") motions.push_back(translation(std::move(nodes), b.velocity, b.until));
    else if (b.motion == "rotate")
      motions.push_back(rotation(std::move(nodes), b.point, b.axis, b.omega, b.until, b.velocity));
    else motions.push_back(fixed_nodes(std::move(nodes)));
    motions.back().release = b.release;
  }
  return motions;
}

void write_frame(const std::string& dir, int frame, const Mesh& mesh, const Eigen::VectorXd& u, const Eigen::VectorXd& v,
                 const Eigen::VectorXd& energy_density, std::vector<std::pair<double, std::string>>& frames, double t) {
  const std::string name = fmt::format("frame_{:05d}.vtu", frame);
  std::vector<VtuField> point{{"displacement", u.reshaped(3, mesh.num_nodes())}};
  if (v.size() > 0) point.push_back({"velocity", v.reshaped(3, mesh.num_nodes())});
  write_vtu((std::filesystem::path(dir) / name).string(), mesh, point,
            {{"strain_energy_density", energy_density.transpose()}});
  frames.emplace_back(t, name);
}

void progress_bar(double fraction, double t, bool done) {
  const int width = 40, filled = static_cast<int>(std::lround(fraction * width));
  std::fprintf(stderr, "\r[%s%s] %3d%%  t = %.4g%s", std::string(filled, '#').c_str(),
               std::string(width - filled, '.').c_str(), static_cast<int>(std::lround(100 * fraction)), t,
               done ? "\n" : "");
  std::fflush(stderr);
}

json stats_json(const DynamicsStats& st) {
  return json{{"mass", st.mass},
              {"mass_matrices_built", st.mass_matrices_built},
              {"mass_factorizations", st.mass_factorizations},
              {"gradient_evaluations", st.gradient_evaluations},
              {"energy_evaluations", st.energy_evaluations},
              {"hessian_assemblies", st.hessian_assemblies},
              {"symbolic_analyses", st.symbolic_analyses},
              {"factorizations", st.factorizations},
              {"newton_iterations", st.newton_iterations},
              {"linear_iterations", st.linear_iterations},
              {"floor_evaluations", st.floor_evaluations},
              {"step_halvings", st.step_halvings},
              {"releases", st.releases},
              {"contact_node_steps", st.contact_node_steps},
              {"max_penetration", st.max_penetration},
              {"polar_decompositions", st.polar_decompositions},
              {"assembly_seconds", st.assembly_seconds},
              {"solve_seconds", st.solve_seconds}};
}

}  // namespace

SceneRunResult run_scene(const Scene& s, const std::string& out_dir, const SceneRunOptions& options) {
  const auto t_start = Clock::now();
  std::error_code ec;
  std::filesystem::create_directories(out_dir, ec);
  if (ec) throw SceneError(fmt::format("{}: cannot create the output directory '{}': {}", s.file, out_dir, ec.message()));
  const Mesh mesh = build_scene_mesh(s);
  const auto material = make_material(s.material, LameParameters::from_young_poisson(s.young, s.poisson));
  std::vector<PrescribedMotion> motions = scene_motions(s, mesh);
  const bool progress = options.progress && isatty(fileno(stderr));

  SceneRunResult result;
  json& st = result.stats;
  st["scene"] = s.name;
  st["file"] = s.file;
  st["integrator"] = s.is_static ? std::string("static") : std::string(integrator_name(s.dynamics.integrator));
  st["mesh"] = {{"cell", s.cell == CellType::Hexahedron ? "hex" : "tet"}, {"order", mesh.order},
                {"nodes", mesh.num_nodes()}, {"elements", mesh.num_elements()}};
  st["material"] = {{"model", s.material}, {"young", s.young}, {"poisson", s.poisson}, {"density", s.density}};
  std::vector<std::pair<double, std::string>> frames;

  if (s.is_static) {
    // Static equilibrium: the motions' positions at their end time are the
    // prescribed displacements; no mass, no time stepping.
    std::vector<DirichletCondition> dirichlet;
    for (PrescribedMotion& m : motions) {
      if (!m.moves()) {
        dirichlet.push_back({m.nodes, nullptr});
        continue;
      }
      // The motion's final position (its "until" time) is the displacement.
      const auto position = m.position;
      dirichlet.push_back({m.nodes, [position](const Eigen::Vector3d& X) { return Eigen::Vector3d(position(X, 1e300) - X); }});
    }
    StaticOptions so;
    so.linear_solver = s.dynamics.linear_solver;
    so.newton = s.dynamics.newton;
    const Eigen::Vector3d rho_g = s.density * s.dynamics.gravity;
    VectorField body;
    if (rho_g.squaredNorm() > 0.0) body = [rho_g](const Eigen::Vector3d&) { return rho_g; };
    StaticElasticity problem(mesh, *material, dirichlet, body, so);
    const StaticReport r = problem.solve();
    result.ok = r.converged;
    result.message = r.message;
    const Eigen::VectorXd u = problem.displacement();
    const Eigen::VectorXd x = Eigen::Map<const Eigen::VectorXd>(mesh.nodes.data(), u.size()) + u;
    const Eigen::VectorXd density =
        problem.assembler().element_energies(*material, x).cwiseQuotient(problem.assembler().element_volumes());
    if (options.write_frames) write_frame(out_dir, 0, mesh, u, Eigen::VectorXd(), density, frames, 0.0);
    st["built"] = {{"mass", "none (static)"},
                   {"mass_matrices_built", 0},
                   {"hessian_assemblies", r.newton_iterations},
                   {"symbolic_analyses", r.symbolic_analyses},
                   {"factorizations", r.factorizations},
                   {"newton_iterations", r.newton_iterations},
                   {"linear_iterations", r.linear_iterations},
                   {"load_steps", r.load_steps},
                   {"polar_decompositions", material->needs_polar_decomposition()
                                                ? static_cast<long long>(r.newton_iterations) * mesh.num_elements() *
                                                      problem.assembler().rule().size()
                                                : 0},
                   {"assembly_seconds", r.assembly_seconds},
                   {"solve_seconds", r.solve_seconds}};
  } else {
    DynamicElasticity sim(mesh, *material, std::move(motions), s.dynamics);
    const Eigen::Vector3d v0 = s.initial_velocity;
    if (v0.squaredNorm() > 0.0) sim.set_velocity([v0](const Eigen::Vector3d&) { return v0; });
    const Eigen::VectorXd volumes = sim.assembler().element_volumes();
    auto frame = [&](int k) {
      if (!options.write_frames) return;
      const Eigen::VectorXd density = sim.assembler().element_energies(*material, sim.positions()).cwiseQuotient(volumes);
      write_frame(out_dir, k, mesh, sim.displacement(), sim.velocities(), density, frames, sim.time());
    };
    if (is_explicit(s.dynamics.integrator)) st["stable_dt_estimate"] = sim.estimate_stable_dt();
    const int steps = static_cast<int>(std::ceil(s.duration / s.dynamics.dt - 1e-9));
    frame(0);
    json per_step = json::array();
    int done = 0;
    for (int k = 1; k <= steps; ++k) {
      const StepReport r = sim.step();
      json row{{"step", k}, {"t", r.time}, {"ok", r.ok}, {"newton_iterations", r.newton_iterations},
               {"linear_iterations", r.linear_iterations}, {"newton_residual", r.newton_residual},
               {"seconds", r.seconds}};
      if (!r.ok) {
        row["message"] = r.message;
        per_step.push_back(row);
        result.ok = false;
        result.message = r.message;
        break;
      }
      const Energies e = sim.energies();
      row["energy"] = {{"kinetic", e.kinetic}, {"elastic", e.elastic}, {"gravity", e.gravity}, {"floor", e.floor},
                       {"total", e.total()}};
      // The displacement curve the integrators are compared by (thesis Fig.
      // 10-11): the mean nodal displacement and the lowest point.
      const Eigen::Matrix3Xd u = sim.displacement().reshaped(3, mesh.num_nodes());
      const Eigen::Vector3d mean = u.rowwise().mean();
      row["mean_displacement"] = {mean.x(), mean.y(), mean.z()};
      row["lowest_z"] = sim.positions().reshaped(3, mesh.num_nodes()).row(2).minCoeff();
      per_step.push_back(row);
      done = k;
      if (k % s.output_every == 0 || k == steps) frame(k);
      if (progress) progress_bar(static_cast<double>(k) / steps, sim.time(), k == steps);
    }
    if (progress && !result.ok) std::fprintf(stderr, "\n");
    st["dt"] = s.dynamics.dt;
    st["duration"] = s.duration;
    st["steps"] = per_step;
    st["steps_done"] = done;
    st["built"] = stats_json(sim.stats());
    if (result.ok) result.message = fmt::format("{} steps to t = {:.6g}", done, sim.time());
  }
  if (options.write_frames) write_pvd((std::filesystem::path(out_dir) / (s.name + ".pvd")).string(), frames);
  st["frames"] = frames.size();
  st["ok"] = result.ok;
  st["message"] = result.message;
  st["wall_seconds"] = std::chrono::duration<double>(Clock::now() - t_start).count();
  const std::string stats_path = (std::filesystem::path(out_dir) / "stats.json").string();
  std::ofstream out(stats_path);
  if (!out) throw SceneError(fmt::format("cannot write '{}'", stats_path));
  out << st.dump(1) << "\n";
  return result;
}

}  // namespace hofem
