// A sealed checkpoint reads back exactly, and no change to its bytes passes for a valid checkpoint.
#include <catch2/catch.hpp>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>

#include "../scratch_dir.hpp"
#include "core/checkpoint_file.hpp"

using terracal::CheckpointKind;
using terracal::CheckpointState;
using terracal::read_checkpoint_file;
using terracal::write_checkpoint_file;

namespace {

std::string slurp(const std::string& p) {
  std::ifstream in(p, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

void spit(const std::string& p, const std::string& bytes) { std::ofstream(p, std::ios::binary) << bytes; }

const CheckpointKind kKind{"terracal-test-checkpoint", 3};

}  // namespace

TEST_CASE("checkpoint file: round trip, missing, foreign", "[core][checkpoint]") {
  const terracal::test::ScratchDir scratch("ckpt");
  const std::string file = scratch.str() + "/.checkpoint";
  CHECK(read_checkpoint_file(file, kKind, "abc").state == CheckpointState::kMissing);

  std::string payload(1000, '\0');
  for (std::size_t i = 0; i < payload.size(); ++i) payload[i] = static_cast<char>(i * 7 + 3);  // binary, NULs too
  write_checkpoint_file(file, kKind, "abc", payload);
  const auto ok = read_checkpoint_file(file, kKind, "abc");
  REQUIRE(ok.state == CheckpointState::kValid);
  CHECK(ok.payload == payload);

  const auto other_run = read_checkpoint_file(file, kKind, "abd");
  CHECK(other_run.state == CheckpointState::kForeign);
  CHECK(other_run.why.find("other inputs or options") != std::string::npos);
  const auto other_version = read_checkpoint_file(file, {kKind.format, 4}, "abc");
  CHECK(other_version.state == CheckpointState::kForeign);
  CHECK(other_version.why.find("format version 3") != std::string::npos);
  CHECK(read_checkpoint_file(file, {"terracal-other", 3}, "abc").state == CheckpointState::kForeign);

  spit(file, "{\"format\": \"terracal-mcmc-checkpoint-1\"}");  // an old or unrelated file
  CHECK(read_checkpoint_file(file, kKind, "abc").state == CheckpointState::kForeign);
}

TEST_CASE("checkpoint file: every flipped byte and every truncation is caught", "[core][checkpoint]") {
  const terracal::test::ScratchDir scratch("ckpt_flip");
  const std::string file = scratch.str() + "/.checkpoint";
  const std::string payload = "chains: 0.125 -3.5e-7 17 and some more state";
  write_checkpoint_file(file, kKind, "f00d", payload);
  const std::string good = slurp(file);
  for (std::size_t i = 0; i < good.size(); ++i) {
    std::string bad = good;
    bad[i] = static_cast<char>(bad[i] ^ 0x10);
    spit(file, bad);
    const auto r = read_checkpoint_file(file, kKind, "f00d");
    INFO("byte " << i << " flipped");
    CHECK(r.state != CheckpointState::kValid);
    CHECK_FALSE(r.why.empty());
  }
  for (std::size_t n = 0; n < good.size(); ++n) {
    spit(file, good.substr(0, n));
    INFO("cut to " << n << " bytes");
    CHECK(read_checkpoint_file(file, kKind, "f00d").state != CheckpointState::kValid);
  }
  spit(file, good + "x");
  CHECK(read_checkpoint_file(file, kKind, "f00d").state == CheckpointState::kCorrupt);
}
