#pragma once
// The registry of CRM effects: every effect a scene may name, in the order their terms apply. A new
// effect is one file beside these (crm_effect.hpp says what it holds) and one entry here.
#include "core/effect_list.hpp"
#include "highfi/crm/effects/active_domain.hpp"
#include "highfi/crm/effects/artificial_viscosity.hpp"
#include "highfi/crm/effects/cohesion.hpp"
#include "highfi/crm/effects/hourglass_damping.hpp"
#include "highfi/crm/effects/hourglass_stiffness.hpp"
#include "highfi/crm/effects/shifting.hpp"

namespace terracal {

using CrmEffects =
    EffectList<Cohesion, ArtificialViscosity, Shifting, ActiveDomain, HourglassDamping, HourglassStiffness>;
using CrmEffectSet = EffectSet<CrmEffects>;

// Which effects the engine compiles into each pass (core/effect_list.hpp, with_named).
template <class E>
struct InSoilLoop : std::bool_constant<E::kInLoop> {};
template <class E>
struct InMarkerLoop : std::bool_constant<E::kInMarkerLoop> {};

// Every effect's constants in the precision T of the particle state (the defaults of an effect
// that is off, which no code reads).
template <class T>
struct EffectConstantsIn {
  template <class E>
  using of = typename E::template Constants<T>;
};
template <class T>
using CrmEffectConstants = PerEffect<EffectConstantsIn<T>::template of, CrmEffects>;

// The effects' own sums over a particle's neighbours, and over a marker's.
template <class T>
struct EffectSumsIn {
  template <class E>
  using of = typename E::template Sums<T>;
  template <class E>
  using marker = typename E::template MarkerSums<T>;
};

// Per-particle records: effects with kRecord get a slot each, in registry order.
template <class L>
struct RecordSlots;
template <class... E>
struct RecordSlots<EffectList<E...>> {
  static constexpr int kCount = (int(E::kRecord) + ... + 0);
};
constexpr int kCrmRecordCount = RecordSlots<CrmEffects>::kCount;
// At least one slot, so that the arrays that hold them are never empty.
constexpr int kCrmRecordSlots = kCrmRecordCount > 0 ? kCrmRecordCount : 1;

// The record slot of effect X (its rank among the effects with records), or -1 when it keeps none.
template <class X, class L = CrmEffects>
struct RecordSlotOf;
template <class X>
struct RecordSlotOf<X, EffectList<>> : std::integral_constant<int, -1> {};
template <class X, class H, class... R>
struct RecordSlotOf<X, EffectList<H, R...>>
    : std::integral_constant<int, std::is_same_v<X, H>
                                      ? (H::kRecord ? 0 : -1)
                                      : (RecordSlotOf<X, EffectList<R...>>::value < 0
                                             ? -1
                                             : int(H::kRecord) + RecordSlotOf<X, EffectList<R...>>::value)> {};
template <class X>
constexpr int kRecordSlot = RecordSlotOf<X>::value;

}  // namespace terracal
