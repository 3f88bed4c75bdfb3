#!/usr/bin/env bash
# Is the default rest test safe for the default droplet? 200 droplets from the same starts on each
# of four media (overlapping and non-overlapping, phi = 0.6 and 0.75; medium seed 77, start seed
# 78), with the stuck test alone (--rest-window 0) and with the default rest test; every droplet's
# verdict and T compared. Writes defaults.csv (one row per medium). About 3 minutes on 2 cores.
#     bash results/stuck_test/defaults.sh
set -euo pipefail
cd "$(dirname "$0")"
BIN=${SOFTDROP:-../../build/softdrop}
tmp=$(mktemp -d); trap 'rm -rf "$tmp"' EXIT
for kind in overlapping non-overlapping; do
  for phi in 0.6 0.75; do
    common=(simulate --kind "$kind" --porosity "$phi" --medium-seed 77 --seed 78 --droplets 200 --quiet)
    "$BIN" "${common[@]}" --runs "$tmp/$kind-$phi-ref.csv" --rest-window 0 > /dev/null
    "$BIN" "${common[@]}" --runs "$tmp/$kind-$phi-rest.csv" > /dev/null
  done
done
/usr/bin/python3 - "$tmp" <<'PY'
import glob, os, sys
import pandas as pd
tmp, rows = sys.argv[1], []
for ref_path in sorted(glob.glob(f"{tmp}/*-ref.csv")):
    name = os.path.basename(ref_path)[:-len("-ref.csv")]
    ref, rest = pd.read_csv(ref_path), pd.read_csv(ref_path.replace("-ref.csv", "-rest.csv"))
    kind, phi = name.rsplit("-", 1)
    passed = ref["outcome"] == "passed"
    rows.append({"kind": kind, "porosity": float(phi), "droplets": len(ref), "passed": int(passed.sum()),
                 "verdicts_changed": int((ref["outcome"] != rest["outcome"]).sum()),
                 "t_changed": int((ref["tortuosity"][passed] != rest["tortuosity"][passed]).sum()),
                 "steps_ratio": round(ref["steps"].sum() / rest["steps"].sum(), 2)})
pd.DataFrame(rows).to_csv("defaults.csv", index=False)
print(pd.DataFrame(rows).to_string(index=False))
PY
