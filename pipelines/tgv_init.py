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
In a 3-D store (cases/bench_tgv3d, a periodic cube of side L) it sets the 3-D vortex of Taylor
and Green (1937), the classic initial state of Brachet et al. (1983), with k = 2 pi/L:
    u =  U sin(k x) cos(k y) cos(k z)
    v = -U cos(k x) sin(k y) cos(k z)
    w =  0
    p =  (rho0 U^2 / 16) (cos(2 k x) + cos(2 k y)) (cos(2 k z) + 2)
and rho from p likewise.
With --perturb SEED (an integer, 0: none, the default) each velocity component is multiplied
by 1 + 2e-7 N(0, 1) (numpy's default_rng(SEED)), about one float32 ulp, the store's precision:
the members of an ensemble. The vortex's decay rate at these resolutions is chaotic in the
particles' disorder (cases/taylor_green_vres2d/README.md: such a perturbation moves the error
at dp 0.02 m from 0.019 to 0.024), so one run's error is one sample of a spread.
A line naming this command is put at the top of the store's history. Exit 0 on success, 1 on
a store that is not a 2-D or 3-D vres store with fluid, 2 on a usage error.
"""
import argparse
import os
import sys

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from vresstore import domains, fail, note_history, open_rw  # noqa: E402

TOOL = "tgv_init.py"


def vortex(dim, k, U, rho0):
    """The vortex at the angles k = 2 pi (position - origin) / L (columns x, y, z): the velocity
    (n x 3, m/s) and the pressure (Pa), the 2-D one in the x-z plane or the 3-D one."""
    kx, ky, kz = k[:, 0], k[:, 1], k[:, 2]
    vel = np.zeros((k.shape[0], 3))
    if dim == 2:
        vel[:, 0], vel[:, 2] = -U * np.cos(kx) * np.sin(kz), U * np.sin(kx) * np.cos(kz)
        return vel, -(rho0 * U * U / 4) * (np.cos(2 * kx) + np.cos(2 * kz))
    vel[:, 0] = U * np.sin(kx) * np.cos(ky) * np.cos(kz)
    vel[:, 1] = -U * np.cos(kx) * np.sin(ky) * np.cos(kz)
    return vel, (rho0 * U * U / 16) * (np.cos(2 * kx) + np.cos(2 * ky)) * (np.cos(2 * kz) + 2)


def main():
    """Outline: read each domain's fluid and buffer, compute the fields, write them back, note the history."""
    ap = argparse.ArgumentParser(prog="tgv_init.py", description=__doc__.split("\n")[0])
    ap.add_argument("store")
    ap.add_argument("--U", type=float, default=1.0, help="velocity scale (m/s)")
    ap.add_argument("--perturb", type=int, default=0, metavar="SEED",
                    help="multiply the velocities by 1 + 2e-7 N(0,1), seeded (0: no perturbation)")
    args = ap.parse_args()
    rng = np.random.default_rng(args.perturb) if args.perturb else None
    with open_rw(TOOL, args.store) as f:
        dim = int(f.attrs.get("dim", 0))
        if dim not in (2, 3):
            fail(TOOL, f"{args.store}: not a 2-D or 3-D vres store")
        axes = (0, 2) if dim == 2 else (0, 1, 2)  # the periodic axes: x-z plane in 2-D
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
        lo = np.zeros(3)
        lo[list(axes)] = pos0[moved][:, axes].min(axis=0)
        L = pos0[moved, 0].max() - lo[0] + dp0
        for a in axes[1:]:
            if abs((pos0[moved, a].max() - lo[a] + dp0) - L) > 1e-6 * L:
                fail(TOOL, f"{args.store}: the fluid is not a {'square' if dim == 2 else 'cube'}")
        U = args.U
        nset = 0
        for name in names:
            d = f["Domains/" + name]
            sel = np.isin(d["Type"][:], (0, 1))
            pos = d["Position"][:]
            vel = d["Velocity"][:]
            u, p_sel = vortex(dim, 2 * np.pi * (pos[sel] - lo + dp0 / 2) / L, U, rho0)
            if rng is not None:
                for a in ((0, 2) if dim == 2 else (0, 1)):  # the components that are not zero
                    u[:, a] = u[:, a] * (1 + 2e-7 * rng.standard_normal(u.shape[0]))
            vel[sel] = u
            p = d["Pressure"][:]
            p[sel] = p_sel
            rho = d["Density"][:]
            rho[sel] = rho0 * (1 + p[sel] / B) ** (1 / gamma)
            d["Velocity"][...] = vel
            d["Pressure"][...] = p
            d["Density"][...] = rho
            nset += int(sel.sum())
        note_history(f, TOOL)
    print(f"tgv_init.py: {args.store}: {dim}-D Taylor-Green vortex set on {nset} fluid and buffer particles "
          f"in {len(names)} domain(s), L = {L:g} m, U = {U:g} m/s"
          + (f", perturbed (seed {args.perturb})" if args.perturb else ""), file=sys.stderr)


if __name__ == "__main__":
    main()
