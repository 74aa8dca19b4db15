#!/usr/bin/env python3
"""pipelines/tgv_init.py - set the Taylor-Green vortex initial state in a vres store.

    python3 pipelines/tgv_init.py STORE [--U U]

The case format (DualSPHysics' GenCase XML) has no way to give a velocity field that varies in
space, so cases/taylor_green2d/check writes it into the store vres-gencase made, in place,
with h5py (the store is plain HDF5, vres-store(5)). For the fluid and buffer particles of every
domain (D0, D1, ...: run it after vres-partition, which redraws each domain at its own dp), in
the x-z plane, with L the side of the periodic square (the extent of the root domain's fluid
and buffer particles plus its dp; the origin is half a root dp below the lowest of them) and U
the velocity scale (default 1 m/s):
    u = -U cos(2 pi x/L) sin(2 pi z/L)
    w =  U sin(2 pi x/L) cos(2 pi z/L)
    p = -(rho0 U^2 / 4) (cos(4 pi x/L) + cos(4 pi z/L))
and the density from p by the inverse Tait equation rho = rho0 (1 + p/B)^(1/gamma), with
rhop0, b and gamma from /Parameters, so that density and pressure agree as vres-run expects.
(refdata/taylor_green_2d_analytical.csv: Adami, Hu & Adams 2013; PySPH's taylor_green.)
With --perturb SEED (an integer, 0: none, the default) each velocity component is multiplied
by 1 + 2e-7 N(0, 1) (numpy's default_rng(SEED)), about one float32 ulp, the store's precision:
the members of an ensemble. The vortex's decay rate at these resolutions is chaotic in the
particles' disorder (cases/taylor_green_vres2d/README.md: such a perturbation moves the error
at dp 0.02 m from 0.019 to 0.024), so one run's error is one sample of a spread.
A line naming this command is put at the top of the store's history. Exit 0 on success, 1 on
a store that is not a 2-D vres store with fluid, 2 on a usage error.
"""
import argparse
import os
import sys

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from vresstore import domains, fail, note_history, open_rw  # noqa: E402

TOOL = "tgv_init.py"


def main():
    """Outline: read each domain's fluid and buffer, compute the fields, write them back, note the history."""
    ap = argparse.ArgumentParser(prog="tgv_init.py", description=__doc__.split("\n")[0])
    ap.add_argument("store")
    ap.add_argument("--U", type=float, default=1.0, help="velocity scale (m/s)")
    ap.add_argument("--perturb", type=int, default=0, metavar="SEED",
                    help="multiply the velocities by 1 + 2e-7 N(0,1), seeded (0: no perturbation)")
    args = ap.parse_args()
    rng = np.random.default_rng(args.perturb) if args.perturb else None
    with open_rw(TOOL, args.store, dim=2) as f:
        par = f["Parameters"].attrs
        rho0, B, gamma = float(par["rhop0"]), float(par["B"]), float(par["gamma"])
        names = domains(f)
        if not names or names[0] != "D0":
            fail(TOOL, f"{args.store}: no root domain D0")
        d0 = f["Domains/D0"]
        dp0 = float(d0.attrs["dp"])
        moved = np.isin(d0["Type"][:], (0, 1))  # fluid and buffer: together they tile the square
        if not (d0["Type"][:] == 0).any():
            fail(TOOL, f"{args.store}: no fluid particles")
        pos0 = d0["Position"][:]
        xmin, zmin = pos0[moved, 0].min(), pos0[moved, 2].min()
        L = pos0[moved, 0].max() - xmin + dp0
        if abs((pos0[moved, 2].max() - zmin + dp0) - L) > 1e-6 * L:
            fail(TOOL, f"{args.store}: the fluid is not a square")
        U = args.U
        nset = 0
        for name in names:
            d = f["Domains/" + name]
            sel = np.isin(d["Type"][:], (0, 1))
            pos = d["Position"][:]
            x, z = pos[sel, 0], pos[sel, 2]
            kx, kz = 2 * np.pi * (x - xmin + dp0 / 2) / L, 2 * np.pi * (z - zmin + dp0 / 2) / L
            vel = d["Velocity"][:]
            u, w = -U * np.cos(kx) * np.sin(kz), U * np.sin(kx) * np.cos(kz)
            if rng is not None:
                u = u * (1 + 2e-7 * rng.standard_normal(u.shape))
                w = w * (1 + 2e-7 * rng.standard_normal(w.shape))
            vel[sel, 0] = u
            vel[sel, 1] = 0.0
            vel[sel, 2] = w
            p = d["Pressure"][:]
            p[sel] = -(rho0 * U * U / 4) * (np.cos(2 * kx) + np.cos(2 * kz))
            rho = d["Density"][:]
            rho[sel] = rho0 * (1 + p[sel] / B) ** (1 / gamma)
            d["Velocity"][...] = vel
            d["Pressure"][...] = p
            d["Density"][...] = rho
            nset += int(sel.sum())
        note_history(f, TOOL)
    print(f"tgv_init.py: {args.store}: Taylor-Green vortex set on {nset} fluid and buffer particles "
          f"in {len(names)} domain(s), L = {L:g} m, U = {U:g} m/s"
          + (f", perturbed (seed {args.perturb})" if args.perturb else ""), file=sys.stderr)


if __name__ == "__main__":
    main()
