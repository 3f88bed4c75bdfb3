// A sweep unit's record as bytes: fixed-size fields copied as they are in memory, then the
// droplets. Only for processes of one job, so no byte-order or version handling.
#include "sweep_record_bytes.hpp"

#include <cstdint>
#include <cstring>
#include <stdexcept>
#include <string>
#include <type_traits>

#include "softdrop/sweep.hpp"
#include "util/byte_codec.hpp"

namespace softdrop {
namespace {

using Writer = detail::ByteWriter;

constexpr std::uint32_t kMagic = 0x53445752;  // "SDWR"

void put_droplet(Writer& w, const SweepDroplet& d) {
  w.put(d.droplet), w.put(d.start_x), w.put(static_cast<std::int32_t>(d.outcome)), w.put(d.tortuosity);
  w.put(d.steps), w.put(d.shaken_at), w.put(d.route_tortuosity);
}

void read_droplet(detail::ByteReader& r, SweepDroplet& d) {
  d.droplet = r.get<int>(), d.start_x = r.get<double>();
  const auto outcome = r.get<std::int32_t>();
  if (outcome < 0 || outcome > static_cast<std::int32_t>(Outcome::diverged)) r.fail("bad outcome");
  d.outcome = static_cast<Outcome>(outcome);
  d.tortuosity = r.get<double>(), d.steps = r.get<std::int64_t>();
  d.shaken_at = r.get<double>(), d.route_tortuosity = r.get<double>();
}

}  // namespace

std::string encode_sweep_medium(const SweepMedium& m) {
  Writer w;
  w.put(kMagic);
  w.put(m.unit.porosity), w.put(m.unit.medium);
  w.put(m.target_porosity), w.put(m.porosity), w.put(m.grains), w.put(m.medium_seed);
  w.put(m.passed), w.put(m.stuck), w.put(m.timeout), w.put(m.diverged);
  w.put(m.mean_t), w.put(m.standard_error), w.put(m.stuck_fraction), w.put(m.seconds);
  w.put<std::uint64_t>(m.droplets.size());
  for (const SweepDroplet& d : m.droplets) put_droplet(w, d);
  w.put<std::uint64_t>(m.second_droplets.size());
  for (const SweepSecond& s : m.second_droplets) {
    put_droplet(w, s.run);
    w.put(s.released_at), w.put(s.first_held_at), w.put(s.held_at), w.put(s.contact_steps), w.put(s.shared_touched);
  }
  return w.out;
}

SweepMedium decode_sweep_medium(const std::string& bytes) {
  detail::ByteReader r(bytes, "sweep record");
  if (r.get<std::uint32_t>() != kMagic) r.fail("not one");
  SweepMedium m;
  m.unit.porosity = r.get<int>(), m.unit.medium = r.get<int>();
  m.target_porosity = r.get<double>(), m.porosity = r.get<double>(), m.grains = r.get<int>();
  m.medium_seed = r.get<std::uint64_t>();
  m.passed = r.get<int>(), m.stuck = r.get<int>(), m.timeout = r.get<int>(), m.diverged = r.get<int>();
  m.mean_t = r.get<double>(), m.standard_error = r.get<double>(), m.stuck_fraction = r.get<double>();
  m.seconds = r.get<double>();
  const auto n = r.get<std::uint64_t>();
  if (n > bytes.size()) r.fail("truncated");
  m.droplets.resize(n);
  for (SweepDroplet& d : m.droplets) read_droplet(r, d);
  const auto pairs = r.get<std::uint64_t>();
  if (pairs > bytes.size()) r.fail("truncated");
  m.second_droplets.resize(pairs);
  for (SweepSecond& s : m.second_droplets) {
    read_droplet(r, s.run);
    s.released_at = r.get<double>(), s.first_held_at = r.get<double>(), s.held_at = r.get<double>();
    s.contact_steps = r.get<std::int64_t>(), s.shared_touched = r.get<int>();
  }
  if (!r.at_end()) r.fail("trailing bytes");
  return m;
}

}  // namespace softdrop
