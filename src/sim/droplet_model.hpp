#pragma once
// DropletModel: what every droplet of one set of parameters in one medium shares and nothing in a
// step changes: the parameters, the step's constants, the grain grid of the contact stages, the
// resting area and the start height. Built once, in one place (droplet_model.cpp), and read by
// every layout of the step. Private to the library (Simulation::model()).
#include <cstdint>
#include <memory>

#include "media/distance_field.hpp"
#include "media/grain_grid.hpp"
#include "softdrop/droplet.hpp"
#include "softdrop/medium.hpp"
#include "step_context.hpp"

namespace softdrop {

struct DropletModel {
  DropletParams params;
  const Medium& medium;  ///< outlives the model (Simulation's contract)
  StepContext context;   ///< the step's constants, from params
  GrainGrid grid;        ///< the medium's grains by cell, for the collisions and the contact limit
  /// An image medium's solid, which the contact stages read instead of the grains; null otherwise.
  std::shared_ptr<const DistanceField> field;
  /// The touched set's entries: the grains, or the image's solid parts.
  std::int32_t obstacles = 0;
  double area0 = 0;    ///< the droplet's resting area S0 (length^2)
  double start_y = 0;  ///< where place_above puts the centre: clear of the highest grain (length)
  /// Far above the rounding of any distance in the box (about 1e-15 of its size), far below any
  /// distance that matters: the contact limit's anchors keep this clear of every disc (length).
  double clearance_margin = 0;

  /// The model of droplets of parameters p in medium m. Throws std::invalid_argument, naming the
  /// parameter, for invalid parameters or medium, and for a grain narrower than the droplet's
  /// longest edge (a grain could slip between two masses).
  DropletModel(const DropletParams& p, const Medium& m);
};

}  // namespace softdrop
