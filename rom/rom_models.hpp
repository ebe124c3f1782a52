#pragma once
// The models by name: calls f(Model{}) for the model `m` selects, so that the code choosing a model
// is written once (runs, batches, sensitivities).
#include "rom/rom11.hpp"
#include "rom/rom18.hpp"
#include "rom/rom24.hpp"
#include "rom/rom_run.hpp"

namespace terracal::rom {

template <class F>
void with_model(RomModel m, F&& f) {
  switch (m) {
    case RomModel::k11Dof:
      f(Rom11{});
      break;
    case RomModel::k18Dof:
      f(Rom18{});
      break;
    case RomModel::k24Dof:
      f(Rom24{});
      break;
  }
}

}  // namespace terracal::rom
