"""Tables and figure of run.sh from its sweeps' reports (db/*.csv)."""
import os

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import pandas as pd  # noqa: E402

here = os.path.dirname(os.path.abspath(__file__))
kinds = ["overlapping", "sequential-0.13", "relaxed-0.13", "relaxed-0.3", "relaxed-0.4"]


def paper(phi):
    return 1.58 - 0.58 * phi ** 3.87


frames = []
for kind in kinds:
    f = pd.read_csv(os.path.join(here, "db", f"{kind}.csv"))
    f.insert(0, "medium", kind)
    f["passed_fraction"] = f["passed"] / f["droplets"]
    f["paper_tortuosity"] = paper(f["porosity"])
    f["minus_paper"] = f["mean_tortuosity"] - f["paper_tortuosity"]
    f["minus_paper_in_se"] = f["minus_paper"] / f["media_standard_error"]
    frames.append(f)
points = pd.concat(frames, ignore_index=True)
points.to_csv(os.path.join(here, "points.csv"), index=False)

table = points.pivot(index="target_porosity", columns="medium", values=["passed_fraction", "minus_paper"])
table = table.reindex(columns=kinds, level=1)
table.columns = [f"{what}:{kind}" for what, kind in table.columns]
table.round(4).to_csv(os.path.join(here, "relaxed.csv"))

fig, (left, right) = plt.subplots(1, 2, figsize=(10, 4), constrained_layout=True)
for kind in kinds:
    p = points[points["medium"] == kind]
    style = "k-o" if kind == "overlapping" else ("--s" if kind.startswith("sequential") else "-^")
    left.plot(p["porosity"], 100 * p["passed_fraction"], style, label=kind)
    right.errorbar(p["porosity"], p["minus_paper"], yerr=p["media_standard_error"], fmt=style, capsize=3, label=kind)
left.set_xlabel("porosity φ")
left.set_ylabel("droplets passing (%)")
left.legend()
right.axhline(0, color="grey", lw=0.8)
right.set_xlabel("porosity φ")
right.set_ylabel("⟨T⟩ − f(φ), the paper's fit")
fig.suptitle("The default droplet on overlapping, sequential and relaxed non-overlapping media (held-out)")
fig.savefig(os.path.join(here, "relaxed.png"), dpi=120)
