#include "core/checkpoint_file.hpp"

#include <charconv>
#include <fstream>
#include <iterator>
#include <sstream>

#include <fmt/format.h>

#include "core/atomic_file.hpp"
#include "core/checksum.hpp"

namespace terracal {
namespace {

// The file: one header line of text, then exactly `size` bytes of payload.
//   terracal-checkpoint FORMAT VERSION FINGERPRINT SIZE CHECKSUM\n
// CHECKSUM covers the header's other fields and the payload, so a flipped byte anywhere shows.
constexpr std::string_view kMagic = "terracal-checkpoint";

std::string checksum(const std::string& format, int version, std::string_view fingerprint, std::string_view payload) {
  Fnv1a64 h;
  h.add(fmt::format("{} {} {} {}\n", format, version, fingerprint, payload.size()));
  h.add(payload);
  return h.hex();
}

struct Header {
  std::string magic, format, fingerprint, sum;
  int version = 0;
  std::size_t size = 0;
};

bool parse_header(const std::string& line, Header& h) {
  std::istringstream is(line);
  std::string version, size;
  if (!(is >> h.magic >> h.format >> version >> h.fingerprint >> size >> h.sum)) return false;
  const auto v = std::from_chars(version.data(), version.data() + version.size(), h.version);
  const auto s = std::from_chars(size.data(), size.data() + size.size(), h.size);
  std::string rest;
  return v.ec == std::errc() && s.ec == std::errc() && !(is >> rest);
}

CheckpointRead fail(CheckpointState state, std::string why) { return {state, {}, std::move(why)}; }

}  // namespace

void write_checkpoint_file(const std::string& path, const CheckpointKind& kind, std::string_view fingerprint,
                           std::string_view payload) {
  std::string bytes = fmt::format("{} {} {} {} {} {}\n", kMagic, kind.format, kind.version, fingerprint, payload.size(),
                                  checksum(kind.format, kind.version, fingerprint, payload));
  bytes += payload;
  write_text_atomically(path, bytes);
}

CheckpointRead read_checkpoint_file(const std::string& path, const CheckpointKind& kind, std::string_view fingerprint) {
  std::ifstream in(path, std::ios::binary);
  if (!in) return {};
  const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const auto eol = bytes.find('\n');
  Header h;
  if (eol == std::string::npos || eol > 512 || !parse_header(bytes.substr(0, eol), h) || h.magic != kMagic)
    return fail(CheckpointState::kForeign, "not a terracal checkpoint (unrecognised header)");
  const std::string_view payload = std::string_view(bytes).substr(eol + 1);
  if (payload.size() != h.size)
    return fail(CheckpointState::kCorrupt,
                fmt::format("{} bytes of payload where the header announces {} (cut off?)", payload.size(), h.size));
  if (checksum(h.format, h.version, h.fingerprint, payload) != h.sum)
    return fail(CheckpointState::kCorrupt, "checksum mismatch: the file changed after it was written");
  if (h.format != kind.format)
    return fail(CheckpointState::kForeign, fmt::format("a '{}' checkpoint, expected '{}'", h.format, kind.format));
  if (h.version != kind.version)
    return fail(CheckpointState::kForeign,
                fmt::format("format version {}, this terracal reads version {}", h.version, kind.version));
  if (h.fingerprint != fingerprint)
    return fail(CheckpointState::kForeign, "written for other inputs or options (fingerprint " + h.fingerprint +
                                               ", this run " + std::string(fingerprint) + ")");
  return {CheckpointState::kValid, std::string(payload), {}};
}

}  // namespace terracal
