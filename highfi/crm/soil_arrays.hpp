#pragma once
// The soil particles' storage, shared by both backends: a structure of arrays of 16-byte Vec4
// records, so that a neighbour's field is one 128-bit load on the GPU, and one more array per
// named effect that keeps a record per particle (CrmEffect::kRecord).
#include "highfi/crm/effects/crm_effects.hpp"
#include "highfi/crm/sph_fields.hpp"

namespace terracal {

template <typename T>
struct SoilArrays {
  Vec4<T>* pos = nullptr;  // x, y, z, density
  Vec4<T>* vel = nullptr;  // vx, vy, vz, status (ParticleStatus)
  Vec4<T>* s0 = nullptr;   // sigma xx, yy, zz, xy (Cauchy stress, compression negative)
  Vec4<T>* s1 = nullptr;   // sigma xz, yz, accumulated plastic shear strain, kernel support (Shepard sum)
  // The effects' records by slot (kRecordSlot<E>); null where the effect is off.
  Vec4<T>* record[kCrmRecordSlots] = {};
};

}  // namespace terracal
