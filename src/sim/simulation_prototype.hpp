#pragma once
// One droplet in one medium, made once on first use from any thread, whose copies share its model
// (parameters, the step's constants, the grain grid): what a batch of droplets in one medium runs,
// instead of each droplet building the same model again. Private to the library.
#include <memory>
#include <mutex>
#include <optional>

#include "softdrop/simulation.hpp"

namespace softdrop {

class SimulationPrototype {
 public:
  /// A new droplet of `params` in `medium` (the same every call: the first call's), sharing the
  /// first's model. Throws as Simulation's constructor does, on every call.
  std::unique_ptr<Simulation> copy(const DropletParams& params, const Medium& medium) {
    std::call_once(made_, [&] { first_.emplace(params, medium); });
    return std::make_unique<Simulation>(*first_);
  }

 private:
  std::once_flag made_;
  std::optional<Simulation> first_;
};

}  // namespace softdrop
