#pragma once
// Each stage of one droplet's step on its own arrays: the entry points of the one-ring layout
// (OneRing, step_driver.hpp), which Simulation::step runs in the order of kStepStages. Each reads
// the droplets' shared model and changes the droplet's runtime. Private to the library.
#include <cstddef>

#include "droplet_model.hpp"
#include "droplet_runtime.hpp"

namespace softdrop {

/// Clears the forces to the weight m g.
void gravity_stage(const DropletModel& m, DropletRuntime& r);
/// Damped springs along the ring.
void springs_stage(const DropletModel& m, DropletRuntime& r);
/// The gas, P = nRT / S, P l_e on each edge's outward normal; measures the area S (r.area).
void pressure_stage(const DropletModel& m, DropletRuntime& r);
/// The shaken medium's inertial force on each mass, r.shake (the driver runs it only while
/// r.shake.on).
void vibration_stage(const DropletModel& m, DropletRuntime& r);
/// Grain and wall contacts (penalty and damping) and the touched set, mass i's force added to
/// fx[i * stride], fy[i * stride]. Right after the contact limit it adds the forces that stage
/// recorded (unless recorded_added: the caller has added them itself) and looks at the masses it
/// listed; otherwise it tests every mass against its record.
void collisions_stage(const DropletModel& m, DropletRuntime& r, double* fx, double* fy, std::ptrdiff_t stride,
                      bool recorded_added);
/// Internal viscosity relative to the rigid motion (the driver runs it only where nu > 0).
void viscosity_stage(const DropletModel& m, DropletRuntime& r);
/// Position Verlet.
void integrate_stage(const DropletModel& m, DropletRuntime& r);
/// The Provot length constraint, in the droplet's constraint order.
void constraint_stage(const DropletModel& m, DropletRuntime& r);
/// Inverse dynamics: no mass deeper than max_depth inside a grain; records the contacts (and the
/// forces of most) for the next collisions.
void contact_limit_stage(const DropletModel& m, DropletRuntime& r);

}  // namespace softdrop
