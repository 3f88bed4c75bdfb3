#pragma once
// The files a command line names, and the rule that no command writes over a file it reads or
// writes under another name: an output may not be the database, an input or another output.

#include <CLI/CLI.hpp>
#include <string>
#include <vector>

namespace softdrop::cli {

/// One file named on the command line (or in a config file, or by an option's default).
struct NamedFile {
  std::string option;  ///< "--json", "--db", "inputs", ...
  std::string path;
  bool written = false;   ///< the command writes or replaces it
  bool database = false;  ///< an SQLite file: its -wal, -shm and -journal files are part of it
};

/// The options of a command and of its option groups (nameless subcommands to CLI11).
void options_of(const CLI::App& command, std::vector<const CLI::Option*>* out);

/// The files named by the chosen command (and its subcommand, for render), from the values parsed
/// into `app` and the defaults of the options not given.
std::vector<NamedFile> named_files(const CLI::App& app);

/// True if the two paths name one file: the same inode where both exist (so hard links, symbolic
/// links and "./" spellings are caught), else the same canonical path.
bool same_file(const std::string& a, const std::string& b);

/// Throws std::invalid_argument, one line naming both options, if a written file is the same file
/// as any other named file (or one of a database's side files). (An empty path never reaches it:
/// every option refuses an empty value when the command line is parsed.)
void check_distinct_files(std::vector<NamedFile> files);

}  // namespace softdrop::cli
