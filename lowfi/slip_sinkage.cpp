#include "lowfi/slip_sinkage.hpp"

#include <fmt/format.h>

#include "core/errors.hpp"
#include "core/text_check.hpp"

namespace terracal::lowfi {

SlipSinkage parse_slip_sinkage(const nlohmann::json& b, const std::string& where) {
  if (!b.is_object()) throw InputError(fmt::format("{}: 'Slip sinkage' must be an object", where));
  for (const auto& [key, value] : b.items())
    if (key != "Model" && key != "S")
      throw InputError(fmt::format("{}: unknown key 'Slip sinkage.{}' (expected Model, S)", where, key));
  if (b.contains("Model") && !(b["Model"].is_string() && b["Model"].get<std::string>() == "Lyasko"))
    throw InputError(fmt::format("{}: key 'Slip sinkage.Model': {} is not a model terracal has (expected \"Lyasko\")",
                                 where, excerpt(b["Model"].dump())));
  SlipSinkage s;
  if (b.contains("S")) {
    if (!b["S"].is_number())
      throw InputError(fmt::format("{}: key 'Slip sinkage.S': {} is not a number", where, excerpt(b["S"].dump())));
    s.S = b["S"].get<double>();
    if (!(s.S >= 0 && s.S <= 20))
      throw InputError(fmt::format("{}: key 'Slip sinkage.S' = {}: expected in [0, 20] (Lyasko's relation: 1.5)",
                                   where, s.S));
  }
  return s;
}

nlohmann::json slip_sinkage_json(const SlipSinkage& s) { return {{"Model", "Lyasko"}, {"S", s.S}}; }

}  // namespace terracal::lowfi
