#include "virtual_bevameter/rig_checks.hpp"

#include <cmath>

#include <fmt/format.h>

#include "core/errors.hpp"

namespace terracal::rigs {

void check_range(const std::string& key, double value, double lo, double hi, const std::string& unit) {
  if (!(value >= lo && value <= hi))
    throw InputError(fmt::format("{} = {}: expected in [{}, {}] {}", key, value, lo, hi, unit));
}

void check_fits(const TerrainSite& site, const RigidBody& body, double reach_x, double reach_y, double travel_x) {
  const Vec3<double> c = site.centre();
  const double need_x = std::abs(body.position.x - c.x) + std::abs(travel_x) + 2 * reach_x;
  const double need_y = std::abs(body.position.y - c.y) + 2 * reach_y;
  if (need_x > site.half_length() || need_y > site.half_width())
    throw InputError(
        fmt::format("{} on {}: needs {:.3g} m x {:.3g} m of soil on each side of the centre (its reach and one reach "
                    "of undisturbed soil), the bin offers {:.3g} m x {:.3g} m; enlarge the bin or shrink the test",
                    body.name, site.name(), need_x, need_y, site.half_length(), site.half_width()));
}

}  // namespace terracal::rigs
