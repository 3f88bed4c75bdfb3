// Fuzz target: command-line values. The input is split at newlines into arguments after
// "softdrop"; the command line is parsed and checked exactly as the program does (without running
// the command). Parse errors and check errors are the expected outcomes for bad values; any
// other exception, a crash, a sanitizer report or a large allocation is a bug.
#include <cstdint>
#include <string>
#include <vector>

#include "parse_and_check.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  std::vector<std::string> args{"softdrop"};
  std::string current;
  for (std::size_t i = 0; i < size; ++i) {
    if (data[i] == '\n') {
      args.push_back(current);
      current.clear();
    } else {
      current.push_back(static_cast<char>(data[i]));
    }
  }
  if (!current.empty()) args.push_back(current);
  // Options that would read files, print help or run are left to the other targets and tests.
  for (const std::string& a : args)
    if (a.rfind("--config", 0) == 0 || a == "--help" || a == "-h" || a == "--help-all" || a == "--version") return 0;
  std::vector<const char*> argv;
  for (const std::string& a : args) argv.push_back(a.c_str());
  parse_and_check(argv);
  return 0;
}
