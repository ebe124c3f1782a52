#pragma once
// Seeded random numbers whose full state can be saved in a checkpoint and restored exactly.
// Engine and distributions are GSL's (gsl_rng_mt19937, gsl_ran_*): none of them caches values
// outside the engine state, so saving the engine's bytes captures the whole generator.
#include <cstdint>
#include <string>

#include <gsl/gsl_rng.h>

namespace terracal {

class Rng {
 public:
  explicit Rng(std::uint64_t seed = 0);
  // Independent, reproducible stream `stream` derived from one user seed (one per MCMC chain).
  static Rng for_stream(std::uint64_t seed, std::uint64_t stream);

  Rng(const Rng& other);
  Rng& operator=(const Rng& other);
  Rng(Rng&& other) noexcept;
  Rng& operator=(Rng&& other) noexcept;
  ~Rng();

  double uniform();                      // in (0, 1): log(uniform()) is always finite
  double normal();                       // standard normal
  double gamma(double shape);            // Gamma(shape, scale 1)
  std::uint64_t below(std::uint64_t n);  // integer uniform in [0, n)

  // Engine state as a hex string, and back; set_state rejects a string of the wrong size.
  std::string state() const;
  void set_state(const std::string& hex);

 private:
  gsl_rng* r_ = nullptr;
};

}  // namespace terracal
