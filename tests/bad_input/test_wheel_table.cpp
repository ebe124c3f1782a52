// Bad input to `terracal wheel-table` (the grid and the output file) and to the table's readers
// (`terracal rom --terrain-table`): exit 2 naming the option or file, nothing written.
#include "bad_input_suite.hpp"

using terracal::test::BadInput;
using terracal::test::InputFile;

namespace {

const std::string kTable = "wheel-table --scm {demo}/truth.json --wheel {dir}/wheel.json --duration 0.1 ";

std::vector<InputFile> files() {
  return {{"wheel.json", R"({"radius": 0.47, "width": 0.25, "mass": 108, "angular_velocity": 1.0})"},
          {"not_a_table.h5", "this is no HDF5 file"}};
}

BadInput table(const std::string& args, std::vector<std::string> phrases) {
  return {args, {}, kTable + args, std::move(phrases)};
}

}  // namespace

TEST_CASE("bad input, wheel-table: the grid and the output", "[cli][bad_input]") {
  const std::vector<BadInput> cases = {
      table("--loads 2000,1000 --out {out}/t.h5", {"--loads: values must increase; 1000 follows 2000"}),
      table("--loads 0,1000 --out {out}/t.h5", {"--loads: value 0 in the list '0,1000' is outside (0, 10000000] N"}),
      table("--loads 1000 --slips 0.2,0.1 --out {out}/t.h5", {"--slips: values must increase; 0.1 follows 0.2"}),
      table("--loads 1000 --slips -0.2,0 --out {out}/t.h5", {"--slips: needs a slip above zero (largest 0)"}),
      table("--loads 1000 --slips 0.1,0.2 --out {out}/t.h5", {"--slips: needs 0"}),
      table("--loads 1000 --slip-angles 0.1,0.2 --out {out}/t.h5",
            {"--slip-angles: with several angles the first must be 0 (got 0.1)"}),
      table("--loads 1000 --slip-angles 0,1 --out {out}/t.h5", {"--slip-angles: value 1 in the list '0,1' is outside"}),
      table("--loads 1000 --out {dir}", {"--out '{dir}': is a folder"}),
      {"no --scm", {}, "wheel-table --wheel {dir}/wheel.json --loads 1000 --out {out}/t.h5", {"--scm SCM.json"}},
      {"no --loads", {}, "wheel-table --scm {demo}/truth.json --wheel {dir}/wheel.json --out {out}/t.h5", {"--loads"}},
  };
  terracal::test::check_bad_inputs("bad_wheel_table", cases, files());
}

TEST_CASE("bad input, rom --terrain-table: a missing or broken table", "[cli][bad_input]") {
  const std::string rom = "rom --model 18dof --vehicle hmmwv --maneuver {dir}/m.json --out {out} --terrain-table ";
  const std::vector<InputFile> common = {
      {"m.json", R"({"type": "step_steer", "steering": 0.1, "step_time": 1, "initial_speed": 5, "end_time": 2})"},
      {"not_a_table.h5", "this is no HDF5 file"}};
  const std::vector<BadInput> cases = {
      {"no such table", {}, rom + "{dir}/none.h5", {"wheel table '{dir}/none.h5': cannot open it"}},
      {"not HDF5", {}, rom + "{dir}/not_a_table.h5", {"wheel table '{dir}/not_a_table.h5'"}},
  };
  terracal::test::check_bad_inputs("bad_rom_terrain_table", cases, common);
}
