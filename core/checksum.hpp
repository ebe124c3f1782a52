#pragma once
// FNV-1a (64 bit): a small, dependency-free hash for fingerprints (do two scenes or calibrations
// differ?) and checkpoint checksums (did the bytes change on disk?). It is not cryptographic: it
// catches accidents (a flipped bit, a truncated or foreign file), not deliberate forgery.
#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>

#include <fmt/format.h>

namespace terracal {

class Fnv1a64 {
 public:
  void add(const void* data, std::size_t size) {
    const auto* p = static_cast<const unsigned char*>(data);
    for (std::size_t i = 0; i < size; ++i) h_ = (h_ ^ p[i]) * 1099511628211ull;
  }
  void add(std::string_view bytes) { add(bytes.data(), bytes.size()); }
  std::uint64_t value() const { return h_; }
  std::string hex() const { return fmt::format("{:016x}", h_); }

 private:
  std::uint64_t h_ = 1469598103934665603ull;
};

inline std::string fnv1a64_hex(std::string_view bytes) {
  Fnv1a64 h;
  h.add(bytes);
  return h.hex();
}

}  // namespace terracal
