"""Joins tension.sh's groups (tension/S_G1_G2_TAG.csv and tension/S_G1_G2_TAG_points.csv, and
tension/balloon_16_32_nu*.csv) into tension.csv and tension_points.csv, one row per setting (and
porosity) with the group's scale S and grain radii (in units of S) as columns, and draws
tension.png: <T>(phi) and the share of droplets passed, for a few settings, against the paper's
fit f(phi) and the defaults (final_points.csv, setting 0).

    /usr/bin/python3 results/calibration/plot_tension.py
"""
import glob
import os

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
import pandas as pd  # noqa: E402

HERE = os.path.dirname(os.path.abspath(__file__))
# (scale, grains from, grains to, label) of the settings drawn; scale 1 is the balloon.
DRAWN = [(8400, 8, 16, "nu 100"), (8400, 16, 32, "nu 1000, c_c 0"), (8400, 16, 48, "nu 1500, c_c 0"),
         (8400, 20, 40, "nu 30"), (1, 16, 32, "viscosity=1500")]


def joined():
    """(settings, points) of every group, with scale, grains_from and grains_to columns."""
    settings, points = [], []
    for path in sorted(glob.glob(os.path.join(HERE, "tension", "*_points.csv"))):
        name = os.path.basename(path)[: -len("_points.csv")]
        scale, g1, g2, _ = name.split("_")
        group = {"scale": 1 if scale == "balloon" else int(scale), "grains_from": int(g1), "grains_to": int(g2)}
        setting = pd.read_csv(path.replace("_points.csv", ".csv"))
        point = pd.read_csv(path).merge(setting[["setting", "label"]], on="setting")
        for table in (setting, point):
            for i, (column, value) in enumerate(group.items()):
                table.insert(i, column, value)
        settings.append(setting)
        points.append(point)
    return pd.concat(settings, ignore_index=True), pd.concat(points, ignore_index=True)


def main():
    settings, points = joined()
    settings.to_csv(os.path.join(HERE, "tension.csv"), index=False)
    points.to_csv(os.path.join(HERE, "tension_points.csv"), index=False)

    defaults = pd.read_csv(os.path.join(HERE, "final_points.csv"))
    defaults = defaults[defaults.setting == 0]
    fig, (ax_t, ax_p) = plt.subplots(1, 2, figsize=(12, 4.8))
    phi = np.linspace(0.45, 1.0, 100)
    ax_t.plot(phi, 1.58 - 0.58 * phi ** 3.87, "k-", lw=2, label="paper: 1.58 - 0.58 phi^3.87")
    shown = defaults[defaults.passed >= 2]
    ax_t.errorbar(shown.porosity, shown.mean_tortuosity, yerr=shown.standard_error, fmt="ks--", mfc="white", capsize=3,
                  label="defaults: balloon, grains 8-16")
    ax_p.plot(defaults.porosity, defaults.passed / defaults.droplets, "ks--", mfc="white", label="defaults")
    for scale, g1, g2, label in DRAWN:
        rows = points[(points.scale == scale) & (points.grains_from == g1) & (points.grains_to == g2)
                      & (points.label == label)]
        if rows.empty:
            continue
        name = (f"balloon, {label.replace('viscosity=', 'nu ')}" if scale == 1 else f"S = {scale}, {label}") + \
            f", grains {g1}-{g2}" + (" S" if scale > 1 else "")
        shown = rows[rows.passed >= 2]
        line = ax_t.errorbar(shown.porosity, shown.mean_tortuosity, yerr=shown.standard_error, fmt="o-", capsize=3, label=name)
        ax_p.plot(rows.porosity, rows.passed / rows.droplets, "o-", color=line[0].get_color(), label=name)
    ax_t.set(xlabel="porosity phi", ylabel="<T> of the droplets that passed (2 or more)",
             title="Mean tortuosity against the paper")
    ax_p.set(xlabel="porosity phi", ylabel="share of the 200 droplets that passed", ylim=(0, 1.02),
             title="Passage")
    ax_t.legend(fontsize=7)
    ax_p.legend(fontsize=7)
    fig.tight_layout()
    fig.savefig(os.path.join(HERE, "tension.png"), dpi=110)


if __name__ == "__main__":
    main()
