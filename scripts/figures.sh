#!/usr/bin/env bash
# Regenerates the pictures of README.md and docs/pictures.md (docs/images/), about 3 minutes on
# 2 cores. Each command is also written beside its picture in docs/pictures.md.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/build.sh > build.log 2>&1 || { cat build.log; exit 1; }
S=./build/softdrop
out=docs/images
mkdir -p "$out"
# The paper's Fig. 2: a droplet squeezing through a pore of three grains.
$S render snapshots --medium examples/pore.json --x0 100 --times 0.0084,0.014,0.018,0.021,0.025,0.03 \
  --size 480 -o $out/pore_snapshots.png
# The same droplet as an animation (0.005 time units per second: 8 s).
$S render animation --medium examples/pore.json --x0 100 --speed 0.005 --size 240 -o $out/pore.gif
# 300 droplets through one overlapping medium: much-used channels and trapping spots darken.
$S render paths --porosity 0.85 --droplets 300 --seed 1 --size 600 --path-colour "#101010" -o $out/paths.png
# A 1000-generation search (lambda 2), its best arrangement and its best-T curve.
rm -f build/figures.db build/figures.db-wal build/figures.db-shm
$S optimize --db build/figures.db --generations 1000 --lambda 2 --strategy paper --relocate-every 0 --quiet
$S render search --db build/figures.db --run 1 --size 600 -o $out/search.png --curve $out/search_curve.png
