"""Tables of time_step_held_out.sh from its runs' sweep-report files (time_step_held_out/*.csv)."""
import os

import numpy as np
import pandas as pd

here = os.path.dirname(os.path.abspath(__file__))
runs = os.path.join(here, "time_step_held_out")
# (label, run, dt, the finer dt): rows compare run-dt with run-finer, medium by medium.
pairs = [("defaults", "defaults", "6e-6", "3e-6"), ("exponential", "exponential", "6e-6", "3e-6"),
         ("explicit-nu", "explicit-nu", "3.5e-6", "1.75e-6"),
         ("defaults-more", "defaults-more", "6e-6", "3e-6"),  # 300 more media (seed 55502), phi 0.45 and 0.5
         ("defaults-more-quarter", "defaults-more", "6e-6", "1.5e-6")]  # the same at dt / 4, phi 0.45


def paper(phi):
    return 1.58 - 0.58 * np.asarray(phi) ** 3.87


points, rows, paired, seen = [], [], {}, set()
for droplet, run, dt, finer in pairs:
    a = pd.read_csv(os.path.join(runs, f"{run}-{dt}.csv")).set_index("target_porosity", drop=False)
    b = pd.read_csv(os.path.join(runs, f"{run}-{finer}.csv")).set_index("target_porosity", drop=False)
    ma = pd.read_csv(os.path.join(runs, f"{run}-{dt}-media.csv"))
    mb = pd.read_csv(os.path.join(runs, f"{run}-{finer}-media.csv"))
    for frame, step in ((a, dt), (b, finer)):
        if (run, step) not in seen:
            seen.add((run, step))
            points.append(frame.assign(droplet=run, dt=float(step), minus_paper=frame["mean_tortuosity"] - paper(frame["porosity"])))
    for target in [t for t in a.index if t in b.index]:  # the porosities both runs have
        x = ma[ma["target_porosity"] == target].set_index("medium_index")
        y = mb[mb["target_porosity"] == target].set_index("medium_index")
        both = (x["passed"] > 0) & (y["passed"] > 0)
        d = (y["mean_tortuosity"] - x["mean_tortuosity"])[both]
        paired[droplet, target] = d
        ra, rb = a.loc[target], b.loc[target]
        rows.append({"droplet": droplet, "dt": float(dt), "dt_finer": float(finer), "target_porosity": target,
                     "porosity": ra["porosity"], "t_dt": ra["mean_tortuosity"], "t_finer": rb["mean_tortuosity"],
                     "difference": rb["mean_tortuosity"] - ra["mean_tortuosity"],
                     "difference_se": float(np.hypot(ra["media_standard_error"], rb["media_standard_error"])),
                     "per_medium_difference": d.mean(), "per_medium_difference_se": d.std(ddof=1) / np.sqrt(len(d)),
                     "media_both_passed": int(both.sum()),
                     "t_dt_minus_paper": ra["mean_tortuosity"] - paper(ra["porosity"])})
# The defaults' 100 and 300 more media together, medium by medium (rows "defaults-400": the pooled
# columns are left empty, since the two runs' media are not one sweep).
for target in sorted({t for (name, t) in paired if name == "defaults-more"}):
    d = pd.concat([paired["defaults", target], paired["defaults-more", target]])
    rows.append({"droplet": "defaults-400", "dt": 6e-6, "dt_finer": 3e-6, "target_porosity": target,
                 "per_medium_difference": d.mean(), "per_medium_difference_se": d.std(ddof=1) / np.sqrt(len(d)),
                 "media_both_passed": len(d)})
pd.concat(points).to_csv(os.path.join(here, "time_step_held_out_points.csv"), index=False)
pd.DataFrame(rows).to_csv(os.path.join(here, "time_step_held_out.csv"), index=False)
