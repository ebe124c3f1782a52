#include "core/rng.hpp"

#include <random>
#include <stdexcept>
#include <utility>

#include <gsl/gsl_randist.h>

namespace terracal {

Rng::Rng(std::uint64_t seed) : r_(gsl_rng_alloc(gsl_rng_mt19937)) {
  // gsl_rng_set takes an unsigned long; fold 64 bits so that high seed bits matter.
  gsl_rng_set(r_, static_cast<unsigned long>(seed ^ (seed >> 32)));
}

Rng Rng::for_stream(std::uint64_t seed, std::uint64_t stream) {
  // seed_seq mixes (seed, stream) so that neighbouring streams are not correlated.
  std::seed_seq seq{static_cast<std::uint32_t>(seed), static_cast<std::uint32_t>(seed >> 32),
                    static_cast<std::uint32_t>(stream), static_cast<std::uint32_t>(stream >> 32), 0x7e77aca1u};
  std::uint32_t out[2];
  seq.generate(out, out + 2);
  return Rng((static_cast<std::uint64_t>(out[0]) << 32) | out[1]);
}

Rng::Rng(const Rng& other) : r_(gsl_rng_clone(other.r_)) {}
Rng& Rng::operator=(const Rng& other) {
  if (this != &other) gsl_rng_memcpy(r_, other.r_);
  return *this;
}
Rng::Rng(Rng&& other) noexcept : r_(std::exchange(other.r_, nullptr)) {}
Rng& Rng::operator=(Rng&& other) noexcept {
  std::swap(r_, other.r_);
  return *this;
}
Rng::~Rng() {
  if (r_) gsl_rng_free(r_);
}

double Rng::uniform() { return gsl_rng_uniform_pos(r_); }
double Rng::normal() { return gsl_ran_gaussian_ziggurat(r_, 1.0); }
double Rng::gamma(double shape) { return gsl_ran_gamma(r_, shape, 1.0); }
std::uint64_t Rng::below(std::uint64_t n) { return gsl_rng_uniform_int(r_, static_cast<unsigned long>(n)); }

std::string Rng::state() const {
  static const char* hex = "0123456789abcdef";
  const auto* bytes = static_cast<const unsigned char*>(gsl_rng_state(r_));
  const std::size_t n = gsl_rng_size(r_);
  std::string s(2 * n, '0');
  for (std::size_t i = 0; i < n; ++i) {
    s[2 * i] = hex[bytes[i] >> 4];
    s[2 * i + 1] = hex[bytes[i] & 15];
  }
  return s;
}

void Rng::set_state(const std::string& s) {
  const std::size_t n = gsl_rng_size(r_);
  if (s.size() != 2 * n) throw std::invalid_argument("Rng::set_state: state string has the wrong size");
  auto* bytes = static_cast<unsigned char*>(gsl_rng_state(r_));
  auto nibble = [](char c) -> unsigned {
    if (c >= '0' && c <= '9') return c - '0';
    if (c >= 'a' && c <= 'f') return c - 'a' + 10;
    throw std::invalid_argument("Rng::set_state: state string is not hex");
  };
  for (std::size_t i = 0; i < n; ++i)
    bytes[i] = static_cast<unsigned char>(nibble(s[2 * i]) << 4 | nibble(s[2 * i + 1]));
}

}  // namespace terracal
