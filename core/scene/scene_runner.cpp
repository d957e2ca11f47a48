#include "scene/scene_runner.hpp"

#include "scene/run_checkpoint.hpp"
#include "scene/scene_fingerprint.hpp"

#include "material/material.hpp"
#include "io/atomic_file.hpp"
#include "io/vtu_writer.hpp"
#include "problem/static_elasticity.hpp"
#include "scene/scene_embedding.hpp"
#include "scene/scene_mesh.hpp"

#include "parallel/mpi_runtime.hpp"
#include "provenance/progress.hpp"
#include "provenance/provenance.hpp"

#include <fmt/format.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <optional>
#include <regex>

namespace hofem {

// What a dynamic run built and evaluated, each counter under its own name.
NLOHMANN_DEFINE_TYPE_NON_INTRUSIVE(DynamicsStats, linear_solver, linear_solver_reason, mass, mass_matrices_built,
                                   mass_factorizations, gradient_evaluations, energy_evaluations, hessian_assemblies,
                                   symbolic_analyses, factorizations, setup_reuses, newton_iterations, linear_iterations,
                                   projected_directions, shifted_directions, gradient_directions, hessian_nonzeros,
                                   floor_evaluations, step_halvings, releases, contact_node_steps, max_penetration,
                                   polar_decompositions, assembly_seconds, solve_seconds, setup_seconds)

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

// Strain-energy density per cell; 0 where a finite cell integrates nothing (volume 0).
Eigen::VectorXd energy_density(const Eigen::VectorXd& energies, const Eigen::VectorXd& volumes) {
  return (volumes.array() > 0.0).select(energies.array() / volumes.array(), 0.0).matrix();
}

// Frame `frame` of the mesh (the background, when embedded: with each cell's
// volume fraction, and the embedded surface in its own series); frame < 0 is
// the final frame (final.vtu, final_surface.vtu), listed in no series.
void write_frame(const std::string& dir, int frame, const Mesh& mesh, const Eigen::VectorXd& u,
                 const Eigen::VectorXd& v, const Eigen::VectorXd& density, SceneEmbedding* embedding,
                 std::vector<std::pair<double, std::string>>& frames, double t, VtuFormat format) {
  const std::string stem = frame < 0 ? std::string("final") : fmt::format("frame_{:05d}", frame);
  const std::string name = stem + ".vtu";
  std::vector<VtuField> point{{"displacement", u.reshaped(3, mesh.num_nodes())}};
  if (v.size() > 0) point.push_back({"velocity", v.reshaped(3, mesh.num_nodes())});
  std::vector<VtuField> cell{{"strain_energy_density", density.transpose()}};
  if (embedding) {
    const std::vector<double>& f = embedding->volume_fraction();
    cell.push_back(
        {"volume_fraction", Eigen::Map<const Eigen::RowVectorXd>(f.data(), static_cast<Eigen::Index>(f.size()))});
    embedding->write_frame(dir, stem + "_surface.vtu", u, t, format);
  }
  write_vtu((std::filesystem::path(dir) / name).string(), mesh, point, cell, format);
  if (frame >= 0) frames.emplace_back(t, name);
}

// The displacement curve of a step (thesis Fig. 10-11): mean displacement and
// lowest z over the mesh's nodes, or over the embedded surface's vertices.
void add_displacement_curve(const Mesh& mesh, const Eigen::VectorXd& u, const SceneEmbedding* embedding, json& row) {
  const Eigen::Matrix3Xd d =
      embedding ? embedding->surface_displacement(u) : Eigen::Matrix3Xd(u.reshaped(3, mesh.num_nodes()));
  const Eigen::Matrix3Xd& X = embedding ? embedding->surface().nodes : mesh.nodes;
  const Eigen::Vector3d mean = d.rowwise().mean();
  row["mean_displacement"] = {mean.x(), mean.y(), mean.z()};
  row["lowest_z"] = (X + d).row(2).minCoeff();
}

// Inversion over a run (the thesis §5.2, Fig. 9: StVK inverts under strong
// compression, Neo-Hookean does not): the smallest det F over the stiffness
// quadrature points and how many elements have det F <= 0 somewhere, per step
// and over the run.
struct VolumeRatioRecord {
  double min_det_F = std::numeric_limits<double>::infinity();
  double t_min = 0.0;
  int max_inverted = 0, steps_with_inversion = 0;
  json to_json() const {
    return {{"min_det_F", std::isfinite(min_det_F) ? json(min_det_F) : json(nullptr)},
            {"t_of_min_det_F", t_min},
            {"max_inverted_elements", max_inverted},
            {"steps_with_inverted_elements", steps_with_inversion}};
  }
  static VolumeRatioRecord from_json(const json& j) {
    VolumeRatioRecord r;
    if (j.contains("min_det_F") && j["min_det_F"].is_number()) r.min_det_F = j["min_det_F"].get<double>();
    r.t_min = j.value("t_of_min_det_F", 0.0);
    r.max_inverted = j.value("max_inverted_elements", 0);
    r.steps_with_inversion = j.value("steps_with_inverted_elements", 0);
    return r;
  }
};
void add_volume_ratio(const Eigen::VectorXd& min_det_F, json& row, VolumeRatioRecord& record) {
  const double m = min_det_F.size() ? min_det_F.minCoeff() : std::numeric_limits<double>::infinity();
  const int inverted = static_cast<int>((min_det_F.array() <= 0.0).count());
  row["min_det_F"] = std::isfinite(m) ? json(m) : json(nullptr);
  row["inverted_elements"] = inverted;
  if (m < record.min_det_F) {
    record.min_det_F = m;
    record.t_min = row["t"].get<double>();
  }
  record.max_inverted = std::max(record.max_inverted, inverted);
  record.steps_with_inversion += inverted > 0;
}

// Stiffness quadrature points over the whole mesh: the standard rule's in every
// element, or a finite cell's own rule where it has one (scene_embedding.hpp).
long long stiffness_points(const Mesh& mesh, int standard, const SceneEmbedding* embedding) {
  if (!embedding) return static_cast<long long>(standard) * mesh.num_elements();
  long long n = 0;
  const ElementRules rules = embedding->element_rules();
  for (int e = 0; e < mesh.num_elements(); ++e)
    n += rules.stiffness[e] ? rules.stiffness[e]->rule.size() : standard;
  return n;
}

// Removes what an earlier run wrote into the output directory - frames, .pvd
// indexes, stats.json, partial files of a killed run - so that a run's folder
// never mixes two runs (a frame 40 of the old run beside frames 0-20 of the new
// one would pass for a longer run). Other files are left alone.
void clear_earlier_output(const std::string& out_dir) {
  static const std::regex kOurs(R"(((frame_\d+|final)(_surface)?\.vtu|.*\.pvd|stats\.json)(\.partial-\d+)?)");
  std::error_code ec;
  for (const auto& entry : std::filesystem::directory_iterator(out_dir, ec))
    if (entry.is_regular_file(ec) && std::regex_match(entry.path().filename().string(), kOurs) &&
        !std::filesystem::remove(entry.path(), ec) && ec)
      throw SceneError(fmt::format("cannot remove '{}' of an earlier run: {}", entry.path().string(), ec.message()));
}

// A distributed run's fields live on the ranks' pieces of the mesh: gathered
// to the writer in global order (one VTU per frame, one stats file).
Eigen::VectorXd nodal(const DistributedMesh* d, const Eigen::VectorXd& v) { return d ? d->gather_nodal(v) : v; }
Eigen::VectorXd elemental(const DistributedMesh* d, const Eigen::VectorXd& v) { return d ? d->gather_elemental(v) : v; }

// What every part of a run shares: the scene and where it writes, the mesh,
// the embedding and the material built once, and what the run records.
struct SceneRun {
  const Scene& s;
  const std::string& out_dir;
  const SceneRunOptions& options;
  bool writer;  ///< this rank writes the files (rank 0)
  Clock::time_point t_start;
  const Mesh& mesh;
  SceneEmbedding* emb;  ///< null without embedded geometry
  const Material& material;
  SceneRunResult& result;
  json& st;  ///< result.stats
  std::vector<std::pair<double, std::string>>& frames;
  ProgressLog* progress;  ///< null unless options.progress

  void run_static(std::vector<PrescribedMotion> motions);
  void run_dynamic(std::vector<PrescribedMotion> motions);
  /// The run's summary into stats.json, and the .pvd files listing its frames (the writer only).
  void write_outputs();
};

// What a static solve built and evaluated (the static counterpart of DynamicsStats' JSON).
json static_stats_json(const StaticReport& r) {
  return {{"linear_solver", r.linear_solver},
          {"linear_solver_reason", r.linear_solver_reason},
          {"mass", "none (static)"},
          {"mass_matrices_built", 0},
          {"hessian_assemblies", r.newton_iterations},
          {"symbolic_analyses", r.symbolic_analyses},
          {"factorizations", r.factorizations},
          {"newton_iterations", r.newton_iterations},
          {"linear_iterations", r.linear_iterations},
          {"load_steps", r.load_steps},
          {"polar_decompositions", r.polar_decompositions},
          {"assembly_seconds", r.assembly_seconds},
          {"solve_seconds", r.solve_seconds}};
}

// Static equilibrium: the motions' positions at their end time are the
// prescribed displacements; no mass, no time stepping.
void SceneRun::run_static(std::vector<PrescribedMotion> motions) {
  std::vector<DirichletCondition> dirichlet;
  for (PrescribedMotion& m : motions) {
    dirichlet.push_back({m.nodes, nullptr});  // a fixed motion: zero
    // The motion's final position (its "until" time) is the displacement.
    if (m.moves())
      dirichlet.back().displacement = [position = m.position](const Eigen::Vector3d& X) {
        return Eigen::Vector3d(position(X, 1e300) - X);
      };
  }
  StaticOptions so;
  static_cast<ProblemOptions&>(so) = s.dynamics;  // what both problems share: solver, Newton, quadrature
  so.distributed = options.distributed;
  if (emb) {
    so.element_rules = emb->element_rules();
    so.preconditioner_blocks = emb->preconditioner_blocks();
  }
  const Eigen::Vector3d rho_g = s.density * s.dynamics.gravity;
  VectorField body;
  if (rho_g.squaredNorm() > 0.0) body = [rho_g](const Eigen::Vector3d&) { return rho_g; };
  StaticElasticity problem(mesh, material, dirichlet, body, so);
  st["quadrature_points"] = stiffness_points(mesh, static_cast<int>(problem.assembler().rule().size()), emb);
  if (options.observer && writer)
    options.observer(SceneState{mesh, emb, 0, 0.0, Eigen::VectorXd::Zero(3 * mesh.num_nodes())});
  if (progress) progress->stage("static solve", 0.0);  // a heartbeat while Newton runs
  const StaticReport r = problem.solve();
  if (progress) progress->done(r.converged ? "converged" : "not converged");
  result.ok = r.converged;
  result.message = r.message;
  const DistributedMesh* piece = problem.distributed_mesh();
  const Eigen::VectorXd& u_mine = problem.displacement();
  const Eigen::VectorXd x = Eigen::Map<const Eigen::VectorXd>(problem.mesh().nodes.data(), u_mine.size()) + u_mine;
  const Eigen::VectorXd u = nodal(piece, u_mine);
  const Eigen::VectorXd energies = elemental(piece, problem.assembler().element_energies(material, x));
  const Eigen::VectorXd volumes = elemental(piece, problem.assembler().element_volumes());
  const Eigen::VectorXd density = writer ? energy_density(energies, volumes) : Eigen::VectorXd();
  if (options.observer && writer && r.converged) options.observer(SceneState{mesh, emb, 1, 1.0, u});
  if (writer && (options.write_frames || options.final_frame))
    write_frame(out_dir, options.write_frames ? 0 : -1, mesh, u, Eigen::VectorXd(), density, emb, frames, 0.0,
                options.vtu_format);
  st["built"] = static_stats_json(r);
  if (piece) st["per_rank"] = to_json(gather_rank_stats(problem.rank_stats(), piece->comm));
}

// One step's row of stats.json, before its energies and curves.
json step_row(int k, const StepReport& r) {
  return {{"step", k}, {"t", r.time}, {"ok", r.ok}, {"newton_iterations", r.newton_iterations},
          {"linear_iterations", r.linear_iterations}, {"setups", r.setups}, {"setup_reuses", r.setup_reuses},
          {"newton_residual", r.newton_residual}, {"projected_directions", r.projected_directions},
          {"seconds", r.seconds}};
}

// Time stepping: frames every output_every steps, energies, the displacement
// curve and min det F per step.
void SceneRun::run_dynamic(std::vector<PrescribedMotion> motions) {
  DynamicsOptions dynamics = s.dynamics;
  dynamics.distributed = options.distributed;
  if (emb) {
    dynamics.element_rules = emb->element_rules();
    dynamics.preconditioner_blocks = emb->preconditioner_blocks();  // "schwarz": cut cells under 0.5 (§5.2)
  }
  DynamicElasticity sim(mesh, material, std::move(motions), std::move(dynamics));
  const Eigen::Vector3d v0 = s.initial_velocity;
  if (v0.squaredNorm() > 0.0) sim.set_velocity([v0](const Eigen::Vector3d&) { return v0; });
  const DistributedMesh* piece = sim.distributed_mesh();
  st["quadrature_points"] = stiffness_points(mesh, static_cast<int>(sim.assembler().rule().size()), emb);
  if (!piece) st["free_dofs"] = sim.dofs().num_free();  // the unknowns of the linear systems (serial)
  const Eigen::VectorXd volumes = elemental(piece, sim.assembler().element_volumes());
  // k < 0: the final frame (SceneRunOptions::final_frame).
  auto frame = [&](int k) {
    if (k >= 0 ? !options.write_frames : !options.final_frame) return;
    const Eigen::VectorXd energies = elemental(piece, sim.assembler().element_energies(material, sim.positions()));
    const Eigen::VectorXd u = nodal(piece, sim.displacement()), v = nodal(piece, sim.velocities());
    if (!writer) return;
    write_frame(out_dir, k, mesh, u, v, energy_density(energies, volumes), emb, frames, sim.time(),
                options.vtu_format);
  };
  if (is_explicit(s.dynamics.integrator)) st["stable_dt_estimate"] = sim.estimate_stable_dt();
  // The initial state, before a stored or checkpointed state replaces it.
  if (options.observer) {
    const Eigen::VectorXd u0 = nodal(piece, sim.displacement());
    if (writer) options.observer(SceneState{mesh, emb, 0, sim.time(), u0});
  }
  int first = 0;  // the step the run starts after
  json per_step = json::array();
  VolumeRatioRecord deformation;
  const std::string key = options.checkpoint_dir.empty() ? std::string() : scene_fingerprint(s);
  std::optional<RunCheckpoint> resumed;
  if (options.resume && !options.checkpoint_dir.empty()) {
    try {
      resumed = read_checkpoint(options.checkpoint_dir, key);
    } catch (const std::runtime_error& e) {
      throw SceneError(e.what());  // an input problem (exit status 2), named by the file
    }
  }
  const StoredState* start = resumed ? &resumed->state : options.start;
  if (start) {
    if (start->x.size() != sim.positions().size())
      throw SceneError(fmt::format("{}: the stored state has {} values, this scene's mesh {}", s.file,
                                   start->x.size(), sim.positions().size()));
    sim.restart(start->t, start->x, start->v);
    first = start->step;
  }
  if (resumed) {
    const json& rec = resumed->record;
    per_step = rec.value("steps", json::array());
    for (const json& f : rec.value("frames", json::array())) frames.emplace_back(f.at(0).get<double>(), f.at(1).get<std::string>());
    deformation = VolumeRatioRecord::from_json(rec.value("deformation", json::object()));
    st["resumed_from_step"] = first;
    if (options.on_resume) options.on_resume(rec.value("caller", json(nullptr)), first, resumed->state.t);
  }
  const int steps = std::max(0, static_cast<int>(std::ceil((s.duration - sim.time()) / s.dynamics.dt - 1e-9)));
  // Mesh, finite-cell rules, mass matrix, ...: everything before the first step.
  const auto t_steps = Clock::now();
  st["setup_seconds"] = std::chrono::duration<double>(t_steps - t_start).count();
  if (!resumed) frame(0);
  auto last_checkpoint = t_steps;
  auto checkpoint = [&](int k) {
    // The directory first: the caller's record (a study's recorded states) is
    // written into it before the checkpoint itself.
    std::error_code ec;
    std::filesystem::create_directories(options.checkpoint_dir, ec);
    if (ec)
      throw std::runtime_error(
          fmt::format("{}: cannot create the checkpoint directory: {}", options.checkpoint_dir, ec.message()));
    json rec{{"steps", per_step}, {"deformation", deformation.to_json()}, {"frames", json::array()}};
    for (const auto& [t, file] : frames) rec["frames"].push_back({t, file});
    if (options.checkpoint_record) rec["caller"] = options.checkpoint_record(options.checkpoint_dir, k);
    write_checkpoint(options.checkpoint_dir, RunCheckpoint{key, StoredState{key, sim.time(), k, sim.positions(), sim.velocities()}, rec});
    last_checkpoint = Clock::now();
  };
  if (progress) progress->stage(fmt::format("{} steps of dt = {:.3g} s", steps, s.dynamics.dt), 0.0);
  int done = first;
  for (int k = first + 1; k <= first + steps; ++k) {
    const StepReport r = sim.step();
    json row = step_row(k, r);
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
    const Eigen::VectorXd u = nodal(piece, sim.displacement());  // gathered: the writer's curve
    if (writer) add_displacement_curve(mesh, u, emb, row);
    add_volume_ratio(elemental(piece, sim.assembler().element_min_det_F(sim.positions())), row, deformation);
    if (writer && options.observer) options.observer(SceneState{mesh, emb, k, r.time, u});
    per_step.push_back(row);
    done = k;
    if (k % s.output_every == 0 || k == first + steps) frame(k);
    if (!options.checkpoint_dir.empty() && writer && k < first + steps &&
        ((options.checkpoint_every_steps > 0 && k % options.checkpoint_every_steps == 0) ||
         (options.checkpoint_every_seconds > 0.0 &&
          std::chrono::duration<double>(Clock::now() - last_checkpoint).count() >= options.checkpoint_every_seconds)))
      checkpoint(k);
    if (progress)
      progress->update(fmt::format("step {}/{}, t = {:.4g}", k, first + steps, sim.time()), double(k - first) / steps);
  }
  if (!options.write_frames) frame(-1);  // the last state reached, also of a failed run
  if (!options.save_state.empty() && writer)
    write_state(options.save_state, StoredState{options.save_state_key, sim.time(), done, sim.positions(), sim.velocities()});
  if (progress) progress->done(result.ok ? fmt::format("{} steps", done) : "failed at step " + std::to_string(done + 1));
  st["dt"] = s.dynamics.dt;
  st["duration"] = s.duration;
  st["steps"] = per_step;
  st["steps_done"] = done;
  st["deformation"] = deformation.to_json();
  st["stepping_seconds"] = std::chrono::duration<double>(Clock::now() - t_steps).count();  // frames included
  st["built"] = sim.stats();
  if (piece && done > 0) st["per_rank"] = to_json(gather_rank_stats(sim.rank_stats(), piece->comm));
  if (result.ok) result.message = fmt::format("{} steps to t = {:.6g}", done, sim.time());
}

void SceneRun::write_outputs() {
  st["ranks"] = 1;
  if (options.distributed) {
    int ranks = 1;
    MPI_Comm_size(MPI_COMM_WORLD, &ranks);
    st["ranks"] = ranks;
  }
  if (!writer) return;
  if (options.write_frames) {
    write_pvd((std::filesystem::path(out_dir) / (s.name + ".pvd")).string(), frames);
    if (emb) emb->write_pvd(out_dir, s.name);
  }
  st["frames"] = frames.size();
  st["status"] = result.ok ? "completed" : "failed";
  st["ok"] = result.ok;
  st["message"] = result.message;
  st["wall_seconds"] = std::chrono::duration<double>(Clock::now() - t_start).count();
  if (!out_dir.empty())
    write_file_atomically((std::filesystem::path(out_dir) / "stats.json").string(), st.dump(1) + "\n");
}

SceneRunResult run_scene_in(const Scene& s, const std::string& out_dir, const SceneRunOptions& options, bool writer,
                            Clock::time_point t_start) {
  // Progress on stderr (the writer's): set-up, then the solve or the steps with
  // the time, an estimate of the rest and a line at least every 20 s.
  std::optional<ProgressLog> progress;
  if (options.progress && writer) progress.emplace("scene " + s.name).stage("set-up: mesh, embedding, material", 0.0);
  const Mesh mesh = build_scene_mesh(s);
  std::optional<SceneEmbedding> embedding;
  if (s.embedded) embedding.emplace(s, mesh);
  const auto material = make_material(s.material, LameParameters::from_young_poisson(s.young, s.poisson));
  std::vector<PrescribedMotion> motions = scene_motions(s, mesh);

  SceneRunResult result;
  std::vector<std::pair<double, std::string>> frames;
  SceneRun run{s, out_dir, options, writer, t_start, mesh, embedding ? &*embedding : nullptr, *material, result,
               result.stats, frames, progress ? &*progress : nullptr};
  json& st = result.stats;
  st["context"] = provenance_context(s.name);
  st["scene"] = s.name;
  st["file"] = s.file;
  st["integrator"] = s.is_static ? std::string("static") : std::string(integrator_name(s.dynamics.integrator));
  st["mesh"] = {{"cell", s.cell == CellType::Hexahedron ? "hex" : "tet"}, {"order", mesh.order},
                {"nodes", mesh.num_nodes()}, {"elements", mesh.num_elements()}};
  st["material"] = {{"model", s.material}, {"young", s.young}, {"poisson", s.poisson}, {"density", s.density}};
  if (run.emb) st["embedded"] = run.emb->stats();
  if ((options.start || !options.save_state.empty() || !options.checkpoint_dir.empty()) &&
      (s.is_static || options.distributed))
    throw SceneError(fmt::format("{}: stored states and checkpoints are for serial time-stepping runs", s.file));
  if (s.is_static)
    run.run_static(std::move(motions));
  else
    run.run_dynamic(std::move(motions));
  run.write_outputs();
  return result;
}

}  // namespace

SceneRunResult run_scene(const Scene& s, const std::string& out_dir, const SceneRunOptions& options) {
  const auto t_start = Clock::now();
  int rank = 0;
  if (options.distributed) {
    ensure_hypre();
    MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  }
  const bool writer = rank == 0;  // distributed: one rank writes
  if (out_dir.empty() && (options.write_frames || options.final_frame))
    throw SceneError(fmt::format("{}: frames need an output directory", s.file));
  // No output directory: nothing is written (a study's run keeps what it needs in memory).
  const bool files = writer && !out_dir.empty();
  std::error_code ec;
  if (!out_dir.empty()) std::filesystem::create_directories(out_dir, ec);
  if (ec) throw SceneError(fmt::format("{}: cannot create the output directory '{}': {}", s.file, out_dir, ec.message()));
  // Resuming keeps the frames written before the checkpoint (later ones are written again).
  const bool resuming = options.resume && !options.checkpoint_dir.empty() &&
                        std::filesystem::exists(std::filesystem::path(options.checkpoint_dir) / "checkpoint.json", ec);
  if (resuming) {
    // Refused before anything is written: a wrong checkpoint leaves the earlier run's files as they were.
    try {
      read_checkpoint(options.checkpoint_dir, scene_fingerprint(s));
    } catch (const std::runtime_error& e) {
      throw SceneError(e.what());
    }
  }
  if (files && !resuming) clear_earlier_output(out_dir);
  try {
    return run_scene_in(s, out_dir, options, writer, t_start);
  } catch (const std::exception& e) {
    // A run that stops on an error still leaves a stats.json, which says so and why.
    if (files)
      write_file_atomically((std::filesystem::path(out_dir) / "stats.json").string(),
                            json{{"context", provenance_context(s.name)}, {"scene", s.name}, {"file", s.file},
                                 {"status", "failed"}, {"ok", false}, {"message", e.what()},
                                 {"wall_seconds", std::chrono::duration<double>(Clock::now() - t_start).count()}}
                                    .dump(1) +
                                "\n");
    throw;
  }
}

}  // namespace hofem
