"""Every repository path that a document or a comment names exists: a path under one of the
repository's folders (docs/model.md, src/cli/columns.cpp, ...), and a bare file name of a source
or a document (simulation.hpp, README.md) in a comment or a Markdown file. Files that commands
write when they run (results/run/, the studies' db/ folders) and the generated version header are
named on purpose: those that .gitignore names count as written, the others are listed below. A path
counts as present only if git lists it, so a file left on one disk does not hide a stale name.

    python3 tests/repository_paths.py SOURCE_DIR     (exit 1 and one line a stale path)
"""
import os
import re
import subprocess
import sys

root = sys.argv[1] if len(sys.argv) > 1 else os.path.join(os.path.dirname(os.path.abspath(__file__)), "..")
os.chdir(root)
listed = subprocess.run(["git", "ls-files"], capture_output=True, text=True)
if listed.returncode == 0:
    files = listed.stdout.split()
else:  # not a git checkout (a source archive): every file but the build folders
    files = [os.path.relpath(os.path.join(d, n)) for d, sub, found in os.walk(".") for n in found
             if not os.path.relpath(d).startswith(("build", ".git", ".ccache"))]
names = {os.path.basename(f) for f in files}
# What a fresh clone holds: the listed files and their folders. A file on this disk that git
# ignores (a study's database, a build) is not in a fresh clone, so it does not count.
present = set(files) | {os.path.dirname(f) for f in files}
for f in list(present):
    while f:
        f = os.path.dirname(f)
        present.add(f)


def ignored(named):
    """True for a path that .gitignore marks as written by a command (results/**/*.db, ...)."""
    if listed.returncode != 0:
        return os.path.exists(named)
    return subprocess.run(["git", "check-ignore", "-q", "--no-index", named]).returncode == 0


def exists(named):
    folder = named.endswith("/")  # a .gitignore pattern "dir/" matches only a name that says it is one
    named = os.path.normpath(named)
    return named in present or ignored(named + "/" if folder else named)

# Written by commands when they run, or made by the build: named before they exist.
WRITTEN = (re.compile(r"^results/run(/|$)"), re.compile(r"^results/\w+/db(/|$)"),
           re.compile(r"^include/softdrop/version\.hpp$"), re.compile(r"^results/calibration/FILE$"))
FOLDERS = "docs|src|optimizer|include|tests|results|scripts|bench|examples|python|fuzz|tools"
# A path under a folder of the repository, not inside a longer word, a variable ($src/...) or a URL.
PATH = re.compile(r"(?<![\w/.$}{:-])((?:" + FOLDERS + r")/[A-Za-z0-9_./+-]*[A-Za-z0-9_/])")
BARE = re.compile(r"(?<![\w/.$}{:-])([A-Za-z][\w-]*\.(?:md|cpp|hpp|inc|sh))\b")
TEXT = (".md", ".cpp", ".hpp", ".h", ".inc", ".py", ".pyi", ".sh", ".txt", ".toml")


def comments(path, text):
    """The text a reader reads as prose: all of a Markdown file, the comments of code."""
    if path.endswith(".md"):
        return text
    marker = "//" if path.endswith((".cpp", ".hpp", ".h", ".inc")) else "#"
    lines = []
    for line in text.splitlines():
        at = line.find(marker)
        if at >= 0:
            lines.append(line[at:])
        elif marker == "//" and line.strip().startswith(("*", "/*")):
            lines.append(line)
    return "\n".join(lines)


stale = []
for path in files:
    if not (path.endswith(TEXT) or os.path.basename(path) == "CMakeLists.txt") or path == "tests/repository_paths.py":
        continue
    with open(path, encoding="utf-8", errors="replace") as f:
        text = f.read()
    for match in PATH.finditer(text):
        named = match.group(1)
        if any(w.search(named) for w in WRITTEN):
            continue
        if not (exists(named) or exists(os.path.join(os.path.dirname(path), named))):
            stale.append(f"{path}: names {named}, which is not in the repository")
    for match in BARE.finditer(comments(path, text)):
        if match.group(1) not in names:
            stale.append(f"{path}: names {match.group(1)}, which is not in the repository")
print("\n".join(sorted(set(stale))) or f"repository paths: every path named in {len(files)} files exists")
sys.exit(1 if stale else 0)
