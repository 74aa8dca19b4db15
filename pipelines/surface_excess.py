#!/usr/bin/python3
"""surface_excess.py - the pressure excess of an SPH lattice's top rows under a free surface at rest.

    surface_excess.py [--xrange LO HI] [--yrange LO HI] RUNDIR...

For each single-resolution run of still water (one domain; e.g. cases/hydrostatic_vres2d/check
--single -o RUNDIR), over the snapshots of the second half of the run: the fluid particles whose
x (and y, 3D) lie in the given ranges (away from the side walls), grouped by lattice row from
the top (row i: depth (i + 1/2) dp below the surface, the surface dp/2 above the first
snapshot's highest fluid particle), and each row's mean pressure excess over rho0 g times its
mean depth, as a fraction of rho0 g h: (p - rho0 g d) / (rho0 g h); then phi, that less the
bulk's own deviation (a straight line in q fitted to the rows from --fit-from down: the
column's slope error, which is not the surface's). kernels/surface.h's VRES_SURFACE_PHI* are
rows 0..2's phi (kernels/surface.h says which runs). Prints one line per row and run: run, dp,
h, row, q = d / h, the raw excess, phi, the standard deviation of the row's per-snapshot means,
and the samples.
"""
import argparse
import glob
import os
import sys

import h5py
import numpy as np


def snapshots(run):
    """The run's snapshots in order of time."""
    files = sorted(glob.glob(os.path.join(run, "snap_*.h5")))
    if not files:
        sys.exit(f"surface_excess.py: {run}: no snapshots")
    return files


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--xrange", nargs=2, type=float, default=[0.3, 0.7], help="columns kept in x (m)")
    ap.add_argument("--yrange", nargs=2, type=float, default=None, help="columns kept in y (m), 3D")
    ap.add_argument("--rows", type=int, default=10, help="rows read from the top")
    ap.add_argument("--fit-from", type=int, default=4, help="first row of the bulk's fit")
    ap.add_argument("runs", nargs="+")
    a = ap.parse_args()
    print("# run\tdp_m\th_m\trow\tq\traw\tphi\tsd\tsamples")
    for run in a.runs:
        files = snapshots(run)
        with h5py.File(files[0], "r") as f:
            if len(f["Domains"]) != 1:
                sys.exit(f"surface_excess.py: {files[0]}: {len(f['Domains'])} domains, not a single-resolution run")
            d0 = f["Domains/D0"]
            dp, h = float(d0.attrs["dp"]), float(d0.attrs["h"])
            P = f["Parameters"].attrs
            rho0, g = float(P["rhop0"]), float(np.linalg.norm(P["gravity"]))
            t = d0["Type"][:] == 0
            H = float(d0["Position"][:, 2][t].max()) + dp / 2
        with h5py.File(files[-1], "r") as f:
            tend = float(f.attrs["time"])
        means = [[] for _ in range(a.rows)]
        n = [0] * a.rows
        for fn in files:
            with h5py.File(fn, "r") as f:
                if float(f.attrs["time"]) <= tend / 2:
                    continue
                d0 = f["Domains/D0"]
                x = d0["Position"][:]
                p = d0["Pressure"][:].astype(float)
                keep = (d0["Type"][:] == 0) & (x[:, 0] >= a.xrange[0]) & (x[:, 0] <= a.xrange[1])
                if a.yrange:
                    keep &= (x[:, 1] >= a.yrange[0]) & (x[:, 1] <= a.yrange[1])
                d = H - x[keep, 2]
                row = np.floor(d / dp).astype(int)
                for i in range(a.rows):
                    s = row == i
                    if s.any():
                        means[i].append((d[s].mean(), ((p[keep][s] - rho0 * g * d[s]) / (rho0 * g * h)).mean()))
                        n[i] += int(s.sum())
        if not means[0]:
            sys.exit(f"surface_excess.py: {run}: no fluid in the columns over the second half")
        q = np.array([np.mean([m[0] for m in means[i]]) / h for i in range(a.rows)])
        raw = np.array([np.mean([m[1] for m in means[i]]) for i in range(a.rows)])
        sd = [np.std([m[1] for m in means[i]]) for i in range(a.rows)]
        fit = np.polyfit(q[a.fit_from:], raw[a.fit_from:], 1)
        phi = raw - np.polyval(fit, q)
        for i in range(a.rows):
            print(f"{run}\t{dp:g}\t{h:.6g}\t{i}\t{q[i]:.4f}\t{raw[i]:.4f}\t{phi[i]:.4f}\t{sd[i]:.4f}\t{n[i]}")


if __name__ == "__main__":
    main()
