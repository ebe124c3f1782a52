#pragma once
// Reads the "Soil parameters" block of a Chrono SCM JSON file (docs/formats.md) -- the
// block terracal writes -- into a parameter vector.
#include <string>

#include "bayes/scm_parameters.hpp"

namespace terracal::bayes {

// Throws InputError naming the file and the missing or non-numeric key.
ParamVector read_scm_soil_parameters(const std::string& path);

}  // namespace terracal::bayes
