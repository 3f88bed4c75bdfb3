// A database's write-ahead log as the store reads it before SQLite does: a damaged frame with
// committed transactions after it is refused by every command, by name, and nothing is written; an
// uncommitted tail cut short is not damage. A reader who cannot write the file leaves no side files
// behind for its owner to trip over.
#include <SQLiteCpp/SQLiteCpp.h>
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>

#include "search_cli.hpp"
#include "store/wal_file.hpp"

namespace {
using namespace softdrop::test;
namespace fs = std::filesystem;

std::string contents(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), {}};
}

// Flips one byte of a file in place.
void flip(const std::string& path, std::streamoff at) {
  std::fstream f(path, std::ios::in | std::ios::out | std::ios::binary);
  f.seekg(at);
  const char c = static_cast<char>(f.get() ^ 0xff);
  f.seekp(at);
  f.put(c);
}

// A history whose last `commits` transactions are only in its -wal, as a killed search leaves it:
// the files are copied while the writing connection still holds them.
std::string history_with_wal(const std::string& name, int commits) {
  const std::string seed = fresh(name + "_seed.db"), db = fresh(name);
  EXPECT_EQ(run("optimize --db " + seed + kScene + " --generations 2").code, 0);
  {
    SQLite::Database w(seed, SQLite::OPEN_READWRITE);
    w.exec("PRAGMA wal_autocheckpoint = 0");
    for (int i = 0; i < commits; ++i)  // ends on 'running'
      w.exec(std::string("UPDATE runs SET status = '") + ((commits - i) % 2 == 1 ? "running" : "interrupted") + "'");
    fs::copy_file(seed, db);
    fs::copy_file(seed + "-wal", db + "-wal");
  }
  fs::remove(seed);
  return db;
}

constexpr std::streamoff kFrameStart = 32, kFrameHeader = 24;

TEST(WalDamage, ACleanLogWithCommitsAfterAKillIsRead) {
  const std::string db = history_with_wal("wal_clean.db", 5);
  const auto report = softdrop::detail::read_wal(db + "-wal");
  EXPECT_TRUE(report.present);
  EXPECT_TRUE(report.header_valid);
  EXPECT_EQ(report.valid_frames, report.frames);
  EXPECT_EQ(report.first_bad_frame, -1);
  EXPECT_EQ(softdrop::detail::wal_damage(report), "");
  const Result r = run("history --db " + db);
  EXPECT_EQ(r.code, 0) << r.err;
  EXPECT_NE(r.out.find("running"), std::string::npos) << r.out;  // the log's last commit is seen
}

TEST(WalDamage, ADamagedFrameBeforeCommitsIsRefusedByReadersAndWriters) {
  const std::string db = history_with_wal("wal_damaged.db", 5);
  const std::int64_t page = SQLite::Database::getHeaderInfo(db).pageSizeBytes;
  flip(db + "-wal", kFrameStart + kFrameHeader + 100);  // inside frame 1's page
  const auto report = softdrop::detail::read_wal(db + "-wal");
  EXPECT_EQ(report.first_bad_frame, 1);
  EXPECT_EQ(report.valid_frames, 0);
  EXPECT_EQ(report.lost_commits, 4);  // frame 1 is the first transaction's only page; four follow it
  EXPECT_EQ(report.frames, (static_cast<std::int64_t>(fs::file_size(db + "-wal")) - 32) / (24 + page));
  const std::string db_bytes = contents(db), wal_bytes = contents(db + "-wal");
  for (const std::string& command :
       {"history --db " + db, "optimize --db " + db + kScene + " --generations 1",
        "optimize --db " + db + " --resume 1 --generations 4 --quiet",
        "export --db " + db + " --run 1 -o " + fresh("w.json"), "sweep --db " + db + " --preset quick --quiet"}) {
    SCOPED_TRACE(command);
    const Result r = run(command);
    EXPECT_EQ(r.code, 1);
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
    EXPECT_NE(r.err.find("write-ahead log '" + db + "-wal' is damaged: frame 1 of"), std::string::npos) << r.err;
    EXPECT_NE(r.err.find("drop the 4 committed transactions"), std::string::npos) << r.err;
    EXPECT_EQ(contents(db), db_bytes);
    EXPECT_EQ(contents(db + "-wal"), wal_bytes);
    EXPECT_FALSE(fs::exists(db + "-shm"));
    EXPECT_FALSE(fs::exists(fresh("w.json")));
  }
}

TEST(WalDamage, ADamagedHeaderIsRefused) {
  const std::string db = history_with_wal("wal_header.db", 2);
  flip(db + "-wal", 17);  // a salt: the header's checksum fails
  const Result r = run("history --db " + db);
  EXPECT_EQ(r.code, 1);
  EXPECT_NE(r.err.find("its header is damaged"), std::string::npos) << r.err;
}

// A write cut short leaves a last frame that fails its checksum and commits nothing after it:
// SQLite drops only that transaction, which never completed, and the file is usable.
TEST(WalDamage, ACutShortLastTransactionIsNotDamage) {
  const std::string db = history_with_wal("wal_tail.db", 3);
  const std::int64_t page = SQLite::Database::getHeaderInfo(db).pageSizeBytes;
  const auto before = softdrop::detail::read_wal(db + "-wal");
  flip(db + "-wal", kFrameStart + (before.frames - 1) * (kFrameHeader + page) + kFrameHeader + 10);
  const auto report = softdrop::detail::read_wal(db + "-wal");
  EXPECT_EQ(report.first_bad_frame, before.frames);
  EXPECT_EQ(report.lost_commits, 0);
  EXPECT_EQ(softdrop::detail::wal_damage(report), "");
  EXPECT_EQ(run("history --db " + db).code, 0);
}

// Another user's reader used to create -wal and -shm files of its own beside the owner's file, and
// the owner's next search failed with "attempt to write a readonly database".
TEST(ReaderSideFiles, AReaderWhoCannotWriteTheFileLeavesNoneBehind) {
  if (::geteuid() != 0) GTEST_SKIP() << "needs root to act as two users";
  const fs::path dir = fresh("shared_folder");
  fs::remove_all(dir);
  fs::create_directories(dir);
  fs::permissions(dir, fs::perms::all);
  const std::string db = (dir / "h.db").string();
  const std::string cli = SOFTDROP_CLI;
  auto as = [&](const char* uid, const std::string& args) {
    return run_shell("setpriv --reuid=" + std::string(uid) + " --regid=" + uid + " --clear-groups " + cli + " " + args);
  };
  if (as("1", "--version").code != 0) GTEST_SKIP() << "the program is not readable by other users here";
  ASSERT_EQ(as("1", "optimize --db " + db + kScene + " --generations 2").code, 0);  // the owner: daemon
  const Result read = as("65534", "history --db " + db);                            // another user: nobody
  EXPECT_EQ(read.code, 0) << read.err;
  EXPECT_FALSE(fs::exists(db + "-wal"));
  EXPECT_FALSE(fs::exists(db + "-shm"));
  const Result resume = as("1", "optimize --db " + db + " --resume 1 --generations 3 --quiet");
  EXPECT_EQ(resume.code, 0) << resume.err;
  fs::remove_all(dir);
}

}  // namespace
