#pragma once
// CRM checkpoints (HDF5): the soil state in the engine's order, the bodies, time and step count,
// and a fingerprint of the scene. A run restarted from one continues exactly (bit for bit): the
// engine's state round-trips through double without loss and the sort order is preserved.
// The same format caches settled beds.
#include <filesystem>
#include <string>
#include <vector>

#include "highfi/crm/crm_solver.hpp"

namespace terracal {

struct CrmCheckpoint {
  HostSoil soil;
  std::vector<BodyState> bodies;
  double time = 0;
  long steps = 0;
  std::string fingerprint;
};

void write_crm_checkpoint(const std::filesystem::path& file, const CrmCheckpoint& c);
CrmCheckpoint read_crm_checkpoint(const std::filesystem::path& file);

// FNV-1a of a canonical description: scenes that would give different states differ.
std::string crm_fingerprint(const CrmScene& scene, CrmDevice device, bool include_bodies);

}  // namespace terracal
