"""area.png: Delta S = S / S0 of the two droplets of one pair that met, at phi = 0.79, against time
since the first began, with the centre's height (area_example.csv, from summarize.py).

    figure.py [DIR]   (DIR is not read: the figure comes from the committed CSV)
"""
import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import pandas as pd  # noqa: E402

d = pd.read_csv("area_example.csv")
fig, (top, bottom) = plt.subplots(2, 1, figsize=(7, 6), sharex=True)
for order, g in d.groupby("order"):
    label = "first" if order == 1 else "second"
    top.plot(g["time"], g["ratio"], label=label)
    bottom.plot(g["time"], g["y"], label=label)
top.axhline(1.0, color="grey", lw=0.5)
top.set_ylabel("ΔS = S / S₀")
top.legend()
top.set_title(f"two droplets, φ = 0.79 non-overlapping (medium {d['medium'].iloc[0]}, pair {d['droplet'].iloc[0]})")
bottom.set_ylabel("centre y")
bottom.set_xlabel("time since the first droplet began (time units)")
fig.tight_layout()
fig.savefig("area.png", dpi=120)
