#!/usr/bin/env bash
# Regenerates the pictures of README.md and docs/pictures.md (docs/images/), about 8 minutes on
# 2 cores. Each command is also written beside its picture in docs/pictures.md. SOFTDROP=path
# draws with another build (and skips building this one).
set -euo pipefail
cd "$(dirname "$0")/.."
if [[ -z ${SOFTDROP:-} ]]; then
  bash scripts/build.sh > build.log 2>&1 || { cat build.log; exit 1; }
fi
S=${SOFTDROP:-./build/softdrop}
out=docs/images
mkdir -p "$out"
# The paper's Fig. 2: a droplet squeezing through a pore of three grains.
$S render snapshots --medium examples/pore.json --x0 100 --times 0.0084,0.014,0.018,0.021,0.025,0.03 \
  --size 480 -o $out/pore_snapshots.png
# The same droplet as an animation (0.005 time units per second: 8 s).
$S render animation --medium examples/pore.json --x0 100 --speed 0.005 --size 240 -o $out/pore.gif --quiet
# 300 droplets through one overlapping medium: much-used channels and trapping spots darken.
$S render paths --porosity 0.85 --droplets 300 --seed 1 --size 600 --path-colour "#101010" -o $out/paths.png \
  --quiet
# A relaxed medium with wide gaps at porosity 0.5, and one of sequential addition at 0.5.
$S render medium --kind relaxed --porosity 0.5 --gap 0.4 --size 400 -o $out/medium_relaxed.png
$S render medium --kind non-overlapping --porosity 0.5 --size 400 -o $out/medium_sequential.png
# The pore space's diffusion, its creeping flow and shortest paths (softdrop tortuosity).
$S tortuosity --porosity 0.7 --medium-seed 3 --starts 0 --quiet --picture $out/pore_space.png \
  --flow-picture $out/pore_flow.png > /dev/null
# The area trace of one droplet through non-overlapping grains at porosity 0.79 (the paper's figure).
$S render trace --kind non-overlapping --porosity 0.79 --medium-seed 4 --size 600 -o $out/trace.png 2> /dev/null
# Two 2000-evaluation searches, the paper's hill climb (lambda 2) and the default strategy: the best
# arrangement of the second with its value against generation (the starting medium held out too),
# and both curves against evaluations.
rm -f build/figures.db build/figures.db-wal build/figures.db-shm build/figures_es.db build/figures_es.db-*
$S optimize --db build/figures.db --generations 1000 --lambda 2 --strategy paper --relocate-every 0 --quiet
$S optimize --db build/figures_es.db --generations 250 --quiet
$S validate --db build/figures_es.db --run 1 --generation 0 --quiet > /dev/null
$S render search --db build/figures_es.db --run 1 --size 600 -o $out/search.png --curve $out/search_curve.png
$S render curves --db build/figures.db --db build/figures_es.db --size 600 -o $out/curves.png
