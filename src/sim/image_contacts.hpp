#pragma once
// The contact stages of a droplet in an image medium: the collisions and the contact limit of
// ring_stages.hpp, against the solid of a signed distance field instead of grains, by the same
// rules (a penalty k_c depth with damping c_c of the normal velocity, never pulling; no mass deeper
// than max_depth, an inelastic stop). collisions_stage and contact_limit_stage hand over to them,
// so every layout of the step runs them. Private to the library.
#include <cstddef>

#include "droplet_model.hpp"
#include "droplet_runtime.hpp"

namespace softdrop {

/// Solid and wall contacts of every mass, added to fx[i * stride], fy[i * stride]; the touched
/// set holds the solid parts touched.
void image_collisions(const DropletModel& m, DropletRuntime& r, double* fx, double* fy, std::ptrdiff_t stride);
/// No mass deeper than max_depth inside the solid: one deeper moves out along the field's normal
/// to that depth and loses the normal velocity that carried it in. Leaves no records.
void image_contact_limit(const DropletModel& m, DropletRuntime& r);

}  // namespace softdrop
