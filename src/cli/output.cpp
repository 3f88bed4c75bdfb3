#include "cli/output.hpp"

#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <csignal>
#include <cstring>
#include <filesystem>
#include <iomanip>
#include <iostream>
#include <sstream>
#include <stdexcept>

#include "cli/columns.hpp"
#include "softdrop/medium.hpp"
#include "softdrop/render.hpp"
#include "util/temp_files.hpp"
#include "util/validation.hpp"

namespace softdrop::cli {

void check_output_path(const std::string& option, const std::string& path) {
  namespace fs = std::filesystem;
  const fs::path p(path);
  std::error_code ec;
  if (fs::is_directory(p, ec)) throw std::runtime_error(option + " '" + path + "': is a directory");
  const fs::path dir = p.has_parent_path() ? p.parent_path() : fs::path(".");
  if (!fs::is_directory(dir, ec))
    throw std::runtime_error(option + " '" + path + "': directory '" + dir.string() + "' does not exist");
  if (::access(dir.c_str(), W_OK) != 0) throw std::runtime_error(option + " '" + path + "': directory is not writable");
}

nlohmann::json finite_or_null(double v) { return std::isfinite(v) ? nlohmann::json(v) : nlohmann::json(); }

void check_picture_path(const std::string& option, const std::string& path) {
  image_format_for(path);
  check_output_path(option, path);
}

std::string percent_and_eta(double elapsed, double done, double total) {
  const double share = total > 0 ? done / total : 1;
  std::string text = fmt(std::floor(100 * share), 3) + " %";
  if (done > 0 && done < total) text += ", ETA " + fmt(std::ceil(elapsed / done * (total - done)), 6) + " s";
  return text;
}

Progress::Progress(std::string label)
    : label_(std::move(label)), t0_(std::chrono::steady_clock::now()), last_(t0_), tty_(::isatty(2) != 0) {}

void Progress::update(long done, long total) {
  const auto now = std::chrono::steady_clock::now();
  if (done != total && now - last_ < (tty_ ? std::chrono::seconds(1) : std::chrono::seconds(10))) return;
  last_ = now;
  const double elapsed = std::chrono::duration<double>(now - t0_).count();
  std::cerr << (tty_ ? "\r" : "") << label_ << ": " << done << "/" << total << " ("
            << percent_and_eta(elapsed, static_cast<double>(done), static_cast<double>(total)) << ")"
            << (tty_ && done != total ? "\033[K" : "\n") << std::flush;
}

namespace {
std::atomic<bool> g_stop{false};
std::atomic<int> g_signal{0};
const char* g_stop_message = "";

extern "C" void softdrop_on_stop_signal(int sig) {
  if (g_stop.exchange(true)) {  // second signal: leave now; stores stay consistent
    detail::remove_temp_files();
    _exit(128 + sig);
  }
  g_signal = sig;
  [[maybe_unused]] auto n = ::write(2, g_stop_message, std::strlen(g_stop_message));
}

extern "C" void softdrop_on_ending_signal(int sig) {
  detail::remove_temp_files();
  std::signal(sig, SIG_DFL);
  std::raise(sig);  // ends the program as the signal would have (shells report 128 + sig)
}
}  // namespace

void remove_temp_files_on_signals() {
  for (const int sig : {SIGINT, SIGTERM, SIGHUP}) std::signal(sig, softdrop_on_ending_signal);
}

StopOnSignal::StopOnSignal(const char* message) {
  g_stop = false;
  g_signal = 0;
  g_stop_message = message;
  previous_int_ = std::signal(SIGINT, softdrop_on_stop_signal);
  previous_term_ = std::signal(SIGTERM, softdrop_on_stop_signal);
}
StopOnSignal::~StopOnSignal() {
  std::signal(SIGINT, previous_int_);
  std::signal(SIGTERM, previous_term_);
}
bool StopOnSignal::requested() const { return g_stop.load(); }
int StopOnSignal::exit_code() const { return g_signal.load() ? 128 + g_signal.load() : 0; }
const std::atomic<bool>* StopOnSignal::flag() const { return &g_stop; }

namespace {
std::string text(const nlohmann::json& v) {
  if (v.is_null()) return "";
  if (v.is_string()) return v.get<std::string>();
  if (v.is_number_float()) return fmt(v.get<double>());
  return v.dump();
}
}  // namespace

void Table::write_csv(const std::string& path) const {
  std::ostringstream out;
  print(out, "csv");
  write_file_atomically(path, out.str());
}

void Table::print(std::ostream& out, const std::string& format) const {
  check_column_names(header);
  if (format == "json") {
    nlohmann::ordered_json j = nlohmann::ordered_json::array();
    for (const auto& row : rows) {
      nlohmann::ordered_json o;
      for (std::size_t c = 0; c < header.size(); ++c) o[header[c]] = row[c];
      j.push_back(o);
    }
    out << j.dump(2) << '\n';
    return;
  }
  if (format == "csv") {
    for (std::size_t c = 0; c < header.size(); ++c) out << (c ? "," : "") << header[c];
    out << '\n';
    for (const auto& row : rows) {
      for (std::size_t c = 0; c < row.size(); ++c) {
        std::string t = text(row[c]);
        if (t.find_first_of(",\"\n") != std::string::npos) {
          std::string q = "\"";
          for (char ch : t) q += ch == '"' ? std::string("\"\"") : std::string(1, ch);
          t = q + "\"";
        }
        out << (c ? "," : "") << t;
      }
      out << '\n';
    }
    return;
  }
  // Table: doubles shortened for reading; CSV and JSON keep every digit.
  auto cell = [](const nlohmann::json& v) { return v.is_number_float() ? fmt(v.get<double>(), 8) : text(v); };
  std::vector<std::size_t> width(header.size());
  for (std::size_t c = 0; c < header.size(); ++c) width[c] = header[c].size();
  for (const auto& row : rows)
    for (std::size_t c = 0; c < row.size(); ++c) width[c] = std::max(width[c], cell(row[c]).size());
  for (std::size_t c = 0; c < header.size(); ++c)
    out << (c ? "  " : "") << std::left << std::setw(static_cast<int>(width[c])) << header[c];
  out << '\n';
  for (const auto& row : rows) {
    for (std::size_t c = 0; c < row.size(); ++c)
      out << (c ? "  " : "") << std::left << std::setw(static_cast<int>(width[c])) << cell(row[c]);
    out << '\n';
  }
}

void write_area_traces(const std::string& path, const std::vector<AreaTrace>& traces) {
  std::ostringstream out;
  out << "droplet,time,area,area_ratio,phase\n";
  for (std::size_t d = 0; d < traces.size(); ++d) {
    const AreaTrace& tr = traces[d];
    for (std::size_t i = 0; i < tr.t.size(); ++i) {
      const double t = tr.t[i];
      const char* phase = !(t >= tr.enter) ? "above" : !(t >= tr.leave) ? "inside" : "below";  // NaN: never
      out << d << ',' << fmt(t) << ',' << fmt(tr.area[i]) << ',' << (std::isnan(tr.s0) ? "" : fmt(tr.area[i] / tr.s0))
          << ',' << phase << '\n';
    }
  }
  write_file_atomically(path, out.str());
}

std::string fmt(double v, int digits) {
  if (digits >= 17) return detail::num(v);  // every digit that matters, and no more
  std::ostringstream s;
  s.precision(digits);
  s << v;
  return s.str();
}

std::string with_error(double value, double error) {
  if (!std::isfinite(value) || !std::isfinite(error) || !(error > 0)) return fmt(value, 4) + " ± " + fmt(error, 2);
  // Decimal places that keep the error's second significant digit (none when the error is >= 10).
  const int places = std::max(0, 1 - static_cast<int>(std::floor(std::log10(error))));
  return fixed(value, places) + " ± " + fixed(error, places);
}

std::string fixed(double v, int places) {
  std::ostringstream s;
  s << std::fixed << std::setprecision(places) << v;
  return s.str();
}

}  // namespace softdrop::cli
