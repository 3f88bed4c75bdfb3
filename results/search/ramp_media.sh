#!/usr/bin/env bash
# How high a medium's held-out <T> can go on the default problem, with media built by hand: the
# 20 grains of the default problem's starting medium (medium seed 1, radii 18 to 47) laid along one
# straight ramp that winds down the 500 x 500 periodic box at a slope angle, consecutive grains at
# the spacing rule's least gap (0.13 x the larger radius; grains left at the bottom start another
# ramp from the top, a third of the box to the side); the droplet of the defaults from 200
# random starts (softdrop validate, seed 1, at dt only). A droplet that lands on the ramp and rolls
# along it has T near 1 / sin(angle) for the stretch it rolls. Writes ramp_media.csv.
#   bash results/search/ramp_media.sh
set -euo pipefail
cd "$(dirname "$0")/../.."
S=${SOFTDROP:-./build/softdrop}
# The droplet calibrated for the exponential viscosity step (the defaults' <T>(phi) within 0.02),
# which ran these numbers: pinned, so that they reproduce to the bit.
DROPLET=(--config results/calibration/exponential.toml)
OUT=results/search
tmp=$(mktemp -d); trap 'rm -rf "$tmp"' EXIT
"$S" "${DROPLET[@]}" optimize --db "$tmp/g0.db" --generations 0 --quiet --validate-starts 0 > /dev/null
"$S" export --db "$tmp/g0.db" --run 1 --generation 0 -o "$tmp/g0.json" 2> /dev/null
echo "order,angle_degrees,spacing_ok,passed,mean_tortuosity,standard_error,q1,median,q3" > "$OUT/ramp_media.csv"
for order in up down; do
  for angle in 8 12 16 20 24 28 32 40 50; do
    ok=$(python3 - "$tmp/g0.json" "$angle" "$order" "$tmp/ramp.json" <<'PY'
import json, math, sys
src, angle, order, out = sys.argv[1], float(sys.argv[2]), sys.argv[3], sys.argv[4]
m = json.load(open(src))
W, H = m["width"], m["height"]
radii = sorted(g["r"] for g in m["grains"])  # up: small grains first, at the top
if order == "down":
    radii.reverse()
t = math.radians(angle)
x, y, grains = W / 2, H - radii[0] - 1, []
for i, r in enumerate(radii):
    if i > 0:
        d = radii[i - 1] + r + 0.13 * max(radii[i - 1], r) + 0.01
        x, y = x + d * math.cos(t), y - d * math.sin(t)
        if y < r:  # the bottom: the grains left start another ramp from the top, a third of the box on
            x, y = x + W / 3, H - r - 1
    grains.append({"x": x % W, "y": y, "r": r})
def gap_ok(a, b):
    dx = abs(a["x"] - b["x"]); dx = min(dx, W - dx)
    return math.hypot(dx, a["y"] - b["y"]) >= a["r"] + b["r"] + 0.13 * max(a["r"], b["r"])
ok = all(g["r"] <= g["y"] <= H - g["r"] for g in grains) and all(
    gap_ok(a, b) for i, a in enumerate(grains) for b in grains[i + 1:])
m["grains"] = grains
json.dump(m, open(out, "w"))
print("true" if ok else "false")
PY
)
    v=$("$S" "${DROPLET[@]}" validate --medium "$tmp/ramp.json" --starts 200 --seed 1 --same-dt-only --format json --quiet)
    python3 -c "
import json, sys
d = json.loads(sys.argv[1])['at_dt']
f = lambda k: '' if d[k] is None else '%.4f' % d[k]
print(','.join(['$order', '$angle', '$ok', str(d['passed']), f('mean_tortuosity'), f('standard_error'), f('q1'), f('median'), f('q3')]))
" "$v" >> "$OUT/ramp_media.csv"
  done
done
cat "$OUT/ramp_media.csv"
