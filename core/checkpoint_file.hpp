#pragma once
// Checkpoints that cannot lie: the payload is sealed with its format name, format version, the
// fingerprint of the run it belongs to, its size and a checksum over all of these. A reader tells a
// good checkpoint from a corrupt one (bytes changed or cut off) and from a foreign one (another
// kind of file, another format version, another run's inputs), and says which, so the caller can
// report it by name and start over instead of resuming into different results. Written through
// the shared atomic write path (core/atomic_file.hpp).
#include <string>
#include <string_view>

namespace terracal {

struct CheckpointKind {
  std::string format;  // e.g. "terracal-mcmc-checkpoint"
  int version = 1;     // raised whenever the payload's layout changes
};

enum class CheckpointState { kMissing, kValid, kCorrupt, kForeign };

struct CheckpointRead {
  CheckpointState state = CheckpointState::kMissing;
  std::string payload;  // kValid only
  std::string why;      // kCorrupt / kForeign: what was found, in words
};

void write_checkpoint_file(const std::string& path, const CheckpointKind& kind, std::string_view fingerprint,
                           std::string_view payload);

// Never throws for a bad file: its state says what it is.
CheckpointRead read_checkpoint_file(const std::string& path, const CheckpointKind& kind, std::string_view fingerprint);

}  // namespace terracal
