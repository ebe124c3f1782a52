#pragma once
// `--vary VARY.json`: per-parameter distributions for a batch of vehicles drawn around one base
// vehicle (docs/formats.md, "Vary file"). The file is one JSON object, a key per varied parameter:
//
//   {"mass":     {"distribution": "normal",    "mean": 2100, "sd": 50},
//    "friction": {"distribution": "uniform",   "low": 0.5,   "high": 1.0},
//    "tire_cornering_scale": {"distribution": "lognormal", "mu": 0, "sigma": 0.1}}
//
// Distributions: normal(mean, sd > 0); lognormal(mu, sigma > 0), value = exp(N(mu, sigma));
// uniform(low < high), drawn in the open interval (low, high). Parameters (units of the value):
//
//   mass                     sprung mass [kg]
//   cg_height                height of the sprung CG above ground [m]
//   cg_to_front              CG to front axle [m]; the wheelbase is kept: cg_to_rear = wheelbase - value
//   yaw_inertia              [kg m^2]
//   roll_inertia             sprung mass about its CG [kg m^2]
//   max_steer                road-wheel angle at steering = 1 [rad]
//   friction                 road friction relative to the tire data's [-] (scales fm and fs)
//   gravity                  [m/s^2]
//   drag_area                Cd A [m^2]
//   roll_stiffness_front     [N m/rad]          roll_stiffness_rear    [N m/rad]
//   roll_damping_front       [N m s/rad]        roll_damping_rear      [N m s/rad]
//   max_brake_torque         per wheel at braking = 1 [N m]
//   tire_cornering_scale     factor [-] on the lateral df0 at both loads of both axles' tires
//   tire_longitudinal_scale  factor [-] on the longitudinal df0 at both loads of both axles' tires
//   torque_scale             factor [-] on every y value of the engine's full-load torque map
//   tire_cornering_scale_front, tire_cornering_scale_rear
//                            factor [-] on the lateral df0 of one axle's tires
//   rolling_resistance       coefficient [-] of every tire (the vehicle needs the rolling_resistance effect)
//   roll_stiffness_total     front + rear roll stiffness [N m/rad], keeping the front share
//   roll_stiffness_front_share  front / (front + rear) roll stiffness [-], keeping the total
//                            (the pair a fit identifies better than front and rear: manoeuvres
//                            pin the sum more tightly than the split)
//
// Parameters that set the same values (roll_stiffness_total or _front_share with _front or _rear;
// tire_cornering_scale with its _front or _rear) are refused together: one would silently win.
//
// Each parameter has an allowed range (the vehicle reader's, vary_parameter_range); a drawn value
// outside it, or a drawn vehicle that fails rom::validate, is an InputError naming the parameter,
// the value and the vehicle index and asking for a narrower distribution: nothing is clipped or
// redrawn, so the batch is exactly the distribution the file asks for.
//
// Reproducibility: each parameter draws from its own stream Rng::for_stream(seed, k), k its index
// in vary_parameter_names() (a fixed catalogue order), and vehicle i takes the stream's i-th value.
// So a seed gives the same values whatever else the file varies, and the first m of n vehicles are
// the m vehicles drawn with n = m. Values are std::fma(sd, z, mean), exp(std::fma(sigma, z, mu)) and
// std::fma(high - low, u, low) with z = Rng::normal(), u = Rng::uniform(): explicit fused
// multiply-adds, so the same on every build whatever the compiler's contraction flags.
// Parameters are listed (VarySpec, VaryDraws) in sorted name order.
#include <cstdint>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "core/range.hpp"
#include "rom/rom_vehicle.hpp"

namespace terracal::rom {

enum class VaryDistribution { kNormal, kLognormal, kUniform };

struct VaryParameter {
  std::string name;  // one of vary_parameter_names()
  VaryDistribution distribution = VaryDistribution::kNormal;
  double a = 0;  // normal: mean; lognormal: mu; uniform: low
  double b = 0;  // normal: sd;   lognormal: sigma; uniform: high
};

struct VarySpec {
  std::string source;                     // the file (for messages)
  std::vector<VaryParameter> parameters;  // sorted by name, at least one
};

// Throws InputError (file, key path, value, what was expected) for an unreadable file, an unknown
// parameter, distribution or key, a missing key, sd/sigma <= 0, low >= high, or uniform bounds
// outside the parameter's allowed range.
VarySpec read_vary(const std::string& path);
VarySpec vary_from_json(const nlohmann::json& j, const std::string& source);

// The parameters in catalogue order (their stream numbers), their units and allowed values.
const std::vector<std::string>& vary_parameter_names();
std::string vary_parameter_unit(const std::string& name);  // "kg", "m", "-", ...
Range vary_parameter_range(const std::string& name);
// "normal(mean 2100, sd 50)": how the distribution is shown in messages and in batch.h5.
std::string vary_distribution_text(const VaryParameter& p);

struct VaryDraws {
  std::vector<std::string> names;           // the varied parameters, as in VarySpec
  std::vector<std::vector<double>> values;  // [parameter][vehicle], the drawn values
  std::vector<RomVehicle> vehicles;         // [vehicle]: the base with the drawn values applied
  std::vector<std::string> units;           // [parameter]
  std::vector<std::string> distributions;   // [parameter], vary_distribution_text
};

// Default memory limit for the drawn vehicles: 8 GiB (sizeof(RomVehicle) is 3072 bytes today: ~2.8
// million vehicles).
inline constexpr std::uint64_t kVaryDefaultMaxBytes = std::uint64_t{8} << 30;

// n vehicles drawn from `spec` around `base`. Throws InputError when n < 1, when
// n * sizeof(RomVehicle) exceeds max_bytes (the values add 8 bytes per parameter and vehicle on
// top), or when a draw leaves a value outside its range or a vehicle that fails validate (the
// lowest such vehicle index is reported). The vehicles are built in parallel (OpenMP); the result
// does not depend on the thread count.
VaryDraws draw_vehicles(const RomVehicle& base, const VarySpec& spec, long n, std::uint64_t seed,
                        std::uint64_t max_bytes = kVaryDefaultMaxBytes);

// "" when no two of `names` set the same vehicle values; otherwise why they cannot go together.
std::string overlapping_parameters(const std::vector<std::string>& names);

// Sets one parameter of v to `value` (a scale multiplies the base's values): what draw_vehicles
// applies per vehicle. Throws InputError for an unknown name.
void apply_vary_parameter(RomVehicle& v, const RomVehicle& base, const std::string& name, double value);

// The smallest value of a tire scale (tire_cornering_scale[_front|_rear], tire_longitudinal_scale)
// that leaves every curve it scales valid (df0 >= 2 fm / sm, the tire check): below it the vehicle
// fails its checks. 0 for any other parameter.
double smallest_valid_value(const RomVehicle& base, const std::string& name);

}  // namespace terracal::rom
