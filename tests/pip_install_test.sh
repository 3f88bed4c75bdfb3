#!/usr/bin/env bash
# `pip install --no-build-isolation .` into a fresh venv (with the system's numpy and pandas; this
# machine reaches no package index), reusing the build tree; then, from outside the source tree,
# the package imports, its `softdrop` command runs the program, and the Python example runs.
#   bash tests/pip_install_test.sh BUILD_DIR SOURCE_DIR PYTHON
set -euo pipefail
build=$(realpath "$1"); src=$(realpath "$2"); py=$3
work=$(mktemp -d); trap 'rm -rf "$work"' EXIT
"$py" -m venv --system-site-packages "$work/venv"
SOFTDROP_BUILD_DIR=$build "$work/venv/bin/python" -m pip install --no-build-isolation --no-index --quiet "$src" \
  > "$work/pip.log" 2>&1 || { cat "$work/pip.log"; echo "pip_install_test: pip install failed"; exit 1; }
cd "$work"
where=$("$work/venv/bin/python" -c "import softdrop; print(softdrop.__file__)")
[[ $where == "$work/venv/"* ]] || { echo "pip_install_test: imported $where, not the installed package"; exit 1; }
t=$("$work/venv/bin/python" -c "
import softdrop, softdrop.plot
m = softdrop.Medium.generate('non-overlapping', porosity=0.8, seed=1)
print(repr(softdrop.simulate(m, x0=200).tortuosity))")
for f in py.typed __init__.pyi _core.pyi plot.pyi; do  # the type stubs, for editors and type checkers
  [[ -f $(dirname "$where")/$f ]] || { echo "pip_install_test: $f not installed"; exit 1; }
done
version=$("$work/venv/bin/python" -c "import softdrop; print(softdrop.__version__)")
[[ $("$work/venv/bin/softdrop" --version) == "$version" ]] || { echo "pip_install_test: the softdrop command"; exit 1; }
theirs=$("$work/venv/bin/softdrop" simulate --porosity 0.8 --kind non-overlapping --medium-seed 1 --x0 200 --format json |
  sed -n 's/^ *"tortuosity": \([^,]*\),*$/\1/p' | head -1)
echo "python: T = $t; the installed program: T = $theirs"
[[ $(printf '%.17g' "$t") == $(printf '%.17g' "$theirs") ]] || { echo "pip_install_test: they differ"; exit 1; }
"$work/venv/bin/python" "$src/examples/python/droplets.py" > "$work/example.out" 2>&1 ||
  { cat "$work/example.out"; echo "pip_install_test: the example failed"; exit 1; }
echo "pip_install_test: ok ($where)"
