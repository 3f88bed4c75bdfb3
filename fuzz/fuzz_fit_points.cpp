// Fuzz target: points files for `softdrop fit --points FILE` (phi,t,se per line). A file is
// refused with std::runtime_error naming it, or its points are fitted with both laws (refused
// with std::invalid_argument naming the bad point) and averaged both ways. NLopt must end on its
// own bounds for any finite input: no hang, no crash, no sanitizer report.
#include <cstdint>
#include <sstream>
#include <string>

#include "studies/averaging.hpp"
#include "studies/fit.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  std::istringstream in(std::string(reinterpret_cast<const char*>(data), size));
  std::vector<softdrop::FitPoint> points;
  try {
    points = softdrop::read_fit_points(in, "fuzz.csv");
  } catch (const std::runtime_error&) {
    return 0;
  }
  for (const auto law : {softdrop::FitLaw::power, softdrop::FitLaw::log}) {
    try {
      (void)softdrop::fit_law(law, points);
    } catch (const std::invalid_argument&) {
    }
  }
  std::vector<softdrop::MediumPoint> media;
  for (const auto& p : points) media.push_back({p.phi, p.t});
  for (const auto type : {softdrop::AveragingType::by_t, softdrop::AveragingType::by_phi})
    for (int group = 1; group <= 3; ++group) (void)softdrop::group_averages(media, type, group);
  return 0;
}
