#include "study/study.hpp"

#include "io/atomic_file.hpp"
#include "provenance/progress.hpp"
#include "provenance/provenance.hpp"
#include "study/scene_error.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <map>
#include <optional>

namespace hofem {

namespace {

using json = nlohmann::json;
namespace fs = std::filesystem;

const char* const kMetrics[] = {"surface_rms", "surface_max", "displacement_rms", "l2", "h1", "relative_l2",
                                "relative_h1"};

// The q-quantile of v by linear interpolation between order statistics
// (Hyndman & Fan type 7, R's and NumPy's default); q = 0.5 is the median.
double quantile(std::vector<double> v, double q) {
  if (v.empty()) return 0.0;
  std::sort(v.begin(), v.end());
  const double x = q * static_cast<double>(v.size() - 1);
  const size_t k = static_cast<size_t>(x);
  return k + 1 < v.size() ? v[k] + (x - static_cast<double>(k)) * (v[k + 1] - v[k]) : v[k];
}
double median(const std::vector<double>& v) { return quantile(v, 0.5); }

// Cost and size of a run, from its stats.json (scene_runner.hpp).
json cost_of(const json& st, bool embedded) {
  std::vector<double> seconds;
  // Iterations summed over the per-step rows: a run resumed from a checkpoint
  // keeps those rows, while its "built" counters start again at the resumption.
  long long newton = 0, linear = 0;
  if (st.contains("steps"))
    for (const json& row : st["steps"]) {
      seconds.push_back(row.value("seconds", 0.0));
      newton += row.value("newton_iterations", 0LL);
      linear += row.value("linear_iterations", 0LL);
    }
  const long long nodes = st.contains("mesh") ? st["mesh"].value("nodes", 0LL) : 0LL;
  const long long active = embedded ? st["embedded"]["nodes"].value("active", 0LL) : nodes;
  const json built = st.value("built", json::object());
  json c{{"elements", st.contains("mesh") ? st["mesh"].value("elements", 0LL) : 0LL},
         {"nodes", nodes},
         {"unknowns", 3 * active},
         {"quadrature_points", st.value("quadrature_points", 0LL)},
         {"steps", seconds.empty() ? 1 : seconds.size()},
         // A static scene is one step: its solve, mesh and set-up included.
         {"time_per_step_median", seconds.empty() ? st.value("wall_seconds", 0.0) : median(seconds)},
         // The spread of the per-step times (each step a repeat of "one step"):
         // their quartiles, so a ratio of medians can be read against it.
         {"time_per_step_quartiles", seconds.empty() ? json::array({st.value("wall_seconds", 0.0),
                                                                     st.value("wall_seconds", 0.0)})
                                                     : json::array({quantile(seconds, 0.25), quantile(seconds, 0.75)})},
         {"total_seconds", st.value("wall_seconds", 0.0)},
         {"newton_iterations", seconds.empty() ? built.value("newton_iterations", 0LL) : newton},
         {"linear_iterations", seconds.empty() ? built.value("linear_iterations", 0LL) : linear},
         // What a step's time went into and what it solved (Table 1's explanation):
         // totals over the run (a run resumed from a checkpoint: since the resumption).
         {"projected_directions", built.value("projected_directions", 0LL)},
         {"setup_seconds", built.value("setup_seconds", 0.0)},
         {"assembly_seconds", built.value("assembly_seconds", 0.0)},
         {"solve_seconds", built.value("solve_seconds", 0.0)},
         {"hessian_nonzeros", built.value("hessian_nonzeros", 0LL)},
         {"linear_solver", built.value("linear_solver", std::string())}};
  if (embedded) c["active_cells"] = st["embedded"]["cells"].value("uncut", 0) + st["embedded"]["cells"].value("cut", 0);
  return c;
}

// Errors at each frame (state 0 is the floor) and their max over frames.
json errors_of(const std::vector<StateError>& errors) {
  json frames = json::array(), worst = json::object();
  for (const char* m : kMetrics) worst[m] = 0.0;
  for (size_t k = 1; k < errors.size(); ++k) {
    frames.push_back(to_json(errors[k]));
    for (const char* m : kMetrics) worst[m] = std::max(worst[m].get<double>(), frames.back()[m].get<double>());
  }
  const json floor = to_json(errors.front());
  return {{"floor", {{"surface_rms", floor["surface_rms"]}, {"surface_max", floor["surface_max"]}}},
          {"frames", frames},
          {"max_over_frames", worst}};
}

// The reference's own error from the coarser level (richardson_error), per
// metric: surface and L2-type errors converge like h^(p+1), H1 like h^p.
json richardson_of(long long reference_elements, long long coarser_elements, int p, const json& distance) {
  const double ratio = std::cbrt(static_cast<double>(reference_elements) / static_cast<double>(coarser_elements));
  json out{{"ratio", ratio}, {"order_assumed", {{"surface_and_l2", p + 1}, {"h1", p}}}};
  const json& measured = distance["max_over_frames"];
  json estimate = json::object();
  for (const char* m : kMetrics) {
    const double q = std::string(m).find("h1") != std::string::npos ? p : p + 1;
    estimate[m] = ratio > 1.0 ? richardson_error(measured[m].get<double>(), ratio, q) : measured[m].get<double>();
  }
  out["distance_to_coarser"] = measured;
  out["estimate"] = estimate;
  return out;
}

// The measuring floor: the reference's undeformed surface at the study's
// subdivisions against the same at twice as many.
double measuring_floor(const RecordedRun& reference, int subdivisions) {
  const int s = subdivisions >= 1 ? subdivisions : default_subdivisions(reference.mesh.cell, reference.mesh.order);
  const TriangleSurface a = deformed_surface(reference.mesh, run_surface_lattice(reference, s), reference.states[0]);
  const TriangleSurface b = deformed_surface(reference.mesh, run_surface_lattice(reference, 2 * s), reference.states[0]);
  return surface_distance(a, b).rms();
}

// Per threshold: the cheapest run (median time per step) whose metric is under it, overall and per family.
json cheapest_of(const json& runs, const std::vector<double>& thresholds, const std::string& metric) {
  json out = json::array();
  for (const double t : thresholds) {
    json best = nullptr;
    std::map<std::string, json> family;
    for (const json& r : runs) {
      if (!r["ok"].get<bool>() || r["metric"].get<double>() > t) continue;
      const auto cheaper = [&](const json& b) {
        return b.is_null() || r["time_per_step_median"].get<double>() < b["time_per_step_median"].get<double>();
      };
      const json brief_row{{"name", r["name"]}, {"family", r["family"]}, {metric, r["metric"]},
                           {"time_per_step_median", r["time_per_step_median"]}, {"unknowns", r["unknowns"]}};
      if (cheaper(best)) best = brief_row;
      json& f = family[r["family"].get<std::string>()];
      if (cheaper(f)) f = brief_row;
    }
    out.push_back({{"threshold", t}, {"cheapest", best}, {"per_family", family}});
  }
  return out;
}

std::string summary_markdown(const json& study) {
  const std::string metric = study["metric"];
  std::string md = fmt::format("# Study {}: time per step against {}\n\nScene `{}`; frames at t = {}; reference `{}` "
                               "({} unknowns), its own error (Richardson) {}.\n\n",
                               study["name"].get<std::string>(), metric, study["scene"].get<std::string>(),
                               study["frames"].dump(), study["reference"]["name"].get<std::string>(),
                               study["reference"]["unknowns"].get<long long>(),
                               study["reference"].contains("richardson")
                                   ? fmt::format("{:.3g}", study["reference"]["richardson"]["estimate"][metric].get<double>())
                                   : std::string("not estimated (no coarser level)"));
  md += fmt::format("The runs took {} of wall time (each run's own, over every session that ran them; this "
                    "session {}).\n\n",
                    ProgressLog::format_seconds(study.value("run_seconds", 0.0)),
                    ProgressLog::format_seconds(study.value("wall_seconds", 0.0)));
  md += "Errors are maxima over the frames; the reference's own error (same maximum, Richardson) is in brackets.\n\n";
  md += "| run | family | unknowns | quad. points | time/step [s] | Newton | linear | floor | surface RMS | surface max "
        "| displ. RMS | rel. L2 | rel. H1 |\n|---|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|\n";
  for (const json& r : study["runs"]) {
    if (!r["ok"].get<bool>()) {
      md += fmt::format("| {} | {} | failed: {} |\n", r["name"].get<std::string>(), r["family"].get<std::string>(),
                        r["message"].get<std::string>());
      continue;
    }
    const json& m = r["max_over_frames"];
    const json& ref = r["reference_error"];
    auto cell = [&](const char* key) {
      return ref.is_null() ? fmt::format("{:.3g}", m[key].get<double>())
                           : fmt::format("{:.3g} ({:.2g})", m[key].get<double>(), ref[key].get<double>());
    };
    md += fmt::format("| {} | {} | {} | {} | {:.4g} | {} | {} | {:.3g} | {} | {} | {} | {} | {} |\n",
                      r["name"].get<std::string>(), r["family"].get<std::string>(), r["unknowns"].get<long long>(),
                      r["quadrature_points"].get<long long>(), r["time_per_step_median"].get<double>(),
                      r["newton_iterations"].get<long long>(), r["linear_iterations"].get<long long>(),
                      r["floor"]["surface_rms"].get<double>(), cell("surface_rms"), cell("surface_max"),
                      cell("displacement_rms"), cell("relative_l2"), cell("relative_h1"));
  }
  if (!study.value("complete", true))
    md += fmt::format("\n**Incomplete** (stopped, or still running): the runs still to come are {}; the verdicts below "
                      "are of the runs above only.\n",
                      study["pending"].dump());
  if (!study.value("left_out", json::array()).empty())
    md += fmt::format("\nLeft out (the study's extended tier, run by `hofem study --extended`; not measured yet): {}.\n",
                      study["left_out"].dump());
  md += fmt::format("\nCheapest run (median time per step) with {} (max over frames) under each threshold:\n\n", metric);
  for (const json& c : study["cheapest"]) {
    md += fmt::format("- {} <= {:.3g}: ", metric, c["threshold"].get<double>());
    if (c["cheapest"].is_null()) md += "none of the runs\n";
    else
      md += fmt::format("**{}** ({}, {:.4g} s per step)\n", c["cheapest"]["name"].get<std::string>(),
                        c["cheapest"]["family"].get<std::string>(), c["cheapest"]["time_per_step_median"].get<double>());
  }
  return md;
}

// A run's row: what it is (its overrides, cell, order) and what it cost.
json describe(const StudyRun& r, const json& stats, bool ok, const std::string& message, bool stored) {
  json row = cost_of(stats, r.scene.embedded.has_value());
  row["name"] = r.name;
  row["family"] = r.family;
  row["overrides"] = r.overrides;
  row["cell"] = r.scene.cell == CellType::Hexahedron ? "hex" : "tet";
  row["order"] = r.scene.order;
  row["embedded"] = r.scene.embedded.has_value();
  row["ok"] = ok;
  row["message"] = message;
  row["stored"] = stored;  // taken from an earlier run's record (StudyRunOptions::resume)
  return row;
}
json describe(const StudyRun& r, const RecordedRun& run) { return describe(r, run.stats, run.ok, run.message, run.stored); }

// A run's share of a study's work, for the progress line's ETA only: its mesh
// nodes (from a generator's cells and the order; a mesh file, unknown before it
// is read, counts as 10^4) times its steps. The cost per node differs between
// families and grows with size, so the estimate is rough but, unlike counting
// runs, puts a 600 k-unknown reference ahead of a 3 k-unknown run.
double estimated_work(const Scene& s) {
  const Eigen::Vector3d c = s.mesh.cells.cast<double>() * s.order;
  double nodes = s.mesh.tube || s.mesh.torus ? (c[0] + 1.0) * c[1] * (c[2] + 1.0)
                                              : (c[0] + 1.0) * (c[1] + 1.0) * (c[2] + 1.0);
  if (!s.mesh.file.empty()) nodes = 1e4;
  const double steps = s.is_static ? 1.0 : std::max(1.0, std::ceil(s.duration / s.dynamics.dt));
  return nodes * steps;
}

using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point t0) { return std::chrono::duration<double>(Clock::now() - t0).count(); }

}  // namespace

double richardson_error(double distance_to_coarser, double ratio, double order) {
  return distance_to_coarser / (std::pow(ratio, order) - 1.0);
}

json run_study(const Study& s, const std::string& out_dir, const StudyRunOptions& options) {
  const auto t0 = Clock::now();
  const fs::path out(out_dir);
  // Progress: a line per run (with the share of runs done), its result, and a
  // heartbeat at least every 20 s while a run goes on.
  std::optional<ProgressLog> progress;
  if (options.progress) progress.emplace("study " + s.name);
  auto say = [&](const std::string& line) {
    if (progress) progress->note(line);
  };
  // The ETA weighs each run by estimated_work; work found stored (resume) is
  // left out of both sides, so a resumed study's rate is this session's.
  double total_work = estimated_work(s.reference.scene), done_work = 0.0, stored_work = 0.0;
  if (s.coarser_reference) total_work += estimated_work(s.coarser_reference->scene);
  // Runs of the extended tier count only when asked for (StudyRunOptions::extended).
  const auto to_run = [&](const StudyRun& r) { return !r.extended || options.extended; };
  for (const StudyRun& r : s.runs)
    if (to_run(r)) total_work += estimated_work(r.scene);
  const auto share = [&](double work) {
    return std::clamp((work - stored_work) / std::max(total_work - stored_work, 1e-300), 0.0, 1.0);
  };
  // A run's work is done (or was found stored: skipped).
  const auto finished = [&](const StudyRun& r, bool stored) {
    done_work += estimated_work(r.scene);
    if (stored) stored_work += estimated_work(r.scene);
  };
  auto record = [&](const StudyRun& r) {
    if (progress) progress->stage(fmt::format("running {} ({})", r.name, r.family), share(done_work));
    // Within a run, its share of the scene's time: the ETA moves with the steps.
    const double work = estimated_work(r.scene), end = std::max(r.scene.duration, 1e-300);
    // A run resumed from a checkpoint: its steps before it were an earlier
    // session's work, left out of the rate as stored runs are.
    auto on_step = [&](double t, bool resumed) {
      if (resumed) stored_work += std::min(t / end, 1.0) * work;
      if (progress)
        progress->update(fmt::format("running {} ({}): t = {:.4g} of {:.4g} s", r.name, r.family, t, end),
                         share(done_work + std::min(t / end, 1.0) * work));
    };
    RecordedRun run = record_run(r.scene, (out / "runs" / r.name).string(), s.frames, options.resume, 0, on_step);
    if (run.stored) say(fmt::format("{}: stored result of an earlier run (same scene)", r.name));
    finished(r, run.stored);
    return run;
  };
  // 1. The reference, its measuring data and floor, and its own error from the coarser level.
  RecordedRun reference = record(s.reference);
  add_own_rules(reference, s.reference.scene);
  if (!reference.ok)
    throw SceneError(fmt::format("{}: reference: the reference run failed: {}", s.file, reference.message));
  const ReferenceMeasure measure(reference, s.subdivisions);
  const double floor = measuring_floor(reference, s.subdivisions);
  if (s.metric == "surface_rms" && floor > 0.1 * s.thresholds.front())
    throw SceneError(fmt::format("{}: thresholds: {:.3g} is below 10 x the measuring floor {:.3g} (the reference's "
                                 "surface at {} against twice the subdivisions); raise it or 'subdivisions'",
                                 s.file, s.thresholds.front(), floor, s.subdivisions));
  json ref_row = describe(s.reference, reference);
  // What a stored measurement was measured against (recorded_run.hpp:
  // StoredMeasure): with --resume each measured run keeps its errors and drops
  // its states, so a study run in parts keeps only the reference's states.
  const std::string measure_key = fmt::format("{}|subdivisions={}|{}", record_key(s.reference.scene, s.frames),
                                              s.subdivisions, kSceneErrorMethod);
  // A run's row with its errors: from its stored measurement, else run (or taken
  // from its record) and measured now. Throws nothing; a failed run's row says why.
  auto measured_row = [&](const StudyRun& r) {
    const std::string dir = (out / "runs" / r.name).string();
    if (options.resume)
      if (const std::optional<StoredMeasure> m = stored_measure(r.scene, dir, s.frames, measure_key)) {
        if (to_run(r)) finished(r, true);  // a left-out run was never part of the ETA's work
        say(fmt::format("{}: stored measurement of an earlier run (same scene, same reference)", r.name));
        json row = describe(r, m->stats, true, "", true);
        row.update(m->errors);
        return row;
      }
    const RecordedRun run = record(r);
    json row = describe(r, run);
    if (!run.ok) return row;
    const auto t_measure = Clock::now();
    json errors = errors_of(scene_error(run, measure, s.subdivisions));
    errors["measure_seconds"] = seconds_since(t_measure);
    if (options.resume) store_measure(dir, measure_key, errors, true);
    row.update(errors);
    return row;
  };
  // Runs whose scene is the coarser reference's (a study's ladder often holds
  // it) take its row instead of running it again.
  std::optional<json> coarser_row;
  std::string coarser_key;
  if (s.coarser_reference) {
    json coarse = measured_row(*s.coarser_reference);
    if (!coarse["ok"].get<bool>())
      throw SceneError(fmt::format("{}: reference.coarser: the run failed: {}", s.file, coarse["message"].get<std::string>()));
    ref_row["richardson"] = richardson_of(ref_row["elements"].get<long long>(), coarse["elements"].get<long long>(),
                                          s.reference.scene.order, coarse);
    coarser_key = record_key(s.coarser_reference->scene, s.frames);
    coarser_row = std::move(coarse);
  }
  // Quoted beside every run's errors: the reference's own error, or null without a coarser level.
  const json reference_error = ref_row.contains("richardson") ? ref_row["richardson"]["estimate"] : json(nullptr);

  // The study's files, written after every run (a stopped study leaves the rows
  // it has, "complete": false and the runs still to come).
  json runs = json::array();
  json left_out = json::array();  // extended runs neither asked for nor found measured
  // The files with the runs from s.runs[first_pending] on still to come.
  auto study_json = [&](size_t first_pending) {
    const bool complete = first_pending >= s.runs.size();
    json pending = json::array();
    for (size_t k = first_pending; k < s.runs.size(); ++k)
      if (to_run(s.runs[k])) pending.push_back(s.runs[k].name);
    // The study's cost over all the sessions that made it: each run's own wall
    // time (stored runs keep theirs; a coarser level shared with a run counts once).
    double run_seconds = ref_row.value("total_seconds", 0.0) + (coarser_row ? coarser_row->value("total_seconds", 0.0) : 0.0);
    for (const json& r : runs)
      if (!r.contains("same_as")) run_seconds += r.value("total_seconds", 0.0);
    return json{{"context", provenance_context(s.name)},
                {"name", s.name},
                {"file", s.file},
                {"scene", s.scene_file},
                {"overrides", s.overrides},
                {"frames", s.frames},
                {"metric", s.metric},
                {"thresholds", s.thresholds},
                {"subdivisions", s.subdivisions},
                {"measuring_floor", floor},
                {"reference", ref_row},
                {"runs", runs},
                {"complete", complete},
                {"pending", pending},
                {"left_out", left_out},
                {"cheapest", cheapest_of(runs, s.thresholds, s.metric)},
                {"run_seconds", run_seconds},
                {"wall_seconds", seconds_since(t0)}};
  };
  auto write_files = [&](const json& study) {
    write_file_atomically((out / "study.json").string(), study.dump(1) + "\n");
    write_file_atomically((out / "summary.md").string(), summary_markdown(study));
  };

  // 2. Each run, then its errors against the reference.
  for (size_t k = 0; k < s.runs.size(); ++k) {
    const StudyRun& r = s.runs[k];
    json row;
    if (!to_run(r)) {
      // The extended tier, not asked for: reported only from a stored measurement.
      const std::optional<StoredMeasure> m =
          options.resume ? stored_measure(r.scene, (out / "runs" / r.name).string(), s.frames, measure_key)
                         : std::nullopt;
      if (!m) {
        left_out.push_back(r.name);
        say(fmt::format("{}: extended run, left out (hofem study --extended runs it)", r.name));
        continue;
      }
    }
    if (coarser_row && record_key(r.scene, s.frames) == coarser_key) {
      finished(r, true);
      row = *coarser_row;
      row["name"] = r.name;
      row["family"] = r.family;
      row["overrides"] = r.overrides;
      row["same_as"] = s.coarser_reference->name;
      say(fmt::format("{}: the coarser reference's run (same scene)", r.name));
    } else {
      row = measured_row(r);
    }
    if (row["ok"].get<bool>()) {
      row["metric"] = row["max_over_frames"][s.metric];
      row["reference_error"] = reference_error;
      say(fmt::format("{}: {:.3g} s per step, {} = {:.3g}", r.name, row["time_per_step_median"].get<double>(),
                      s.metric, row["metric"].get<double>()));
    } else {
      say(fmt::format("{} failed: {}", r.name, row["message"].get<std::string>()));
    }
    row["extended"] = r.extended;
    runs.push_back(row);
    if (k + 1 < s.runs.size()) write_files(study_json(k + 1));
  }

  // 3. The table, the cheapest runs, the files.
  const json study = study_json(s.runs.size());
  write_files(study);
  say(fmt::format("wrote {}", (out / "study.json").string()));
  return study;
}

}  // namespace hofem
