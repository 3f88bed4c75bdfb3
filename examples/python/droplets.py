"""A first notebook session with softdrop's Python module.

    bash scripts/build.sh                       # builds build/python/softdrop too
    PYTHONPATH=build/python python3 examples/python/droplets.py

Generates a medium, pushes one droplet and draws its path, then 200 droplets from random starts
as a pandas DataFrame. The picture needs matplotlib (python3-matplotlib); without it the numbers
are printed only.
"""
import softdrop

medium = softdrop.Medium.generate("non-overlapping", porosity=0.8, seed=1)
print(medium, "porosity", medium.porosity())

run = softdrop.simulate(medium, x0=200, path=True)
print("one droplet:", run.outcome, "T =", run.tortuosity, "after", run.steps, "steps")

frame = softdrop.simulate_many(medium, 200, seed=3)
print(frame.groupby("outcome").size())
print("mean T of the passed droplets:", frame.loc[frame.outcome == "passed", "tortuosity"].mean())

try:
    import matplotlib.pyplot as plt
except ImportError:
    plt = None
if plt is not None:
    fig, ax = plt.subplots(figsize=(6, 6))
    for x, y, r in medium.grains:
        ax.add_patch(plt.Circle((x, y), r, color="0.6"))
    ax.plot(run.path[:, 1] % medium.width, run.path[:, 2], ".", markersize=1, color="crimson")
    ax.set_xlim(0, medium.width), ax.set_ylim(0, medium.height), ax.set_aspect("equal")
    fig.savefig("droplet_path.png", dpi=150)
    print("wrote droplet_path.png")
