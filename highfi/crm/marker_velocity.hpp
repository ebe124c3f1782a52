#pragma once

namespace terracal {

// How a boundary marker's velocity is extrapolated from the soil.
// - kMirror: Adami's 2 v_wall - v~, with v~ the Shepard average of the soil around the marker
//   (docs/architecture.md, "CRM"). That average sits about one spacing into the soil whatever the
//   marker's depth, so the first marker layer over-extrapolates and the deeper ones under-extrapolate.
// - kMirrorImage: 2 v_wall - v(x*), with v(x*) the Shepard average at the marker's mirror image
//   x* = x_m + 2 a n across the wall (a: the marker's depth, n: the wall's normal). A linear velocity
//   field is then mirrored about the wall's velocity at every depth. Where the image has little soil
//   around it (rims, corners) it blends into kMirror (results/plate_bin_check, ninth study).
// - kWall: the wall's own velocity. Quiets the soil layer on a pushed plate but is not a consistent
//   extrapolation: plate forces no longer converge with spacing, and the walls damp the bed's
//   elastic waves less (results/plate_bin_check, eighth study).
// - kMirrorContact: Adami's mirror where soil touches the wall, the soil's own (Shepard) velocity
//   where a gap separates them, so that a wall does not strain soil it has not reached yet. A held
//   plate keeps more of its force, but the plate force no longer converges with spacing
//   (results/plate_bin_check, ninth study).
enum class MarkerVelocity { kMirror, kMirrorImage, kWall, kMirrorContact };

// Whether the rule needs each marker's wall normal (MarkerArrays::normal).
inline constexpr bool needs_wall_normals(MarkerVelocity v) {
  return v == MarkerVelocity::kMirrorImage || v == MarkerVelocity::kMirrorContact;
}

}  // namespace terracal
