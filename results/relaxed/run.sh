#!/usr/bin/env bash
# Passage and <T> at low porosity on non-overlapping media: does a medium of non-overlapping grains
# let more droplets through than an overlapping one, as the paper reports? The default droplet on
# held-out media (seed 1 of the sweep's held-out stream), 9 porosities (0.5 to 0.9) x 100 media x
# 20 droplets, grains of radii 16 to 48 in 500 x 500, for
#   overlapping        the Boolean model (the defaults)
#   sequential-0.13    non-overlapping by random sequential addition, gap 0.13 (its default)
#   relaxed-0.13       non-overlapping by relaxation (--kind relaxed), gap 0.13
#   relaxed-0.3        the same with gap 0.3
#   relaxed-0.4        the same with gap 0.4, the widest relaxation reaches at porosity 0.5
# (the gap is the least surface gap as a fraction of the larger radius of the two grains).
# Writes points.csv (one row per medium kind and porosity), relaxed.csv (the table of README.md)
# and relaxed.png. About 10 minutes on 2 cores. SOFTDROP=path runs another build.
#     bash results/relaxed/run.sh
set -euo pipefail
cd "$(dirname "$0")"
BIN=${SOFTDROP:-../../build/softdrop}
mkdir -p db
run() {  # name, medium options...
  local name=$1
  shift
  "$BIN" sweep --db "db/$name.db" --porosities 0.5,0.55,0.6,0.65,0.7,0.75,0.8,0.85,0.9 --media 100 \
    --droplets 20 "$@" --quiet --format csv > /dev/null
  "$BIN" sweep-report --db "db/$name.db" --format csv > "db/$name.csv"
}
run overlapping
run sequential-0.13 --kind non-overlapping --gap 0.13
run relaxed-0.13 --kind relaxed --gap 0.13
run relaxed-0.3 --kind relaxed --gap 0.3
run relaxed-0.4 --kind relaxed --gap 0.4
/usr/bin/python3 relaxed.py
