#!/usr/bin/env bash
# Two droplets, one after the other: does the second follow the first's path, and does it free a
# trapped first droplet or clog behind it? The default droplet; the second released once the first
# is 40 length units (five droplet radii) below its start, from the same x. Nothing here was tuned:
# the release distance was set before any run, and the media (seeds 9401 to 9420 a porosity) are
# used by no other study.
#   1. pairs_<phi>_<m>.csv: 20 pairs a medium (`simulate --second-droplet distance --runs`), on 20
#      media at each of phi = 0.79 (non-overlapping, the case the paper cites) and 0.5, 0.6, 0.7
#      (overlapping, where droplets get trapped); alone_<phi>_<m>.csv: the same 20 starts, one
#      droplet each, to tell what the second changed;
#      The phi = 0.79 pairs again released at 20 and 80 (pairs_0.79after<A>_<m>.csv), and at half
#      the time step (pairs_0.79half_<m>.csv);
#   2. traces: at phi = 0.79, each droplet's area and path every 50 steps (media 9401 to 9405);
#   3. summarize.py writes pairs.csv (per porosity) and area.csv (Delta S of each droplet);
#      figure.py draws area.png.
# About 3 minutes on 2 cores.
#     bash results/two_droplets/run.sh
set -euo pipefail
cd "$(dirname "$0")"
BIN=${SOFTDROP:-../../build/softdrop}
tmp=$(mktemp -d); trap 'rm -rf "$tmp"' EXIT
medium() {  # phi -> the medium options
  if [ "$1" = 0.79 ]; then echo "--porosity 0.79 --kind non-overlapping"; else echo "--porosity $1"; fi
}
for phi in 0.79 0.5 0.6 0.7; do
  for m in $(seq 9401 9420); do
    # shellcheck disable=SC2046
    "$BIN" simulate $(medium "$phi") --medium-seed "$m" --droplets 20 --seed "$m" --quiet \
      --second-droplet distance --second-after 40 --runs "$tmp/pairs_${phi}_${m}.csv" > /dev/null
    # shellcheck disable=SC2046
    "$BIN" simulate $(medium "$phi") --medium-seed "$m" --droplets 20 --seed "$m" --quiet \
      --runs "$tmp/alone_${phi}_${m}.csv" > /dev/null
  done
done
# The same pairs at phi = 0.79 released at 20 and at 80 below the first's start: does the answer
# depend on the release?
for after in 20 80; do
  for m in $(seq 9401 9420); do
    # shellcheck disable=SC2046
    "$BIN" simulate $(medium 0.79) --medium-seed "$m" --droplets 20 --seed "$m" --quiet \
      --second-droplet distance --second-after "$after" --runs "$tmp/pairs_0.79after${after}_${m}.csv" > /dev/null
    cp "$tmp/alone_0.79_${m}.csv" "$tmp/alone_0.79after${after}_${m}.csv"
  done
done
# The same pairs at phi = 0.79 at half the time step (twice the step budget): does the answer hold?
for m in $(seq 9401 9420); do
  # shellcheck disable=SC2046
  "$BIN" simulate $(medium 0.79) --medium-seed "$m" --droplets 20 --seed "$m" --quiet --dt 3e-6 --max-steps 24000000 \
    --second-droplet distance --second-after 40 --runs "$tmp/pairs_0.79half_${m}.csv" > /dev/null
  # shellcheck disable=SC2046
  "$BIN" simulate $(medium 0.79) --medium-seed "$m" --droplets 20 --seed "$m" --quiet --dt 3e-6 --max-steps 24000000 \
    --runs "$tmp/alone_0.79half_${m}.csv" > /dev/null
done
for m in $(seq 9401 9405); do
  # shellcheck disable=SC2046
  "$BIN" simulate $(medium 0.79) --medium-seed "$m" --droplets 20 --seed "$m" --quiet \
    --second-droplet distance --second-after 40 --trace "$tmp/trace_${m}.csv" --trace-interval 50 \
    --paths "$tmp/paths_${m}.csv" --path-interval 50 --runs "$tmp/traced_${m}.csv" > /dev/null
done
/usr/bin/python3 summarize.py "$tmp"
/usr/bin/python3 figure.py "$tmp"
cat pairs.csv area.csv
