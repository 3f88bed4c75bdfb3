#!/usr/bin/env bash
# How high T can go in the default search box: a droplet on a straight ramp of equal grains that
# winds down the 300 x 300 periodic box at a slope angle (surface gaps of 26 % of the radius, twice
# the spacing rule's minimum; the droplet starting above the middle of the top, as in the search). T of one
# ramp is about 1 / sin(angle), as long as the droplet rolls instead of coming to rest in a dip
# between two grains. Writes ramps.csv (radius, angle_degrees, grains, outcome, tortuosity).
#   bash results/search/ramps.sh
set -euo pipefail
cd "$(dirname "$0")/../.."
# Measured with the balloon (results/calibration/balloon.toml).
S="${SOFTDROP:-./build/softdrop} --config results/calibration/balloon.toml"
OUT=results/search
tmp=$(mktemp -d); trap 'rm -rf "$tmp"' EXIT
echo "radius,angle_degrees,grains,outcome,tortuosity" > "$OUT/ramps.csv"
for r in 4 5 6 8 12 16; do
  for angle in 18 20 22 24 26 28 30; do
    # grains along the line from (W/2 - 10, H - r - 1) down at `angle`, centres 2r (1 + 0.13) + 0.01 apart
    awk -v r="$r" -v a="$angle" 'BEGIN {
      W = 300; H = 300; pi = atan2(0, -1); t = a * pi / 180; d = 2 * r * 1.13 + 0.01
      x = W / 2 - 10; y = H - r - 1; n = 0
      printf "x,y,r,width,height,periodic\n"
      while (y > r && n < 200) { xx = x - W * int(x / W); printf "%.17g,%.17g,%g,%g,%g,true\n", xx, y, r, W, H; x += d * cos(t); y -= d * sin(t); n++ }
    }' > "$tmp/ramp.csv"
    grains=$(($(wc -l < "$tmp/ramp.csv") - 1))
    result=$($S simulate --medium "$tmp/ramp.csv" --x0 150 --format json)
    outcome=$(sed -n 's/^ *"outcome": "\([a-z]*\)".*/\1/p' <<< "$result" | head -1)
    t=$(sed -n 's/^ *"tortuosity": \([0-9.e+-]*\).*/\1/p' <<< "$result" | head -1)
    echo "$r,$angle,$grains,$outcome,$t" >> "$OUT/ramps.csv"
  done
done
cat "$OUT/ramps.csv"
