"""An independent check of softdrop's flow solve on Matyka, Khalili and Koza's (2008) squares: the
same boxes as squares.py (same L, A, porosity and seed), solved by a lattice-Boltzmann method, the
method those authors used, and the hydrodynamic T = <|u|> / <u_y> over the pore pixels compared box
by box with the committed Stokes value (squares_L_A*.csv).

The scheme: D2Q9, two-relaxation-time collision with the "magic" product (tau+ - 1/2)(tau- - 1/2)
= 3/16, for which halfway bounce-back puts the no-slip wall exactly on the pixel edge, as the
staggered Stokes solve has it, and the steady flow does not depend on the viscosity; a linear
(Stokes) equilibrium, so no inertia at all; a uniform body force along the rows with Guo's
correction; periodic in both directions. A node is a pixel centre. The run ends when T and the mean
velocity change by less than 1e-9 and 1e-7 (relative) over `check` steps. Poiseuille flow between
two walls is exact: the mean velocity is g (h^2 + 1/2) / (12 nu) over the h pixel centres.

    /usr/bin/python3 lbm_squares.py L A PHI SEEDS [TAU]   (writes lbm_squares_L_A_PHI.csv)
    /usr/bin/python3 lbm_squares.py --poiseuille          (the channel check)

TAU is tau+ (default 3, nu = 5/6). At phi = 0.9 it gives the T of tau+ = 1 to 2e-6 in a quarter of
the steps; at lower porosities it relaxes slowly and, with squares of 2 pixels, its steady T moves
by 0.003, so the phi = 0.7 boxes use tau+ = 1 (README.md).
"""
import os
import sys
import time

import numpy as np
import pandas as pd

from squares import squares

# Lattice velocities (along columns, along rows), weights and opposites.
CX = np.array([0, 1, 0, -1, 0, 1, -1, -1, 1])
CY = np.array([0, 0, 1, 0, -1, 1, 1, -1, -1])
WEIGHT = np.array([4 / 9] + [1 / 9] * 4 + [1 / 36] * 4)
OPPOSITE = np.array([0, 3, 4, 1, 2, 7, 8, 5, 6])


def moved(a, dy, dx):
    """a moved by (dy, dx), periodic: the result at [y, x] is a[y - dy, x - dx]."""
    return np.roll(np.roll(a, dy, axis=0), dx, axis=1)


def flow(pore, tau_plus=3.0, force=1e-6, check=100, max_steps=400_000):
    """Steady creeping flow through the boolean image `pore` (True: fluid) driven along the rows.
    Returns (T, mean velocity along the rows over all pixels, steps)."""
    ny, nx = pore.shape
    solid = ~pore
    omega_plus = 1 / tau_plus
    omega_minus = 1 / (0.5 + (3 / 16) / (tau_plus - 0.5))
    w = WEIGHT[:, None, None]
    ex, ey = CX.astype(float), CY.astype(float)
    cx, cy = ex[:, None, None], ey[:, None, None]
    # Guo's forcing for the linear equilibrium: only the antisymmetric (odd) part.
    source = ((1 - omega_minus / 2) * 3 * WEIGHT * CY * force)[:, None, None]
    # A population that would come from a solid node bounces back at the edge: f_i(x) = f*_opp(x).
    bounce = np.array([moved(solid, CY[i], CX[i]) & pore for i in range(9)])
    f = np.broadcast_to(w, (9, ny, nx)).copy()
    post = np.empty_like(f)
    last, steps = None, 0
    while steps < max_steps:
        rho = f.sum(axis=0)
        jx = np.tensordot(ex, f, axes=1)
        jy = np.tensordot(ey, f, axes=1) + force / 2 * rho
        neq = f - w * (rho + 3 * (cx * jx + cy * jy))
        neq_opposite = neq[OPPOSITE]  # the sum and the difference: twice the even and the odd part
        post[...] = (f - omega_plus * 0.5 * (neq + neq_opposite) - omega_minus * 0.5 * (neq - neq_opposite)
                     + source * rho)
        for i in range(9):
            f[i] = moved(post[i], CY[i], CX[i])
        np.copyto(f, post[OPPOSITE], where=bounce)
        f[:, solid] = WEIGHT[:, None]
        steps += 1
        if steps % check == 0:
            ux = np.where(pore, jx / rho, 0.0)
            uy = np.where(pore, jy / rho, 0.0)
            T = np.hypot(ux, uy)[pore].sum() / uy[pore].sum()
            mean = uy.mean()
            if last is not None and abs(T - last[0]) < 1e-9 * T and abs(mean - last[1]) < 1e-7 * abs(mean):
                return T, mean, steps
            last = (T, mean)
    raise RuntimeError(f"lbm_squares: not steady after {max_steps} steps")


def poiseuille(h=20, tau_plus=3.0, force=1e-6):
    pore = np.ones((8, h + 2), dtype=bool)
    pore[:, 0] = pore[:, -1] = False
    T, mean, steps = flow(pore, tau_plus, force)
    nu = (tau_plus - 0.5) / 3
    exact = force * (h * h + 0.5) / (12 * nu) * h / (h + 2)  # mean over every pixel, walls included
    print(f"Poiseuille, h = {h}, tau+ = {tau_plus}: T = {T:.12f}, mean u = {mean:.10e}, "
          f"exact {exact:.10e}, relative error {mean / exact - 1:.1e}, {steps} steps")


def main():
    if sys.argv[1:] == ["--poiseuille"]:
        for tau in (1.0, 3.0):
            poiseuille(tau_plus=tau)
        return
    L, A = int(sys.argv[1]), int(sys.argv[2])
    phi, seeds = float(sys.argv[3]), int(sys.argv[4])
    tau = float(sys.argv[5]) if len(sys.argv) > 5 else 3.0
    here = os.path.dirname(os.path.abspath(__file__))
    # The Stokes values of the same boxes, where squares.py has solved them.
    stokes = {}
    for name in sorted(os.listdir(here)):
        if name.startswith(f"squares_{L}_{A}.") or name.startswith(f"squares_{L}_{A}_"):
            frame = pd.read_csv(os.path.join(here, name))
            for _, r in frame[np.isclose(frame["target_porosity"], phi)].iterrows():
                stokes[int(r["seed"])] = r["hydrodynamic_tortuosity"]
    rows = []
    for seed in range(1, seeds + 1):
        start = time.time()
        pore = squares(L, A, phi, seed)
        T, mean, steps = flow(pore, tau)
        row = {"target_porosity": phi, "seed": seed, "porosity": pore.mean(), "lbm_tortuosity": T,
               "lbm_p": (T - 1) / -np.log(pore.mean()), "lbm_steps": steps, "tau_plus": tau,
               "stokes_tortuosity": stokes.get(seed, np.nan)}
        row["difference"] = row["lbm_tortuosity"] - row["stokes_tortuosity"]
        rows.append(row)
        print(f"phi {phi} seed {seed}: LBM T = {T:.6f}, Stokes T = {row['stokes_tortuosity']:.6f}, "
              f"{steps} steps, {time.time() - start:.0f} s", file=sys.stderr)
    frame = pd.DataFrame(rows)
    frame.to_csv(os.path.join(here, f"lbm_squares_{L}_{A}_{phi}.csv"), index=False)
    print(frame.to_string(index=False))
    frame["stokes_p"] = (frame["stokes_tortuosity"] - 1) / -np.log(frame["porosity"])
    means = frame[["lbm_tortuosity", "stokes_tortuosity", "difference", "lbm_p", "stokes_p"]].agg(["mean", "sem"])
    print(f"L = {L}, A = {A}, phi = {phi}, {len(frame)} boxes: mean and standard error over the boxes")
    print(means.round(4).to_string())


if __name__ == "__main__":
    main()
