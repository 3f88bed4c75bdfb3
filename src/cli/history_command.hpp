#pragma once
// `softdrop history` (list runs, a run's generations, its best-T curve) and `softdrop export`
// (a stored configuration as a grain file that `softdrop simulate` accepts).

#include <CLI/CLI.hpp>
#include <cstdint>
#include <string>

#include "softdrop/store.hpp"

namespace softdrop::cli {

struct HistoryArgs {
  std::string db = "softdrop.db";
  std::int64_t run = 0;     ///< 0: list runs
  bool best = false;        ///< with --run: only accepted generations (the best-T curve)
  bool candidates = false;  ///< with --run: one row per candidate
  bool params = false;      ///< with --run: the stored options, one row each
  std::string format = "table";
};

struct ExportArgs {
  std::string db = "softdrop.db";
  std::int64_t run = 0;
  std::int64_t generation = -1;  ///< -1: the run's best
  std::string output;
  std::string simulate_config;  ///< optional TOML for `softdrop simulate --config`
};

CLI::App* add_history_command(CLI::App& app, HistoryArgs& args);
CLI::App* add_export_command(CLI::App& app, ExportArgs& args);
int run_history(const HistoryArgs& args);
/// Throws std::invalid_argument naming --generation if it is past the run's last stored one.
void check_stored_generation(std::int64_t generation, const RunRecord& run);
int run_export(const ExportArgs& args);

}  // namespace softdrop::cli
