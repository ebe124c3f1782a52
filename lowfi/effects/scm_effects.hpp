#pragma once
// The registry of SCM effects: every effect an SCM terrain may name, in the order their hooks run. A
// new effect is one file beside these (scm_effect.hpp says what it holds) and one entry here.
#include "core/effect_settings.hpp"
#include "lowfi/effects/scm_bulldozing.hpp"
#include "lowfi/effects/scm_damping.hpp"
#include "lowfi/effects/scm_elastic_unloading.hpp"
#include "lowfi/effects/scm_slip_sinkage.hpp"

namespace terracal::lowfi {

using ScmEffects = EffectList<ScmElasticUnloading, ScmDamping, ScmBulldozing, ScmSlipSinkage>;
using ScmEffectChoice = EffectChoice<ScmEffects>;

}  // namespace terracal::lowfi
