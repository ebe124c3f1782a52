#pragma once
// Running a CRM scene end to end: the settled bed (from the cache or settled now), the time loop
// with progress lines, stability checks, ParaView snapshots, body wrenches and checkpoints.
#include <filesystem>
#include <optional>
#include <string>

#include "highfi/crm/crm_solver.hpp"

namespace terracal {

struct CrmRunOptions {
  std::filesystem::path out;  // bodies.csv, summary.json, checkpoint.h5, soil.pvd + vtu/
  CrmDevice device = CrmDevice::kCpu;
  std::filesystem::path cache_dir;  // settled beds; empty = no cache
  bool resume = false;              // continue from out/checkpoint.h5
  long record_every = 10;           // steps between rows of bodies.csv
};

struct CrmRunSummary {
  std::size_t particles = 0, markers = 0;
  long steps = 0;
  double time_step = 0, simulated = 0, wall_seconds = 0, particle_steps_per_second = 0;
  long lost = 0;
  long at_density_cap = 0;  // active particles held at the density cap at the end (soil_model.hpp)
  bool bed_from_cache = false;
  std::string device;
  std::string status = "completed";  // or "failed" (summary.json; the run then throws RunError)
  std::string failure;               // why it failed: what, when, where, what to try
};

// The bed of a scene after settle_time seconds without bodies; cached per (soil, bin, spacing,
// numerics, device) under cache_dir when that is not empty.
HostSoil settled_bed(const CrmScene& scene, CrmDevice device, const std::filesystem::path& cache_dir,
                     bool* from_cache = nullptr);

// Runs the scene for scene.duration, checking its health every kCrmCheckEvery steps (crm_run_check.hpp);
// a run that goes bad writes bodies.csv and summary.json (status "failed") up to that step and
// throws RunError naming the time, the place and what to try.
CrmRunSummary run_crm_scene(const CrmScene& scene, const CrmRunOptions& options);

// Writes the soil (and body markers) as VTU for ParaView.
void write_crm_snapshot(const std::filesystem::path& file, const CrmSolver& solver);

}  // namespace terracal
