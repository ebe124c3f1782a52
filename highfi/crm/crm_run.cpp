#include "highfi/crm/crm_run.hpp"

#include <algorithm>
#include <charconv>
#include <chrono>
#include <cmath>
#include <fstream>
#include <sstream>

#include <fmt/format.h>
#include <spdlog/spdlog.h>
#include <nlohmann/json.hpp>

#include "core/atomic_file.hpp"
#include "core/errors.hpp"
#include "core/vtu_writer.hpp"
#include "highfi/crm/crm_checkpoint.hpp"
#include "highfi/crm/crm_run_check.hpp"

namespace terracal {
namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

namespace {

// The rms particle speed above which a settled bed counts as still moving: ten times that of a
// quiet bed (about 0.002 m/s at 0.06 m, results/crm_settling).
constexpr double kSettledRmsSpeed = 0.02;

// Progress in the style of a long solver run: simulated time, speed and real-time factor.
class Progress {
 public:
  Progress(std::string phase, double total, double every) : phase_(std::move(phase)), total_(total), every_(every) {}
  void maybe(const CrmSolver& s, bool force = false) {
    const auto now = Clock::now();
    if (!force && std::chrono::duration<double>(now - last_).count() < every_) return;
    const double wall = std::chrono::duration<double>(now - start_).count();
    const long steps = s.steps() - first_step_;
    const double rate = wall > 0 ? double(steps) / wall : 0;
    const SoilStats st = s.stats();
    spdlog::info(
        "{}: t = {:.4f} / {:.4f} s, step {}, {:.3g} steps/s, {:.3g} particle-steps/s, real-time factor {:.3g}, "
        "max speed {:.3g} m/s, lost {}",
        phase_, s.time(), total_, s.steps(), rate, rate * double(s.engine().soil_count()),
        wall > 0 ? (s.time() - first_time_) / wall : 0.0, st.max_speed, st.lost);
    last_ = now;
  }
  void start(const CrmSolver& s) {
    first_step_ = s.steps();
    first_time_ = s.time();
    start_ = last_ = Clock::now();
  }
  double wall() const { return std::chrono::duration<double>(Clock::now() - start_).count(); }

 private:
  std::string phase_;
  double total_, every_;
  long first_step_ = 0;
  double first_time_ = 0;
  Clock::time_point start_ = Clock::now(), last_ = Clock::now();
};

}  // namespace

HostSoil settled_bed(const CrmScene& scene, CrmDevice device, const fs::path& cache_dir, bool* from_cache) {
  if (from_cache) *from_cache = false;
  CrmScene bed = scene;
  bed.bodies.clear();
  // Effects that act only around moving bodies change nothing in a bed without them: the same bed.
  for_each_effect(CrmEffects{}, [&](auto tag) {
    using E = typename decltype(tag)::type;
    if constexpr (E::kOnlyAroundBodies) bed.effects.disable<E>();
  });
  if (scene.settle_time <= 0) return initial_bed(bed);
  const std::string key = crm_fingerprint(bed, device, false);
  const fs::path file = cache_dir.empty() ? fs::path() : cache_dir / ("bed_" + key + ".h5");
  if (!file.empty() && fs::exists(file)) {
    try {
      CrmCheckpoint c = read_crm_checkpoint(file);
      if (c.fingerprint != key)
        throw InputError(fmt::format("it belongs to another bed (fingerprint {})", c.fingerprint));
      spdlog::info("settled bed from the cache: {}", file.string());
      if (from_cache) *from_cache = true;
      return std::move(c.soil);
    } catch (const InputError& e) {  // a damaged cache entry costs a settling, never the run
      spdlog::warn("cached bed {} is not usable ({}): settling the bed again", file.string(), e.what());
    }
  }
  const HostSoil start = settling_start(bed);
  CrmSolver solver(bed, device, &start);
  Progress progress("settling", scene.settle_time, scene.output.progress_seconds);
  progress.start(solver);
  const CrmRunCheck health(solver);
  while (solver.time() < scene.settle_time - 0.5 * solver.time_step()) {
    solver.step();
    if (solver.steps() % kCrmCheckEvery == 0)
      if (const auto bad = health.check(solver)) throw RunError("settling: " + bad->message);
    progress.maybe(solver);
  }
  if (const auto bad = health.check(solver)) throw RunError("settling: " + bad->message);
  progress.maybe(solver, true);
  // A bed released from the exact lattice (settle_jitter 0) stays still for a while, then rearranges
  // in a burst that takes about a second to die out (results/crm_settling; sooner in deeper beds and
  // at finer spacing). A bed still moving carries its motion into the test: say so.
  const SoilStats st = solver.stats();
  const double rms_speed = st.mass > 0 ? std::sqrt(2 * st.kinetic_energy / st.mass) : 0;
  if (rms_speed > kSettledRmsSpeed)
    spdlog::warn(
        "settling: the bed is still moving after {:.3g} s (rms particle speed {:.3g} m/s, largest {:.3g} m/s, above {} "
        "m/s): "
        "a test on it meets that motion; settle longer (--settle-time), see results/crm_settling",
        solver.time(), rms_speed, st.max_speed, kSettledRmsSpeed);
  HostSoil soil = solver.soil();
  // A settled bed starts at rest.
  for (auto& v : soil.vel) v = {0, 0, 0, v.w == double(kParticleLost) ? v.w : double(kParticleActive)};
  if (!file.empty()) {
    fs::create_directories(cache_dir);
    remove_stale_temporaries(cache_dir.string());  // beds whose caching was interrupted
    write_crm_checkpoint(file, {soil, {}, 0, 0, key});
    spdlog::info("settled bed cached: {}", file.string());
  }
  return soil;
}

void write_crm_snapshot(const fs::path& file, const CrmSolver& solver) {
  const HostSoil s = solver.soil();
  std::vector<double> xyz;
  xyz.reserve(3 * s.size());
  VtuPointData vel{"velocity", 3, {}}, stress{"stress", 6, {}}, pressure{"pressure", 1, {}}, density{"density", 1, {}},
      plastic{"plastic_strain", 1, {}}, status{"status", 1, {}}, id{"id", 1, {}};
  for (std::size_t i = 0; i < s.size(); ++i) {
    xyz.insert(xyz.end(), {s.pos[i].x, s.pos[i].y, s.pos[i].z});
    vel.values.insert(vel.values.end(), {float(s.vel[i].x), float(s.vel[i].y), float(s.vel[i].z)});
    // ParaView's symmetric tensor order: xx, yy, zz, xy, yz, xz.
    stress.values.insert(stress.values.end(), {float(s.s0[i].x), float(s.s0[i].y), float(s.s0[i].z), float(s.s0[i].w),
                                               float(s.s1[i].y), float(s.s1[i].x)});
    pressure.values.push_back(float(-(s.s0[i].x + s.s0[i].y + s.s0[i].z) / 3));
    density.values.push_back(float(s.pos[i].w));
    plastic.values.push_back(float(s.s1[i].z));
    status.values.push_back(float(s.vel[i].w));
    id.values.push_back(float(s.ids[i]));
  }
  write_vtu_points(file, xyz, {vel, stress, pressure, density, plastic, status, id}, solver.time());
  // Body markers in a second file beside it.
  std::vector<double> bxyz;
  VtuPointData body{"body", 1, {}};
  for (std::size_t b = 0; b < solver.bodies().size(); ++b) {
    const BodyState& st = solver.bodies()[b];
    for (const auto& l : solver.body_markers(b)) {
      const Vec3<double> x = st.position + st.orientation.rotate(l);
      bxyz.insert(bxyz.end(), {x.x, x.y, x.z});
      body.values.push_back(float(b));
    }
  }
  fs::path bfile = file;
  bfile.replace_filename("bodies_" + file.filename().string());
  write_vtu_points(bfile, bxyz, {body}, solver.time());
}

namespace {
// The rows of bodies.csv up to time `until`; InputError for a row whose time is not a number.
std::vector<std::string> rows_until(const fs::path& bodies_csv, double until) {
  std::ifstream in(bodies_csv);
  if (!in) throw InputError(fmt::format("{} is missing", bodies_csv.string()));
  std::vector<std::string> rows;
  std::string line;
  std::getline(in, line);  // the header
  for (int line_no = 2; std::getline(in, line); ++line_no) {
    double t = 0;
    const auto end = line.find(',');
    const auto [ptr, ec] = std::from_chars(line.data(), line.data() + std::min(end, line.size()), t);
    if (ec != std::errc() || end == std::string::npos || ptr != line.data() + end)
      throw InputError(fmt::format("{}:{}: the time is not a number", bodies_csv.string(), line_no));
    if (t <= until) rows.push_back(line);
  }
  return rows;
}

// The ParaView collection of the run being resumed, up to time `until` (a snapshot written after the
// checkpoint is written again by the resumed run).
std::vector<std::pair<double, std::string>> snapshots_until(const fs::path& pvd, double until) {
  std::vector<std::pair<double, std::string>> kept;
  for (const auto& entry : read_pvd(pvd))
    if (entry.first <= until) kept.push_back(entry);
  return kept;
}

// What a resumed run carries on from the run it resumes.
struct Resumed {
  bool resumed = false;
  std::vector<std::string> rows;                          // of bodies.csv, up to the checkpoint
  std::vector<std::pair<double, std::string>> snapshots;  // of soil.pvd, up to the checkpoint
};

// Restores the solver from OUT/checkpoint.h5 of the same scene and device, and the outputs up to its
// time. A missing, damaged or foreign checkpoint (or bodies.csv, soil.pvd) is reported and the run
// starts from the beginning: nothing is restored.
Resumed resume_run(CrmSolver& solver, const fs::path& out, const std::string& fingerprint) {
  const fs::path ckpt = out / "checkpoint.h5";
  try {
    CrmCheckpoint c = read_crm_checkpoint(ckpt);
    if (c.fingerprint != fingerprint)
      throw InputError(fmt::format("it belongs to a different scene or device (fingerprint {}, this run {})",
                                   c.fingerprint, fingerprint));
    const double until = c.time + 0.5 * solver.time_step();
    Resumed r{true, rows_until(out / "bodies.csv", until), snapshots_until(out / "soil.pvd", until)};
    solver.restore(c.soil, c.bodies, c.time, c.steps);
    spdlog::info("resuming from {} at t = {} s, step {}", ckpt.string(), c.time, c.steps);
    return r;
  } catch (const InputError& e) {
    spdlog::warn("--resume: {} cannot be resumed ({}): the run starts from the beginning", ckpt.string(), e.what());
    return {};
  }
}

void fill_summary(const CrmSolver& solver, long first_step, double wall_seconds, CrmRunSummary& sum) {
  sum.particles = solver.engine().soil_count();
  sum.markers = solver.engine().marker_count();
  sum.steps = solver.steps() - first_step;
  sum.time_step = solver.time_step();
  sum.simulated = solver.time();
  sum.wall_seconds = wall_seconds;
  sum.particle_steps_per_second =
      sum.wall_seconds > 0 ? double(sum.steps) * double(sum.particles) / sum.wall_seconds : 0;
  const SoilStats st = solver.stats();
  sum.lost = st.lost;
  sum.at_density_cap = st.at_density_cap;
  sum.device = solver.engine().description();
  if (sum.lost > 0) spdlog::warn("{} particles left the domain and were removed from the simulation", sum.lost);
  if (const std::string note = density_cap_note(st, sum.particles); !note.empty())
    spdlog::info("at the end {} (docs/decisions.md, \"Density cap\")", note);
  spdlog::info("the soil was sorted by cell at {} of these {} steps (resolution.sort_skin {})",
               solver.engine().sort_counts().soil, sum.steps, solver.scene().numerics.sort_skin);
}

void write_summary_json(const fs::path& path, const CrmRunSummary& sum, std::size_t device_bytes) {
  nlohmann::ordered_json j = {
      {"particles", sum.particles},
      {"markers", sum.markers},
      {"steps", sum.steps},
      {"time_step_s", sum.time_step},
      {"simulated_s", sum.simulated},
      {"wall_s", sum.wall_seconds},
      {"particle_steps_per_second", sum.particle_steps_per_second},
      {"lost_particles", sum.lost},
      {"at_density_cap", sum.at_density_cap},
      {"bed_from_cache", sum.bed_from_cache},
      {"device", sum.device},
      {"device_bytes_per_particle", double(device_bytes) / double(std::max<std::size_t>(1, sum.particles))},
      {"status", sum.status}};
  if (sum.status != "completed") j["failure"] = sum.failure;
  write_text_atomically(path.string(), j.dump(2) + "\n");
}
}  // namespace

CrmRunSummary run_crm_scene(const CrmScene& scene, const CrmRunOptions& o) {
  fs::create_directories(o.out);
  CrmRunSummary sum;
  const HostSoil bed = settled_bed(scene, o.device, o.cache_dir, &sum.bed_from_cache);
  CrmSolver solver(scene, o.device, &bed);
  const std::string fingerprint = crm_fingerprint(scene, o.device, true);
  const fs::path ckpt = o.out / "checkpoint.h5";
  std::vector<std::string> rows;
  std::vector<std::pair<double, std::string>> snapshots;
  const std::string header = "time_s,body,fx_N,fy_N,fz_N,tx_Nm,ty_Nm,tz_Nm,x_m,y_m,z_m,vx_mps,vy_mps,vz_mps";
  const Resumed from = o.resume ? resume_run(solver, o.out, fingerprint) : Resumed{};
  rows = from.rows;
  snapshots = from.snapshots;
  auto write_rows = [&] {
    std::string text = header + "\n";
    for (const auto& r : rows) text += r + "\n";
    write_text_atomically((o.out / "bodies.csv").string(), text);
  };
  auto record = [&] {
    for (std::size_t b = 0; b < solver.bodies().size(); ++b) {
      const BodyWrench& w = solver.wrenches()[b];
      const BodyState& s = solver.bodies()[b];
      rows.push_back(
          fmt::format("{:.9g},{},{:.9g},{:.9g},{:.9g},{:.9g},{:.9g},{:.9g},{:.9g},{:.9g},{:.9g},{:.9g},{:.9g},{:.9g}",
                      solver.time(), scene.bodies[b].name, w.force.x, w.force.y, w.force.z, w.torque.x, w.torque.y,
                      w.torque.z, s.position.x, s.position.y, s.position.z, s.velocity.x, s.velocity.y, s.velocity.z));
    }
  };
  auto checkpoint = [&] {
    write_crm_checkpoint(ckpt, {solver.soil(), solver.bodies(), solver.time(), solver.steps(), fingerprint});
    write_rows();
  };
  auto snapshot = [&] {
    fs::create_directories(o.out / "vtu");
    const std::string name = fmt::format("soil_{:08d}.vtu", solver.steps());
    write_crm_snapshot(o.out / "vtu" / name, solver);
    snapshots.emplace_back(solver.time(), "vtu/" + name);
    write_pvd(o.out / "soil.pvd", snapshots);
  };
  spdlog::info("CRM: {} particles, {} markers, dt = {:.4g} s, {} on {}", solver.engine().soil_count(),
               solver.engine().marker_count(), solver.time_step(), scene.duration, solver.engine().description());
  Progress progress("run", scene.duration, scene.output.progress_seconds);
  progress.start(solver);
  const long first = solver.steps();
  const auto snapshot_due = [&](long k) {
    return scene.output.vtu_every > 0 && k % scene.output.vtu_every == 0 && solver.time() >= scene.output.vtu_from;
  };
  if (snapshot_due(0) && !from.resumed) snapshot();
  const CrmRunCheck health(solver);
  std::optional<CrmFailure> failure;
  while (solver.time() < scene.duration - 0.5 * solver.time_step()) {
    solver.step();
    const long k = solver.steps();
    if (o.record_every > 0 && k % o.record_every == 0) record();
    // Checked before anything of this step is saved: a checkpoint never holds a failed state.
    if (k % kCrmCheckEvery == 0 && (failure = health.check(solver))) break;
    if (snapshot_due(k)) snapshot();
    if (scene.output.checkpoint_every > 0 && k % scene.output.checkpoint_every == 0) checkpoint();
    progress.maybe(solver);
  }
  if (!failure) failure = health.check(solver);
  progress.maybe(solver, true);
  if (failure) {
    // What was measured up to the failure is kept: bodies.csv to that step, and summary.json says
    // that the run failed, when and why. The last checkpoint (if any) stays that of a sound state.
    if (rows.empty() || solver.steps() % std::max(1L, o.record_every) != 0) record();
    write_rows();
    // The failed state itself is the snapshot one wants to look at in ParaView.
    if (scene.output.vtu_every > 0 && (snapshots.empty() || snapshots.back().first < solver.time())) snapshot();
    fill_summary(solver, first, progress.wall(), sum);
    sum.status = "failed";
    sum.failure = failure->message;
    write_summary_json(o.out / "summary.json", sum, solver.engine().device_bytes());
    throw RunError(fmt::format("run: {} (bodies.csv and summary.json in {} keep the run up to here)", failure->message,
                               o.out.string()));
  }
  checkpoint();
  fill_summary(solver, first, progress.wall(), sum);
  write_summary_json(o.out / "summary.json", sum, solver.engine().device_bytes());
  return sum;
}

}  // namespace terracal
