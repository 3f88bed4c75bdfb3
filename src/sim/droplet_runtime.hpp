#pragma once
// DropletRuntime: one droplet's own state between steps: its masses, what the last step measured,
// the grains it touched, the contact limit's records for the next step, and its slot in the
// lane-by-lane block that stepped it last. Private to the library (Simulation::runtime()).
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "contact_cache.hpp"
#include "softdrop/droplet.hpp"

namespace softdrop {

// Where the lane-by-lane block (lane_block_step.cpp) left a droplet: the block's id and the lane,
// and the centre of mass it computed. A droplet still in that lane with `id` unchanged need not be
// copied into the block again; every other writer of the state clears `id`.
struct BlockSlot {
  std::uint64_t id = 0;  ///< 0: not as a block's step left it
  int lane = 0;
  std::uint64_t centre_id = 0;  ///< the block step whose centre of mass (cx, cy) is
  double cx = 0, cy = 0;
};

// The shaken medium's inertial force on each mass for the next step (the vibration stage), set
// by the run between steps. A force per mass, all equal, so that a block of droplets adds each
// lane's as it adds the contact limit's records (the same additions as one ring's).
struct ShakeForce {
  bool on = false;  ///< the medium shakes: the vibration stage adds fx, fy
  std::vector<double> fx, fy;

  /// On, with the force on each of n masses of parameters p, t time units after the shaking began.
  void set(const DropletParams& p, int n, double t) {
    double ax = 0, ay = 0;
    p.vibration_acceleration(t, &ax, &ay);
    on = true;
    fx.assign(static_cast<std::size_t>(n), p.mass * ax);
    fy.assign(static_cast<std::size_t>(n), p.mass * ay);
  }
};

struct DropletRuntime {
  DropletState state;
  double area = 0;                    ///< the ring's area as the pressure stage measured it (length^2)
  double last_penetration = 0;        ///< the deepest a mass went into a grain in the last collisions
  std::vector<std::uint8_t> touched;  ///< per grain of the medium, and one more entry for no grain
  std::vector<double> spring_force;   ///< the spring stage's scratch: four arrays of one per spring
  ContactCache contact;               ///< the contact limit's records, for the next step
  BlockSlot block;
  ShakeForce shake;

  /// The step's validity test of the state it left: the area the pressure stage measured is finite
  /// and positive.
  bool valid() const { return std::isfinite(area) && area > 0; }
  /// Something other than a stage moved a mass: no record or block slot describes the state.
  void changed() {
    block.id = 0;
    contact.current = false;
  }
};

}  // namespace softdrop
