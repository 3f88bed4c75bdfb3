// Fuzz target: grain files. The first byte picks the format (odd: JSON, even: CSV), the rest is
// the file's text. A file is either refused with std::runtime_error naming it, or gives a medium
// that the simulator accepts or refuses with std::invalid_argument, and that a droplet can fall
// through for a few hundred steps. Anything else (another exception, a crash, a sanitizer
// report, a hang, a large allocation) is a bug.
#include <cstdint>
#include <cstdlib>
#include <iostream>
#include <sstream>
#include <string>

#include "softdrop/medium.hpp"
#include "softdrop/simulation.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size == 0) return 0;
  const auto format = (data[0] & 1) ? softdrop::GrainFileFormat::json : softdrop::GrainFileFormat::csv;
  std::istringstream in(std::string(reinterpret_cast<const char*>(data) + 1, size - 1));
  softdrop::Medium medium;
  try {
    medium = softdrop::read_medium(in, format, "fuzz.input");
  } catch (const std::runtime_error& e) {
    if (std::string(e.what()).rfind("grain file 'fuzz.input': ", 0) != 0) {
      std::cerr << "error does not name the file: " << e.what() << '\n';
      std::abort();
    }
    return 0;
  }
  (void)softdrop::exact_porosity(medium);
  try {
    softdrop::DropletParams params;
    params.masses = 16;
    softdrop::Simulation sim(params, medium);
    softdrop::RunOptions run;
    run.max_steps = 300;
    (void)sim.run(medium.width / 2, run);
  } catch (const std::invalid_argument&) {
    // e.g. grains narrower than a ring edge: refused by the simulator, with a message.
  }
  return 0;
}
