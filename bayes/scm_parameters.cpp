#include "bayes/scm_parameters.hpp"

namespace terracal::bayes {

int param_index(std::string_view short_or_chrono_name) {
  for (int i = 0; i < kNumParams; ++i)
    if (kShortNames[i] == short_or_chrono_name || kChronoNames[i] == short_or_chrono_name) return i;
  return -1;
}

}  // namespace terracal::bayes
