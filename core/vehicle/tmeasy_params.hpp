#pragma once
// TMeasy tire parameters from JSON, in three forms, each read strictly (every bad input is an
// InputError naming the file, the key, the value and what was expected):
//
//   ours:  {"type": "TMeasy", "unloaded_radius": m, "wheel_inertia": kg m^2, "vertical_stiffness": N/m,
//           "rolling_resistance": -, "nominal_load": N, "max_load": N, "longitudinal_stiffness": N/m,
//           "lateral_stiffness": N/m, "longitudinal_damping": N s/m, "lateral_damping": N s/m,
//           "rdyn_coefficient": [at Fzn, at 2 Fzn],
//           "longitudinal": {"df0": [N, N], "fm": [N, N], "sm": [-, -], "fs": [N, N], "ss": [-, -]},
//           "lateral": {the same}}
//   LFDM:  the tire files of uwsbel/low-fidelity-dynamic-models (wheeled_vehicle_models/18dof/data/
//          json/TMeasy.json): jw, rr, r0, pn, pnmax, cx, cy, kt, dx, dy, rdyncoPn, rdyncoP2n, dfx0Pn ...
//          sysP2n, told apart by their keys; "step", "fzRdynco" and "rdyncoCrit" are accepted and
//          ignored (tmeasy_params.cpp says why). A file with keys of both forms is refused.
//   guess: {"type": "TMeasy", "wheel_inertia": kg m^2, "guess": {"tire_size": "37x12.5R16.5" or
//          "255/50R19", "load_index": 121 or "max_load": N, "vehicle_type": "truck" | "passenger",
//          "tire_mass": kg, optional "inflation_pressure" and "rated_pressure": Pa (both or none)}}:
//          Chrono's engineer's guess (tmeasy_guess below).
#include <string>

#include <nlohmann/json.hpp>

#include "core/vehicle/tmeasy.hpp"

namespace terracal {

// `source` names the input in messages (a file's path).
TmeasyParams read_tmeasy(const nlohmann::json& j, const std::string& source);
TmeasyParams read_tmeasy_file(const std::string& path);

// The checks every parameter set passes, however it was built. Besides each value's range: at Fzn and
// at 2 Fzn each curve has 0 < sm < ss, 0 < fs <= fm and df0 >= 2 fm / sm; Rill's load interpolation
// keeps the curves positive, fs <= fm and 0 < sm < ss at every load from 0 to max_load;
// nominal_load < max_load and the tire is not pressed flat at max_load (max_load / kt < r0).
void validate(const TmeasyParams& p, const std::string& source);

// Our own form of p (type "TMeasy"), which read_tmeasy reads back to p.
nlohmann::json tmeasy_json(const TmeasyParams& p);

// A tire size: width [m], aspect ratio (section height / width) [-], rim diameter [m].
struct TireSize {
  double width = 0, aspect_ratio = 0, rim_diameter = 0;
};
// Metric "255/50R19" (width mm / ratio % construction rim inches; an optional P or LT in front, the
// construction one of R, ZR, D, B, -) or flotation "37x12.5R16.5" (overall diameter x width in inches,
// construction, rim inches; an optional LT at the end). Throws InputError naming `key` and the text.
TireSize parse_tire_size(const std::string& text, const std::string& where, const std::string& key = "tire_size");

// The largest load [N] of a tire's load index (ISO 4000-1 / ETRTO, 0 to 279: LI 121 = 1450 kg), with
// g = 9.81 m/s^2 as Chrono's ChTMeasyTire::GetTireMaxLoad. Throws InputError outside 0..279.
double tire_max_load(int load_index);

// Chrono's engineer's guess (ChTMeasyTire::GuessTruck80Par and GuessPassCar70Par): from the tire's
// largest load [N], size and mass [kg]. pressure_ratio is the inflation pressure in use over the one
// the load is rated at. The wheel's inertia is not guessed. The result passes validate().
TmeasyParams tmeasy_guess(double max_load, double width, double ratio, double rim_diameter, bool truck,
                          double tire_mass, double wheel_inertia, double pressure_ratio = 1.0);

}  // namespace terracal
