#include "fault_vfs.hpp"

#include <signal.h>
#include <sqlite3.h>
#include <unistd.h>

#include <atomic>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>

namespace softdrop::test {
namespace {

// The plan, read once from the environment (see fault_vfs.hpp).
std::int64_t kill_at = 0;      // kill before this main-database write (1-based); 0: never
std::int64_t full_after = -1;  // bytes that may be written before every write fails; -1: no limit
std::atomic<std::int64_t> main_writes{0};
std::atomic<std::int64_t> bytes_written{0};

sqlite3_vfs* real_vfs = nullptr;
sqlite3_vfs shim_vfs;

// A file of the shim: the real file's state follows this header in the same allocation.
struct ShimFile {
  sqlite3_file base;
  bool main_db;
  sqlite3_file* real() { return reinterpret_cast<sqlite3_file*>(this + 1); }
};

ShimFile* shim(sqlite3_file* f) { return reinterpret_cast<ShimFile*>(f); }
const sqlite3_io_methods* io(sqlite3_file* f) { return shim(f)->real()->pMethods; }

int shim_close(sqlite3_file* f) { return io(f)->xClose(shim(f)->real()); }
int shim_read(sqlite3_file* f, void* p, int n, sqlite3_int64 off) { return io(f)->xRead(shim(f)->real(), p, n, off); }
int shim_write(sqlite3_file* f, const void* p, int n, sqlite3_int64 off) {
  // Killed at the system call's entry, as by `strace -e inject=pwrite64:signal=KILL`: the write
  // does not happen.
  if (shim(f)->main_db && ++main_writes == kill_at) ::kill(::getpid(), SIGKILL);
  if (bytes_written.fetch_add(n) + n > full_after && full_after >= 0) return SQLITE_FULL;
  return io(f)->xWrite(shim(f)->real(), p, n, off);
}
int shim_truncate(sqlite3_file* f, sqlite3_int64 size) { return io(f)->xTruncate(shim(f)->real(), size); }
int shim_sync(sqlite3_file* f, int flags) { return io(f)->xSync(shim(f)->real(), flags); }
int shim_size(sqlite3_file* f, sqlite3_int64* size) { return io(f)->xFileSize(shim(f)->real(), size); }
int shim_lock(sqlite3_file* f, int level) { return io(f)->xLock(shim(f)->real(), level); }
int shim_unlock(sqlite3_file* f, int level) { return io(f)->xUnlock(shim(f)->real(), level); }
int shim_check(sqlite3_file* f, int* out) { return io(f)->xCheckReservedLock(shim(f)->real(), out); }
int shim_control(sqlite3_file* f, int op, void* arg) { return io(f)->xFileControl(shim(f)->real(), op, arg); }
int shim_sector(sqlite3_file* f) { return io(f)->xSectorSize(shim(f)->real()); }
int shim_device(sqlite3_file* f) { return io(f)->xDeviceCharacteristics(shim(f)->real()); }
int shim_shm_map(sqlite3_file* f, int page, int size, int extend, void volatile** p) {
  return io(f)->xShmMap(shim(f)->real(), page, size, extend, p);
}
int shim_shm_lock(sqlite3_file* f, int offset, int n, int flags) {
  return io(f)->xShmLock(shim(f)->real(), offset, n, flags);
}
void shim_shm_barrier(sqlite3_file* f) { io(f)->xShmBarrier(shim(f)->real()); }
int shim_shm_unmap(sqlite3_file* f, int del) { return io(f)->xShmUnmap(shim(f)->real(), del); }
int shim_fetch(sqlite3_file* f, sqlite3_int64 off, int n, void** p) {
  return io(f)->xFetch(shim(f)->real(), off, n, p);
}
int shim_unfetch(sqlite3_file* f, sqlite3_int64 off, void* p) { return io(f)->xUnfetch(shim(f)->real(), off, p); }

const sqlite3_io_methods shim_io = {
    3,           shim_close,   shim_read,     shim_write,       shim_truncate,  shim_sync,
    shim_size,   shim_lock,    shim_unlock,   shim_check,       shim_control,   shim_sector,
    shim_device, shim_shm_map, shim_shm_lock, shim_shm_barrier, shim_shm_unmap, shim_fetch,
    shim_unfetch};

int shim_open(sqlite3_vfs*, sqlite3_filename name, sqlite3_file* f, int flags, int* out_flags) {
  ShimFile* s = shim(f);
  s->main_db = (flags & SQLITE_OPEN_MAIN_DB) != 0;
  const int rc = real_vfs->xOpen(real_vfs, name, s->real(), flags, out_flags);
  // SQLite calls xClose only when pMethods is set, so a failed open leaves it null.
  s->base.pMethods = s->real()->pMethods ? &shim_io : nullptr;
  return rc;
}

// Every other call goes to the real VFS with the real VFS as its first argument (the unix VFS
// keeps its locking style in pAppData).
int shim_delete(sqlite3_vfs*, const char* n, int sync) { return real_vfs->xDelete(real_vfs, n, sync); }
int shim_access(sqlite3_vfs*, const char* n, int flags, int* out) { return real_vfs->xAccess(real_vfs, n, flags, out); }
int shim_full(sqlite3_vfs*, const char* n, int size, char* out) {
  return real_vfs->xFullPathname(real_vfs, n, size, out);
}
void* shim_dlopen(sqlite3_vfs*, const char* n) { return real_vfs->xDlOpen(real_vfs, n); }
void shim_dlerror(sqlite3_vfs*, int n, char* out) { real_vfs->xDlError(real_vfs, n, out); }
void (*shim_dlsym(sqlite3_vfs*, void* h, const char* s))(void) { return real_vfs->xDlSym(real_vfs, h, s); }
void shim_dlclose(sqlite3_vfs*, void* h) { real_vfs->xDlClose(real_vfs, h); }
int shim_random(sqlite3_vfs*, int n, char* out) { return real_vfs->xRandomness(real_vfs, n, out); }
int shim_sleep(sqlite3_vfs*, int us) { return real_vfs->xSleep(real_vfs, us); }
int shim_time(sqlite3_vfs*, double* t) { return real_vfs->xCurrentTime(real_vfs, t); }
int shim_last_error(sqlite3_vfs*, int n, char* out) { return real_vfs->xGetLastError(real_vfs, n, out); }
int shim_time64(sqlite3_vfs*, sqlite3_int64* t) { return real_vfs->xCurrentTimeInt64(real_vfs, t); }

// Checkpoints every `pages` pages of WAL instead of SQLite's 1000, so that short runs checkpoint
// often and a kill lands inside automatic checkpoints too, not only the one at close.
// SQLite sets its default after running the automatic extensions, so the extension installs a
// commit hook, and the hook sets the interval before the commit's WAL hook runs.
int autocheckpoint_pages = 0;
int on_commit(void* db) {
  sqlite3_wal_autocheckpoint(static_cast<sqlite3*>(db), autocheckpoint_pages);
  return 0;  // the commit goes ahead
}
int set_autocheckpoint(sqlite3* db, char**, const sqlite3_api_routines*) {
  sqlite3_commit_hook(db, on_commit, db);
  return SQLITE_OK;
}

std::int64_t env_int(const char* name, std::int64_t fallback) {
  const char* v = std::getenv(name);
  return v && *v ? std::strtoll(v, nullptr, 10) : fallback;
}

void report_counts() {
  const char* path = std::getenv("SOFTDROP_FAULT_COUNT_FILE");
  if (!path) return;
  if (FILE* f = std::fopen(path, "w")) {
    std::fprintf(f, "%lld %lld\n", static_cast<long long>(main_writes.load()),
                 static_cast<long long>(bytes_written.load()));
    std::fclose(f);
  }
}

}  // namespace

void install_fault_vfs() {
  kill_at = env_int("SOFTDROP_FAULT_KILL_AT", 0);
  full_after = env_int("SOFTDROP_FAULT_FULL_AFTER", -1);
  autocheckpoint_pages = static_cast<int>(env_int("SOFTDROP_FAULT_AUTOCHECKPOINT", 0));
  real_vfs = sqlite3_vfs_find(nullptr);
  shim_vfs = *real_vfs;
  shim_vfs.szOsFile = static_cast<int>(sizeof(ShimFile)) + real_vfs->szOsFile;
  shim_vfs.zName = "softdrop_fault";
  shim_vfs.pNext = nullptr;
  shim_vfs.pAppData = nullptr;
  shim_vfs.xOpen = shim_open;
  shim_vfs.xDelete = shim_delete;
  shim_vfs.xAccess = shim_access;
  shim_vfs.xFullPathname = shim_full;
  shim_vfs.xDlOpen = shim_dlopen;
  shim_vfs.xDlError = shim_dlerror;
  shim_vfs.xDlSym = shim_dlsym;
  shim_vfs.xDlClose = shim_dlclose;
  shim_vfs.xRandomness = shim_random;
  shim_vfs.xSleep = shim_sleep;
  shim_vfs.xCurrentTime = shim_time;
  shim_vfs.xGetLastError = shim_last_error;
  shim_vfs.xCurrentTimeInt64 = shim_time64;
  shim_vfs.xSetSystemCall = nullptr;  // iVersion 3 calls, not used by SQLite itself
  shim_vfs.xGetSystemCall = nullptr;
  shim_vfs.xNextSystemCall = nullptr;
  shim_vfs.iVersion = 2;
  sqlite3_vfs_register(&shim_vfs, 1);
  if (autocheckpoint_pages > 0) sqlite3_auto_extension(reinterpret_cast<void (*)(void)>(set_autocheckpoint));
  std::atexit(report_counts);
}

}  // namespace softdrop::test
