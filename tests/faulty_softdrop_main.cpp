// softdrop with the fault-injecting SQLite VFS of fault_vfs.hpp: the same program, whose database
// writes can be made to die or fail at a chosen instant (crash and full-disk tests).
#include "cli/cli.hpp"
#include "fault_vfs.hpp"

int main(int argc, char** argv) {
  softdrop::test::install_fault_vfs();
  return softdrop::cli::main(argc, argv);
}
