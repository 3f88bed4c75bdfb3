// Fuzz target: config files (`--config FILE`, TOML/INI whose keys are long option names). The
// first byte picks the subcommand, the rest is the file. The file is parsed and the options
// checked exactly as `softdrop <command> --config FILE` does, without running the command.
#include <unistd.h>

#include <array>
#include <cstdint>
#include <fstream>
#include <string>

#include "parse_and_check.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size == 0) return 0;
  static const std::array<const char*, 5> commands{"simulate", "optimize", "sweep", "render", "medium"};
  const std::size_t which = data[0] % commands.size();
  // The scratch file, removed when the fuzzer exits normally.
  static const struct Scratch {
    std::string path = "/tmp/softdrop-fuzz-config-" + std::to_string(::getpid()) + ".toml";
    ~Scratch() { std::remove(path.c_str()); }
  } scratch;
  const std::string& path = scratch.path;
  {
    std::ofstream out(path, std::ios::binary | std::ios::trunc);
    out.write(reinterpret_cast<const char*>(data) + 1, static_cast<std::streamsize>(size - 1));
  }
  std::vector<const char*> argv{"softdrop"};
  if (which == 4) argv.push_back("render");  // the nested `render medium`
  argv.push_back(commands[which]);
  argv.push_back("--config");
  argv.push_back(path.c_str());
  parse_and_check(argv);
  return 0;
}
