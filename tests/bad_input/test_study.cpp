// Bad study commands and specs: exit 2 naming the key, nothing started (no study folder).
#include "bad_input_suite.hpp"

using terracal::test::BadInput;

namespace {

BadInput spec(const std::string& what, const std::string& study, const std::string& solver, const std::string& body,
              std::vector<std::string> phrases) {
  return {what, {{"spec.json", "{" + body + "}"}},
          "study " + study + " --solver " + solver + " --spec {dir}/spec.json --out {out}", std::move(phrases)};
}

}  // namespace

TEST_CASE("bad input, study: commands and specs", "[cli][bad_input][study]") {
  const std::vector<BadInput> cases = {
      {"an unknown study", {}, "study accuracy --solver scm --out {out}", {"study 'accuracy'", "accuracy-cost"}},
      {"an unknown solver", {}, "study stability --solver sph --out {out}", {"--solver sph", "rom or vehicle"}},
      {"the full vehicle has no effects to switch", {}, "study effects --solver vehicle --out {out}",
       {"vehicle solver has no effects"}},
      spec("a soil's stiffness for a vehicle on rigid ground", "stability", "rom", R"("sweeps": {"stiffness": [0.1]})",
           {"key 'sweeps.stiffness'", "rigid ground"}),
      spec("a gravity for the full vehicle", "stability", "vehicle", R"("sweeps": {"gravity": [1.62]})",
           {"key 'sweeps.gravity'", "Earth's gravity only"}),
      spec("an unknown ROM effect", "effects", "rom", R"("effects": {"x": {"vehicle-effects": ["roll", "wings"]}})",
           {"key 'effects.x.vehicle-effects'", "unknown effect \"wings\""}),
      spec("a ROM option the rom command refuses", "accuracy-cost", "rom", R"("knobs": {"model": ["30dof"]})",
           {"knobs.model[0]", "30dof"}),
      spec("a wheel key for the rom solver", "accuracy-cost", "rom", R"("wheel": {"radius": 0.4})",
           {"unknown key 'wheel'"}),
      {"Wong-Reece has no effects", {}, "study effects --solver wong-reece --out {out}",
       {"wong-reece solver has no effects"}},
      spec("an unknown key", "stability", "scm", R"("sweep": {"step": [0.001]})", {"unknown key 'sweep'"}),
      spec("a knob the wheel command does not take", "accuracy-cost", "scm", R"("knobs": {"gird": [0.02, 0.01]})",
           {"key 'knobs.gird'", "has no option --gird"}),
      spec("a knob value the wheel command refuses", "accuracy-cost", "scm", R"("knobs": {"grid": [5, 0.01]})",
           {"knobs.grid[0]", "refused by terracal wheel --grid"}),
      spec("an empty knob list", "accuracy-cost", "scm", R"("knobs": {"grid": []})",
           {"key 'knobs.grid'", "non-empty list"}),
      spec("a value given twice", "stability", "scm", R"("sweeps": {"slip": [0.2, 0.2]})",
           {"key 'sweeps.slip[1]'", "appears twice"}),
      spec("a gravity out of range", "stability", "scm", R"("sweeps": {"gravity": [0]})",
           {"key 'sweeps.gravity'", "(0, 100]"}),
      spec("a negative stiffness factor", "stability", "scm", R"("sweeps": {"stiffness": [-1]})",
           {"key 'sweeps.stiffness'", "must be positive"}),
      spec("a slip out of range", "stability", "scm", R"("sweeps": {"slip": [1.5]})",
           {"sweeps.slip", "refused by terracal wheel --slips"}),
      spec("an option the study sets", "effects", "scm", R"("options": {"terrain": "crm"})",
           {"key 'options.terrain'", "set by terracal itself"}),
      spec("an effect variant of no options", "effects", "scm", R"("effects": {"off": {}})",
           {"key 'effects.off'", "expected an object of options"}),
      spec("a bad effect option", "effects", "scm", R"("effects": {"off": {"scm-effects": "bulldozer"}})",
           {"effects.off.scm-effects", "bulldozer"}),
      spec("a missing wheel file", "effects", "scm", R"("wheel": "nowhere.json")", {"key 'wheel'", "not found"}),
      spec("a wheel with a bad value", "effects", "scm", R"("wheel": {"radius": -1, "width": 0.25, "mass": 108})",
           {"key 'wheel'", "radius"}),
      spec("an SCM soil without its parameters", "stability", "scm", R"("soil": {"Bekker Kphi": 1e6})",
           {"key 'soil'", "Soil parameters"}),
      spec("a drop on the steady Wong-Reece model", "stability", "wong-reece", R"("sweeps": {"drop-height": [0.1]})",
           {"key 'sweeps.drop-height'", "steady model"}),
      spec("a rig for the ROM", "accuracy-cost", "rom", R"("rig": "bevameter")", {"key 'rig'", "no rig of the rom"}),
      spec("an unknown rig", "accuracy-cost", "scm", R"("rig": "drum")", {"key 'rig'", "\"drum\""}),
      spec("the stability study on the bevameter", "stability", "scm", R"("rig": "bevameter")",
           {"key 'rig'", "stability study runs the wheel rig"}),
      spec("a wheel for the bevameter", "accuracy-cost", "scm", R"("rig": "bevameter", "wheel": {"radius": 0.4})",
           {"unknown key 'wheel'"}),
      spec("a knob value of nested options", "accuracy-cost", "rom",
           R"("knobs": {"fast": [{"integrator": {"name": "cvodes"}}]})",
           {"key 'knobs.fast[0]'", "object of options"}),
      spec("a knob named with a space", "accuracy-cost", "rom", R"("knobs": {"24dof cvodes": [{"rtol": 1e-4}]})",
           {"key 'knobs.24dof cvodes'", "names folders"}),
      spec("an option the rom command lacks in a knob's object", "accuracy-cost", "rom",
           R"("knobs": {"fast": [{"rtoll": 1e-4}]})", {"knobs.fast[0]", "--rtoll"}),
      spec("a CRM soil with a misspelt key", "stability", "crm", R"("soil": {"densty": 1700})",
           {"key 'soil", "density", "missing"}),
  };
  terracal::test::check_bad_inputs("bad_study", cases);
}
