#!/usr/bin/env bash
# Installs the build into a scratch prefix (cmake --install), checks that each installed header
# compiles on its own and keeps the step's private machinery out, builds
# examples/library/push_droplet.cpp against the installed headers and libraries only, and checks
# that it gives the program's own tortuosity for the same droplet, to the last digit; builds
# examples/library/search_run.cpp, a search through the installed service, resumed midway, and
# checks that it keeps the program's best T; the installed configs are the options they stand for.
#   bash tests/install_test.sh BUILD_DIR SOURCE_DIR CXX
set -euo pipefail
build=$(realpath "$1"); src=$(realpath "$2"); cxx=$3
prefix=$(mktemp -d); trap 'rm -rf "$prefix"' EXIT
cmake --install "$build" --prefix "$prefix" > /dev/null
for f in bin/softdrop include/softdrop/simulation.hpp include/softdrop/version.hpp lib/libsoftdrop_sim.a \
         share/softdrop/explicit.toml share/softdrop/exponential.toml share/softdrop/balloon.toml share/softdrop/passage.toml \
         share/softdrop/relaxed.toml; do
  [[ -e $prefix/$f ]] || { echo "install_test: $f was not installed"; exit 1; }
done
# The installed headers are the user's API: each compiles on its own, and none names the step's
# private machinery (its vector widths, lane-by-lane blocks and interleaved drivers).
headers=("$prefix"/include/softdrop/*.hpp)
for h in "${headers[@]}"; do
  "$cxx" -std=c++20 -fsyntax-only -I "$prefix/include" -x c++ "$h" ||
    { echo "install_test: ${h#"$prefix"/} does not compile on its own"; exit 1; }
done
private='VectorWidth|vector_width|lane_policy|run_interleaved|LaneExchange|DropletJob|interleaved_lanes|fewest_block|speculative_lanes|GrainGrid|ContactCache|kStepStages|LaneBlock|StepContext'
if named=$(grep -lE "$private" "${headers[@]}"); then
  echo "install_test: installed headers name the step's private machinery: ${named//$prefix\//}"; exit 1
fi
(( ${#headers[@]} <= 10 )) || { echo "install_test: ${#headers[@]} installed headers, more than the API's 10"; exit 1; }
echo "installed headers: ${#headers[@]}, each compiles on its own"
"$cxx" -std=c++20 -O2 "$src/examples/library/push_droplet.cpp" -I "$prefix/include" -L "$prefix/lib" \
  -lsoftdrop_sim -lsoftdrop_media -lsoftdrop_util -ltbb -lgmp -lmpfr -lpng -ltiff -o "$prefix/push_droplet"
mine=$("$prefix/push_droplet" 250 | sed -n 's/^tortuosity //p')
t() { sed -n 's/^ *"tortuosity": \([^,]*\),*$/\1/p;T;q'; }  # the run's T in simulate's JSON
theirs=$("$prefix/bin/softdrop" simulate --x0 250 --format json | t)
echo "library: T = $mine; softdrop simulate: T = $theirs"
[[ -n $mine && $(printf '%.17g' "$mine") == $(printf '%.17g' "$theirs") ]]
# A search through the installed service (examples/library/search_run.cpp), stopped at generation
# 2 and resumed to 4, keeps the history `softdrop optimize` writes for the same search.
"$cxx" -std=c++20 -O2 "$src/examples/library/search_run.cpp" -I "$prefix/include" -L "$prefix/lib" \
  -lsoftdrop_service -lsoftdrop_store -lsoftdrop_opt -lsoftdrop_studies -lsoftdrop_sim -lsoftdrop_media \
  -lsoftdrop_util -lSQLiteCpp -lsqlite3 -lpagmo -lnlopt -lcholmod -ltbb -lgmp -lmpfr -lpng -ltiff \
  -o "$prefix/search_run"
"$prefix/search_run" "$prefix/lib.db" 2 > /dev/null
lib_best=$("$prefix/search_run" "$prefix/lib.db" 4 | sed -n 's/^best T \([^ ]*\) .*/\1/p')
cli_best=$("$prefix/bin/softdrop" optimize --db "$prefix/cli.db" --generations 4 --lambda 4 --starts 8 \
  --validate-starts 0 --quiet --format json | sed -n 's/^ *"best_tortuosity": \([^,]*\),*$/\1/p')
echo "library search, resumed: best T = $lib_best; softdrop optimize: best T = $cli_best"
[[ -n $lib_best && $(printf '%.17g' "$lib_best") == $(printf '%.17g' "$cli_best") ]]
# An installed config gives the T of the options it stands for, which differs from the defaults'.
#   config_is FILE OPTION...
config_is() {
  local file=$1; shift
  local installed options
  installed=$("$prefix/bin/softdrop" --config "$prefix/share/softdrop/$file" simulate --x0 250 --format json | t)
  options=$("$prefix/bin/softdrop" simulate --x0 250 "$@" --format json | t)
  echo "$file: T = $installed; its options: T = $options"
  [[ -n $installed && $installed == "$options" && $installed != "$theirs" ]]
}
config_is explicit.toml --viscosity-step explicit --viscosity 1.37e5 --dt 3.5e-6
config_is exponential.toml --viscosity-step exponential --viscosity 2.8e5
config_is passage.toml --r-min 26 --r-max 50 --radius 5 --nrt 1.59e9 --kc 2.5e8 --viscosity 1e6 \
  --viscosity-step exponential  # the grains as well as the droplet
config_is relaxed.toml --kind relaxed --gap 0.4  # a medium, not a droplet
# The Python package, where the prefix's python3 finds it (when the module was built).
if [[ -f $build/python/softdrop/__init__.py ]]; then
  site=$(dirname "$(find "$prefix/lib" -path '*/softdrop/__init__.py' -print -quit)")
  [[ -x $site/bin/softdrop && -n $(find "$site" -name '_core*.so' -print -quit) ]] ||
    { echo "install_test: the Python package was not installed whole ($site)"; exit 1; }
  py=$(PYTHONPATH=$(dirname "$site") /usr/bin/python3 -c "
import softdrop
print(repr(softdrop.simulate(softdrop.Medium.generate(), x0=250).tortuosity))")
  echo "installed Python package: T = $py"
  [[ $(printf '%.17g' "$py") == $(printf '%.17g' "$theirs") ]]
fi
