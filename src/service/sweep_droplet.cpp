// One droplet of a stored sweep (sweep_droplet.hpp).
#include "service/sweep_droplet.hpp"

#include <algorithm>
#include <stdexcept>

#include "store/params_json.hpp"

namespace softdrop {

StoredSweepDroplet stored_sweep_droplet(SweepStore& store, const std::string& db, std::int64_t sweep,
                                        int porosity_index, int medium_index, int droplet) {
  StoredSweepDroplet out;
  out.sweep = sweep;
  out.options = sweep_params_from_json(store.sweep(sweep).params);
  if (out.options.second)
    throw std::invalid_argument(
        "sweep = " + std::to_string(sweep) +
        ": a sweep of pairs; a pair's first droplet is not run alone (simulate_pair runs a pair)");
  const auto in_range = [](const char* name, int value, std::size_t size) {
    if (value < 0 || static_cast<std::size_t>(value) >= size)
      throw std::invalid_argument(std::string(name) + " = " + std::to_string(value) + ": must be in [0, " +
                                  std::to_string(size) + ")");
  };
  in_range("porosity_index", porosity_index, out.options.porosities.size());
  in_range("medium_index", medium_index, static_cast<std::size_t>(out.options.media));
  in_range("droplet", droplet, static_cast<std::size_t>(out.options.droplets));
  const SweepUnit unit{porosity_index, medium_index};
  if (const std::optional<SweepMedium> m = store.medium(sweep, unit)) {
    out.medium = sweep_medium_options(out.options, unit);
    if (out.medium.seed != m->medium_seed)  // the stored parameters would not give this medium again
      throw DatabaseError("'" + db + "': sweep " + std::to_string(sweep) + "'s medium " +
                          std::to_string(porosity_index) + ":" + std::to_string(medium_index) +
                          " has a seed its parameters do not derive");
    const auto found = std::find_if(m->droplets.begin(), m->droplets.end(),
                                    [&](const SweepDroplet& d) { return d.droplet == droplet; });
    if (found == m->droplets.end())
      throw DatabaseError("'" + db + "': a stored medium lacks droplet " + std::to_string(droplet));
    out.porosity = m->porosity;
    out.droplet = *found;
    return out;
  }
  throw std::invalid_argument("medium_index = " + std::to_string(medium_index) + ": sweep " + std::to_string(sweep) +
                              " has not stored medium " + std::to_string(medium_index) + " of porosity_index " +
                              std::to_string(porosity_index) + " (yet)");
}

}  // namespace softdrop
