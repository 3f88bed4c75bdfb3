"""A first notebook session with softdrop's Python module.

    bash scripts/build.sh                       # builds build/python/softdrop too
    PYTHONPATH=build/python python3 examples/python/droplets.py

Generates a medium, pushes one droplet and draws its path, then 200 droplets from random starts
as a pandas DataFrame and a rigid disc from the same starts, then runs a 30-generation search and plots its curve from the history. The
pictures need matplotlib (python3-matplotlib); without it the numbers are printed only.
"""
import os
import tempfile

import softdrop

medium = softdrop.Medium.generate("non-overlapping", porosity=0.8, seed=1)
print(medium, "porosity", medium.porosity())

run = softdrop.simulate(medium, x0=200, path=True)
print("one droplet:", run.outcome, "T =", run.tortuosity, "after", run.steps, "steps")

frame = softdrop.simulate_many(medium, 200, seed=3)
print(frame.groupby("outcome").size())
print("mean T of the passed droplets:", frame.loc[frame.outcome == "passed", "tortuosity"].mean())

# A rigid disc of the droplet's radius from the same starts, moved by gravity alone: it cannot
# squeeze or bounce, so it stops in the first gap narrower than itself.
rigid = softdrop.rigid_descent(medium, frame.start_x, radius=8)
print("a rigid disc of radius 8 passes", (rigid.outcome == "passed").mean(), "of the same starts")

# A 30-generation search on the defaults (8 candidates a generation), written to an SQLite history
# as `softdrop optimize` writes it, with a line every 10 generations from the callback; then its history read back as DataFrames.
db = os.path.join(tempfile.mkdtemp(), "search.db")


def report(event):
    if event["generation"] % 10 == 0:
        print(f"  generation {event['generation']}: best T {event['best_tortuosity']:.4f}")
    return True  # False would stop the search here (resume it with softdrop.optimize(db, resume=run))


summary = softdrop.optimize(db, generations=30, callback=report, quiet=True)
history = softdrop.read_history(db)
curve = history["generations"]
print("search: best T", summary["best_tortuosity"], "after", summary["evaluations"], "evaluations")
best = softdrop.best_arrangement(db, run=1)

try:
    import matplotlib.pyplot as plt
except ImportError:
    plt = None
if plt is not None:
    fig, ax = plt.subplots(figsize=(6, 6))
    for x, y, r in medium.grains:
        ax.add_patch(plt.Circle((x, y), r, color="0.6"))
    ax.plot(run.path[:, 0] % medium.width, run.path[:, 1], ".", markersize=1, color="crimson")
    ax.set_xlim(0, medium.width), ax.set_ylim(0, medium.height), ax.set_aspect("equal")
    fig.savefig("droplet_path.png", dpi=150)
    fig, ax = plt.subplots(figsize=(6, 3.5))
    ax.step(curve["generation"], curve["best_tortuosity"], where="post")
    ax.set_xlabel("generation"), ax.set_ylabel("best T")
    fig.savefig("search_curve.png", dpi=150)
    print("wrote droplet_path.png and search_curve.png")
