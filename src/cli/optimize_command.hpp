#pragma once
// `softdrop optimize`: the maximum-tortuosity search, logged generation by generation to an
// SQLite history; `--resume RUN` continues a stored run exactly.

#include <CLI/CLI.hpp>

#include "cli/host.hpp"
#include "cli/search_setup.hpp"

namespace softdrop::cli {

CLI::App* add_optimize_command(CLI::App& app, OptimizeArgs& args);

/// Checks the options without running; throws std::invalid_argument naming the bad parameter.
void check_optimize(const OptimizeArgs& args, const CLI::App& command);
/// Runs it; `command` is the parsed subcommand (to tell which options were given). With a host
/// (see Host) nothing is printed on stdout and the signals are left to the host.
int run_optimize(OptimizeArgs& args, const CLI::App& command, Host* host = nullptr);

}  // namespace softdrop::cli
