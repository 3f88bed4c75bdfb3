#pragma once
// Shared by fuzz_cli and fuzz_config: parse a command line and check its options exactly as the
// program does, without running the command. Parse errors and check errors are the expected
// refusals; any other exception escapes and is reported by libFuzzer as a crash.
#include <vector>

#include "cli/cli.hpp"

inline void parse_and_check(const std::vector<const char*>& argv) {
  softdrop::cli::Cli cli;
  try {
    cli.parse(static_cast<int>(argv.size()), argv.data());
  } catch (const CLI::ParseError&) {
    return;
  }
  try {
    cli.check();
  } catch (const std::invalid_argument&) {
  } catch (const std::runtime_error&) {  // e.g. an output path in a missing folder
  }
}
