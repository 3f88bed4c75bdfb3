"""Tables of time_step_held_out.sh from its runs' sweep-report files (time_step_held_out/*.csv)."""
import os

import numpy as np
import pandas as pd

here = os.path.dirname(os.path.abspath(__file__))
runs = os.path.join(here, "time_step_held_out")
pairs = [("defaults", "6e-6", "3e-6"), ("exponential", "6e-6", "3e-6"), ("explicit-nu", "3.5e-6", "1.75e-6"),
         ("defaults-more", "6e-6", "3e-6")]  # 300 more media (seed 55502) at porosities 0.45 and 0.5


def paper(phi):
    return 1.58 - 0.58 * np.asarray(phi) ** 3.87


points, rows, paired = [], [], {}
for droplet, dt, half in pairs:
    a = pd.read_csv(os.path.join(runs, f"{droplet}-{dt}.csv"))
    b = pd.read_csv(os.path.join(runs, f"{droplet}-{half}.csv"))
    ma = pd.read_csv(os.path.join(runs, f"{droplet}-{dt}-media.csv"))
    mb = pd.read_csv(os.path.join(runs, f"{droplet}-{half}-media.csv"))
    for frame, step in ((a, dt), (b, half)):
        points.append(frame.assign(droplet=droplet, dt=float(step), minus_paper=frame["mean_t"] - paper(frame["phi"])))
    for i in range(len(a)):
        target = a["target_phi"][i]
        x = ma[ma["target_phi"] == target].set_index("medium_index")
        y = mb[mb["target_phi"] == target].set_index("medium_index")
        both = (x["passed"] > 0) & (y["passed"] > 0)
        d = (y["mean_t"] - x["mean_t"])[both]
        paired[droplet, target] = d
        rows.append({"droplet": droplet, "dt": float(dt), "target_phi": target, "phi": a["phi"][i],
                     "t_dt": a["mean_t"][i], "t_half_dt": b["mean_t"][i],
                     "difference": b["mean_t"][i] - a["mean_t"][i],
                     "difference_se": float(np.hypot(a["media_standard_error"][i], b["media_standard_error"][i])),
                     "per_medium_difference": d.mean(), "per_medium_difference_se": d.std(ddof=1) / np.sqrt(len(d)),
                     "media_both_passed": int(both.sum()),
                     "t_dt_minus_paper": a["mean_t"][i] - paper(a["phi"][i])})
# The defaults' 100 and 300 more media together, medium by medium (rows "defaults-400": the pooled
# columns are left empty, since the two runs' media are not one sweep).
for target in sorted({t for (name, t) in paired if name == "defaults-more"}):
    d = pd.concat([paired["defaults", target], paired["defaults-more", target]])
    rows.append({"droplet": "defaults-400", "dt": 6e-6, "target_phi": target,
                 "per_medium_difference": d.mean(), "per_medium_difference_se": d.std(ddof=1) / np.sqrt(len(d)),
                 "media_both_passed": len(d)})
pd.concat(points).to_csv(os.path.join(here, "time_step_held_out_points.csv"), index=False)
pd.DataFrame(rows).to_csv(os.path.join(here, "time_step_held_out.csv"), index=False)
