"""softdrop.plot: each picture draws what it is given, into a new figure or the caller's axes."""
import os
import subprocess

import matplotlib

matplotlib.use("Agg")  # (no display in the tests)
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
import pandas as pd  # noqa: E402
import pytest  # noqa: E402

import softdrop  # noqa: E402
import softdrop.plot  # noqa: E402

import balloon  # noqa: E402


def grain_circles(ax):
    return [p for p in ax.patches if isinstance(p, matplotlib.patches.Circle)]


def test_a_medium_is_drawn_with_the_periodic_copies_of_grains_that_cross_a_side():
    m = softdrop.Medium.generate("non-overlapping", porosity=0.8, seed=1)
    g = np.asarray(m.grains)
    crossing = int(np.sum(g[:, 0] - g[:, 2] < 0) + np.sum(g[:, 0] + g[:, 2] > m.width))
    fig = softdrop.plot.medium(m, touched=[0])
    circles = grain_circles(fig.axes[0])
    assert len(circles) == len(g) + crossing
    assert circles[0].center == pytest.approx((g[0, 0], g[0, 1])) and circles[0].radius == pytest.approx(g[0, 2])
    assert circles[0].get_facecolor() != circles[-1].get_facecolor() or len(g) == 1  # touched grain 0 is darker
    plt.close(fig)


def test_grains_are_shaded_by_the_share_of_droplets_that_touched_them():
    m = softdrop.Medium.generate("non-overlapping", porosity=0.8, seed=1)
    n = len(np.asarray(m.grains))
    shares = np.zeros(n)
    shares[:3] = [1.0, 0.5, 0.02]
    circles = grain_circles(softdrop.plot.medium(m, shares=shares).axes[0])
    darkness = {i: 1 - c.get_facecolor()[0] for c, (_, _, _, i) in zip(circles, softdrop.plot._grain_copies(m))}
    assert darkness[0] > darkness[1] > darkness[2] > darkness[3] == pytest.approx(1 - 0.55)
    for bad, match in (([0.5], "each of the"), (np.full(n, 1.5), r"\[0, 1\]"), (np.full(n, np.nan), r"\[0, 1\]")):
        with pytest.raises(ValueError, match=match):
            softdrop.plot.medium(m, shares=bad)
    # paths() shades by its runs: the share of the two droplets that touched each grain.
    runs = [softdrop.simulate(m, x0=x, path=True) for x in (100, 200)]
    touched = [set(run.touched_grains) for run in runs]
    assert touched[0] & touched[1] and touched[0] ^ touched[1]  # grains both touched, and one only
    fig = softdrop.plot.paths(m, runs)
    for circle, (_, _, _, i) in zip(grain_circles(fig.axes[0]), softdrop.plot._grain_copies(m)):
        share = sum(i in t for t in touched) / 2
        weight = 0.15 + 0.85 * share if share else 0
        assert circle.get_facecolor()[0] == pytest.approx(0.55 + weight * (0.25 - 0.55)), i
    plt.close("all")


def test_paths_are_cut_where_they_wrap_and_drawn_into_the_callers_axes():
    m = softdrop.Medium.generate("non-overlapping", porosity=0.8, seed=1)
    run = softdrop.simulate(m, x0=20, path=True)
    x = run.path[:, 0]
    wraps = int(np.sum(np.abs(np.diff(x)) > 0.5 * m.width))
    fig, ax = plt.subplots()
    assert softdrop.plot.paths(m, [run, run.path], ax=ax) is fig
    assert len(ax.lines) == 2 * (wraps + 1)
    drawn = np.concatenate([line.get_xdata() for line in ax.lines[: wraps + 1]])
    assert np.array_equal(drawn, x)
    with pytest.raises(ValueError, match="rows of"):
        softdrop.plot.paths(m, [np.zeros((3, 4))])
    plt.close(fig)


def test_the_best_curve_is_history_best_with_the_re_runs_and_held_out_values(tmp_path):
    db = tmp_path / "search.db"
    cli = os.environ.get("SOFTDROP_CLI", "softdrop")
    subprocess.run([cli, "optimize", "--db", str(db), "--grains", "16", "--width", "160", "--height", "120",
                    "--medium-seed", "2", "--stuck-window", "0.1", "--stuck-distance", "1", "--generations", "3",
                    "--lambda", "2", "--quiet", "--objective", "mean", "--starts", "4", "--validate-starts", "8",
                    *balloon.ARGS], check=True, capture_output=True)
    h = softdrop.read_history(db, arrangements=False)
    fig = softdrop.plot.best_curve(db, run=1)
    ax = fig.axes[0]
    best, reruns = ax.lines[0], ax.lines[1]
    # The kept arrangements' values as history --best gives them, flat to the last generation.
    kept = h["best"]
    assert np.array_equal(best.get_xdata(), list(kept["generation"]) + [3])
    assert np.array_equal(best.get_ydata(), list(kept["best_tortuosity"]) + [kept["best_tortuosity"].iloc[-1]])
    assert best.get_label() == "in the search (the mean of its re-runs)"
    assert np.array_equal(reruns.get_ydata(), h["generations"]["parent_tortuosity"].to_numpy(), equal_nan=True)
    assert len(ax.containers) == 1  # the held-out value, with its error bar
    with pytest.raises(ValueError, match="run = 2"):
        softdrop.plot.best_curve(h, run=2)
    plt.close("all")


def test_porosity_has_the_points_and_the_papers_fit():
    points = pd.DataFrame({"porosity": [0.6, 0.8], "mean_tortuosity": [1.4, 1.2], "standard_error": [0.02, 0.01],
                           "media_standard_error": [0.04, 0.03], "per_medium_tortuosity": [1.45, 1.22],
                           "per_medium_standard_error": [0.05, 0.02]})
    fig = softdrop.plot.porosity(points)
    fit = fig.axes[0].lines[-1]
    assert np.allclose(fit.get_ydata(), 1.58 - 0.58 * fit.get_xdata() ** 3.87)
    assert softdrop.plot.paper_fit(1.0) == pytest.approx(1.0)
    # The error bars are the media's unless told otherwise.
    bars = fig.axes[0].containers[0]
    assert np.array_equal(bars.lines[0].get_ydata(), [1.4, 1.2])
    segments = bars.lines[2][0].get_segments()
    assert [s[1][1] - s[0][1] for s in segments] == pytest.approx([0.08, 0.06])
    # The labels speak one notation, the program's pictures' (φ, ⟨T⟩, a minus sign), not ASCII stand-ins.
    texts = [fig.axes[0].get_ylabel(), fig.axes[0].get_xlabel()] + [t.get_text() for t in fig.axes[0].get_legend().get_texts()]
    assert "⟨T⟩" in texts and "porosity φ" in texts and any("1.58 − 0.58 φ^3.87" in t for t in texts)
    assert not any(ascii in t for t in texts for ascii in ("<T>", "phi", " - "))
    plt.close(fig)

    # Per medium first, with the residuals against the paper's f in units of the error.
    fig = softdrop.plot.porosity(points, mean="per_medium_tortuosity", error="per_medium_standard_error", residuals=True)
    top, low = fig.axes
    assert np.array_equal(top.containers[0].lines[0].get_ydata(), [1.45, 1.22])
    pull = low.lines[-1].get_ydata()
    f = 1.58 - 0.58 * np.array([0.6, 0.8]) ** 3.87
    assert pull == pytest.approx((np.array([1.45, 1.22]) - f) / np.array([0.05, 0.02]))
    plt.close(fig)
    with pytest.raises(ValueError, match="no column 'per_medium_tortuosity'"):
        softdrop.plot.porosity(points.drop(columns="per_medium_tortuosity"), mean="per_medium_tortuosity")
    with pytest.raises(ValueError, match="leave ax out"):
        softdrop.plot.porosity(points, ax=plt.figure().add_subplot(), residuals=True)
    plt.close("all")


def test_the_area_trace_is_the_runs_area_ratio():
    m = softdrop.Medium.generate("non-overlapping", porosity=0.8, seed=1)
    run = softdrop.simulate(m, x0=200, trace=True)
    fig = softdrop.plot.area_trace(run)
    assert np.array_equal(fig.axes[0].lines[0].get_ydata(), run.trace[:, 2])
    with pytest.raises(ValueError, match="trace=True"):
        softdrop.plot.area_trace(softdrop.simulate(m, x0=200))
    plt.close(fig)
