"""The `softdrop` command a pip install puts on the PATH: the program built with the package."""
import os
import sys


def main():
    program = os.path.join(os.path.dirname(os.path.abspath(__file__)), "bin", "softdrop")
    if not os.access(program, os.X_OK):
        sys.exit(f"softdrop: {program}: the package was installed without its program (reinstall it with pip)")
    os.execv(program, [program] + sys.argv[1:])
