// softdrop: the command-line program (see cli/cli.hpp for exit codes).
#include "cli/cli.hpp"

int main(int argc, char** argv) { return softdrop::cli::main(argc, argv); }
