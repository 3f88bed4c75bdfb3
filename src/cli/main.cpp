// softdrop: the command-line program. Every failure ends with one line on stderr and exit code 1
// (bad input found while running) or 2 (the command line itself is wrong).
#include <exception>
#include <iostream>

#include "cli/cli.hpp"

namespace {
// Errors are one line, whatever the library that raised them put in its message.
std::string one_line(std::string message) {
  for (char& c : message)
    if (c == '\n' || c == '\r') c = ' ';
  return message;
}
}  // namespace

int main(int argc, char** argv) {
  softdrop::cli::Cli cli;
  try {
    cli.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    if (e.get_exit_code() == 0) return cli.app.exit(e);  // --help, --version
    std::cerr << "softdrop: error: " << one_line(e.what()) << '\n';
    return 2;
  }
  try {
    return cli.run();
  } catch (const std::exception& e) {
    std::cerr << "softdrop: error: " << one_line(e.what()) << '\n';
    return 1;
  }
}
