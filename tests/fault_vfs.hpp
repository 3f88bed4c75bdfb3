#pragma once
// An SQLite VFS for crash and full-disk tests: it passes every call to the default VFS, and can
// kill the process or fail writes at a chosen instant. Configured from the environment:
//   SOFTDROP_FAULT_KILL_AT=K         SIGKILL before the K-th write to a main database file (1-based;
//                                    in WAL mode those are the checkpoints' writes, plus the writes
//                                    of a new file before it switches to WAL);
//   SOFTDROP_FAULT_FULL_AFTER=N      once N bytes are written (all files), every write fails with
//                                    SQLITE_FULL, as on a full disk;
//   SOFTDROP_FAULT_AUTOCHECKPOINT=P  every connection checkpoints after P pages of WAL (SQLite's
//                                    default is 1000), so short runs checkpoint often;
//   SOFTDROP_FAULT_COUNT_FILE=F      at a normal exit, writes "MAIN_WRITES BYTES" to F.

namespace softdrop::test {

/// Registers the VFS as SQLite's default; call before any database is opened.
void install_fault_vfs();

}  // namespace softdrop::test
