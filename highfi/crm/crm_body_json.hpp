#pragma once
// Reading the bodies of a CRM scene (docs/crm_scene.md, `bodies[]`).
#include <filesystem>
#include <vector>

#include "core/json_object.hpp"
#include "core/rigid_body.hpp"

namespace terracal {

// The scene's "bodies" array (none when absent); mesh files are found relative to `base`.
std::vector<RigidBody> parse_crm_bodies(JsonObject& scene, const std::filesystem::path& base);

}  // namespace terracal
