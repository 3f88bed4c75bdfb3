#!/usr/bin/env bash
# Sets up, builds and runs the main job on defaults: 16 droplets through a random medium,
# summary on stdout, per-droplet results in results/run/. Extra arguments go to `softdrop simulate`.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/build.sh > build.log 2>&1 || { cat build.log; exit 1; }
mkdir -p results/run
./build/softdrop simulate --droplets 16 --runs results/run/droplets.csv \
  --save-medium results/run/medium.json --json results/run/summary.json "$@"
