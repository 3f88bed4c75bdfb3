// What `simulate` writes about its runs (simulate_output.hpp).
#include "cli/simulate_output.hpp"

#include <cmath>
#include <iostream>
#include <sstream>

#include "cli/columns.hpp"

namespace softdrop::cli {

void write_run_columns(std::ostream& o, const RunSummary& r) {
  o << fmt(r.start_x) << ',' << to_string(r.outcome) << ',' << (r.outcome == Outcome::passed ? fmt(r.tortuosity) : "")
    << ',' << r.steps << ',' << r.touched.size() << ',' << fmt(r.min_area_ratio) << ',' << fmt(r.max_penetration) << ','
    << (std::isnan(r.shaken_at) ? "" : fmt(r.shaken_at)) << ','
    << (r.outcome == Outcome::passed ? fmt(r.route_tortuosity) : "");
}

nlohmann::json run_record(const RunSummary& r) {
  return {{"start_x", r.start_x},
          {"outcome", to_string(r.outcome)},
          {"reason", r.reason},
          {"tortuosity", r.outcome == Outcome::passed ? nlohmann::json(r.tortuosity) : nlohmann::json()},
          {"route_tortuosity", r.outcome == Outcome::passed ? nlohmann::json(r.route_tortuosity) : nlohmann::json()},
          {"steps", r.steps},
          {"touched", r.touched.size()},
          {"min_area_ratio", r.min_area_ratio},
          {"max_penetration", r.max_penetration},
          {"shaken_at", std::isnan(r.shaken_at) ? nlohmann::json() : nlohmann::json(r.shaken_at)}};
}

void write_path_rows(std::ostream& o, const std::string& key, const RunSummary& r) {
  for (std::size_t k = 0; k < r.path_t.size(); ++k)
    o << key << fmt(r.path_t[k]) << ',' << fmt(r.path_x[k]) << ',' << fmt(r.path_y[k]) << '\n';
}

void write_snapshot_rows(std::ostream& o, const std::string& key, const RunSummary& r) {
  for (const Snapshot& sn : r.snapshots)
    for (std::size_t k = 0; k < sn.x.size(); ++k)
      o << key << fmt(sn.time) << ',' << k << ',' << fmt(sn.x[k]) << ',' << fmt(sn.y[k]) << '\n';
}

nlohmann::json medium_record(const Medium& medium, double porosity) {
  nlohmann::json j{{"grains", medium.grains.size()},
                   {"porosity", porosity},
                   {"width", medium.width},
                   {"height", medium.height},
                   {"periodic", medium.periodic}};
  if (medium.image)
    j["image"] = {{"columns", medium.image->nx}, {"rows", medium.image->ny}, {"pixel_size", medium.image->pixel}};
  return j;
}

std::string medium_words(const Medium& medium, double porosity, int digits) {
  std::ostringstream s;
  if (medium.image)
    s << "an image of " << medium.image->nx << " x " << medium.image->ny << " pixels of " << fmt(medium.image->pixel);
  else
    s << medium.grains.size() << " grains";
  s << ", porosity " << fmt(porosity, digits) << ", " << fmt(medium.width) << " x " << fmt(medium.height)
    << (medium.periodic ? ", periodic" : ", walls");
  return s.str();
}

std::string medium_line(const Medium& medium, double porosity) {
  return "medium       " + medium_words(medium, porosity, 6) + "\n";
}

void write_csv(const std::string& path, const std::string& header, const std::function<void(std::ostream&)>& rows) {
  if (path.empty()) return;
  check_csv_header(header);
  std::ostringstream out;
  out << header << '\n';
  rows(out);
  write_file_atomically(path, out.str());
}

int finish_simulate(const std::string& format, const nlohmann::json& j, const std::string& table,
                    const StopOnSignal& stop, std::size_t ran, long asked, const char* what) {
  if (format == "json")
    std::cout << j.dump(2) << '\n';
  else
    std::cout << table;
  if (!stop.requested()) return 0;
  std::cerr << "simulate: stopped by a signal after " << ran << " of " << asked << ' ' << what
            << "; the outputs hold those " << ran << "\n";
  return stop.exit_code();
}

}  // namespace softdrop::cli
