#pragma once
// `softdrop sweep-merge`: sweep stores (the shards of one sweep, say) merged into one
// (sweep_merge_command.cpp); identical units must agree to the bit.

#include <CLI/CLI.hpp>
#include <string>
#include <vector>

namespace softdrop::cli {

struct SweepMergeArgs {
  std::string into;
  std::vector<std::string> inputs;
};

void add_sweep_merge_command(CLI::App& app, SweepMergeArgs& args);
int run_sweep_merge(const SweepMergeArgs& args);

}  // namespace softdrop::cli
