#!/usr/bin/env python3
"""cases/channel_vres2d/channel_analyse.py - the measurements of the channel checks
(cases/channel_vres2d/check: Poiseuille start-up; cases/channel_uniform_vres2d/check: uniform
stream) on a vres-run directory, single or variable resolution.

    python3 channel_analyse.py RUNDIR --mode poiseuille|uniform --box X0 X1 [--U U]

Reads every snapshot RUNDIR/snap_NNNNN.h5 with h5py (not with vres code) and RUNDIR/ledger.tsv,
and prints "key<TAB>value" lines (the check protocol of pipelines/vreslib.sh; the check adds
the run's cost lines and the verdict). X0 < X1 are the faces of the refinement box across the
channel (x = X0 the inflow face, X1 the outflow face); the same region is measured in a single-
resolution run. Owned fluid: each piece of fluid once, from the domain that owns it
(lib/owner.c: a child owns its box, faces included; buffers never count).

Reference (exact solution at every owned fluid particle and snapshot):
  poiseuille  u(z, t) = F/(2 nu) y (L - y) - sum_n 4 F L^2/(nu pi^3 k^3) sin(k pi y/L)
              exp(-k^2 pi^2 nu t/L^2), k = 2n + 1, y = z - z0 (Morris, Fox & Zhu 1997; 200
              terms), w = 0, rho = rho0; F the x gravity, nu Visco, z0 and L the channel's walls
              from the first snapshot's root fluid (lowest z - dp/2, height + dp); U = F L^2/(8 nu)
  uniform     u = U, w = 0, rho = rho0
Keys:
  error           relative L2 error of the velocity (u - u_ex, w) over the owned fluid in the box
                  and all snapshots t > 0: sqrt(sum |v - v_ex|^2 / sum u_ex^2)
  error_global    the same over all owned fluid
  rho_rms_box     RMS of (rho - rho0)/rho0 over the owned fluid in the box, snapshots t > 0
  jump_u_x0, jump_u_x1, jump_rho_x0, jump_rho_x1
                  the jump across each face of the time-averaged x profile (bins dp_root wide,
                  every snapshot of the second half, t > t_end/2) of (u - u_ex)/U and of
                  (rho - rho0)/rho0: |bin just after the face - bin just before|
  noise_u, noise_rho
                  the same profile's bin-to-bin noise: RMS of |b_i+1 - b_i| over the pairs of
                  adjacent bins not within two bins of a face (of the same run)
  jump_ratio      the largest of the four jumps over 3 times its noise (<= 1: no jump beyond the
                  noise)
  and, with several domains (variable resolution), the mass crossing the interface:
  cross_in_coarse_kg, cross_in_fine_kg
                  net mass through the face X0, by particle id between consecutive snapshots:
                  the root's fluid that stopped being root fluid (turned buffer or deleted) there
                  less what turned root fluid there; the child's fluid that appeared there (from
                  buffer or newborn) less what left it
  cross_out_fine_kg, cross_out_coarse_kg
                  the same through X1 (child fluid leaving, root fluid appearing)
  cross_mismatch  the largest of |coarse - fine| at the two faces, at any output, over one
                  column of root particles, rho0 L dp_root (<= 1: the two sides agree to the
                  particle whose centre decides its side)
  created_D1_kg, deleted_D1_kg, created_D0_kg, deleted_D0_kg
                  the ledger's created and deleted (buffer past the outer edge, fluid, no
                  support) masses at the end
  ledger_vs_crossing
                  the largest of |created_D1 - cross_in_coarse|, |deleted_D0 - cross_in_coarse|,
                  |created_D0 - cross_out_fine|, |deleted_D1 - cross_out_fine| over the
                  mass one band of the domain that creates or deletes can hold (its buffer
                  band's width times L times rho0: what sits between a segment and the face)
  ledger_books    the largest disagreement between the ledger and the snapshots' own contents,
                  over all domains and outputs, in particles: the change of a domain's fluid +
                  buffer count against created - deleted, and its fluid count against
                  buffer_to_fluid - fluid_to_buffer - deleted_fluid (0: exact)
  mass_drift      the ledger's total fluid mass drift at the end (0 without a ledger)
Writes RUNDIR/profile.tsv (poiseuille: z, u, u_ex at the last snapshot in the box, bins dp_root
high; uniform: x, u/U, 1 over the time-averaged x profile) and RUNDIR/xprofile.tsv (x, (u -
u_ex)/U, (rho - rho0)/rho0 time-averaged, bin centres). Exit 0, or 1 with a message.
"""
import argparse
import glob
import os
import sys

import h5py
import numpy as np


def fail(msg):
    """One message naming this tool, exit 1."""
    print(f"channel_analyse.py: {msg}", file=sys.stderr)
    sys.exit(1)


def read_snap(path):
    """The snapshot's time and per domain: dict of arrays (id, type, x, z, u, w, rho, m) and the box."""
    with h5py.File(path, "r") as f:
        t = float(f.attrs["time"])
        doms = []
        names = sorted((k for k in f["Domains"].keys() if k[0] == "D" and k[1:].isdigit()), key=lambda k: int(k[1:]))
        for name in names:
            d = f["Domains/" + name]
            pos, vel = d["Position"][:].astype(float), d["Velocity"][:].astype(float)
            a = d.attrs
            doms.append({
                "id": d["Id"][:].astype(np.int64), "type": d["Type"][:].astype(int),
                "x": pos[:, 0], "z": pos[:, 2], "u": vel[:, 0], "w": vel[:, 2],
                "rho": d["Density"][:].astype(float), "m": d["Mass"][:].astype(float),
                "dp": float(a["dp"]), "parent": int(a["parent"]) if "parent" in a else -1,
                "box_min": np.array(a["box_min"], float) if "box_min" in a else None,
                "box_max": np.array(a["box_max"], float) if "box_max" in a else None,
            })
        par = f["Parameters"].attrs
        P = {"rho0": float(par["rhop0"]), "nu": float(np.ravel(par["Visco"])[0]),
             "F": float(np.ravel(par["gravity"])[0])}
    return t, doms, P


def owned(doms):
    """Per domain, the mask of its fluid that it owns (two levels: a child owns its box)."""
    masks = []
    for k, d in enumerate(doms):
        m = d["type"] == 0
        for j, c in enumerate(doms):
            if j != k and c["parent"] == k and c["box_min"] is not None:
                inb = (d["x"] >= c["box_min"][0]) & (d["x"] <= c["box_max"][0]) & \
                      (d["z"] >= c["box_min"][2]) & (d["z"] <= c["box_max"][2])
                m &= ~inb
        masks.append(m)
    return masks


def ledger(rundir):
    """ledger.tsv as {domain: list of row dicts} (None without one)."""
    path = os.path.join(rundir, "ledger.tsv")
    if not os.path.exists(path):
        return None
    rows = {}
    cols = None
    for line in open(path):
        if line.startswith("#"):
            cols = line.lstrip("# ").rstrip("\n").split("\t")
            continue
        v = line.rstrip("\n").split("\t")
        r = dict(zip(cols, (float(x) for x in v)))
        rows.setdefault(int(r["domain"]), []).append(r)
    return rows


def main():
    """Outline: read the snapshots; the reference error; the x profile and its jumps; the crossing."""
    ap = argparse.ArgumentParser(prog="channel_analyse.py")
    ap.add_argument("rundir")
    ap.add_argument("--mode", choices=("poiseuille", "uniform"), required=True)
    ap.add_argument("--box", type=float, nargs=2, required=True, metavar=("X0", "X1"))
    ap.add_argument("--U", type=float, default=1.0, help="uniform: the stream velocity (m/s)")
    a = ap.parse_args()
    X0, X1 = a.box
    snaps = sorted(glob.glob(os.path.join(a.rundir, "snap_[0-9]*.h5")))
    if len(snaps) < 2:
        fail(f"{a.rundir}: fewer than two snapshots")
    data = [read_snap(s) for s in snaps]
    t0, d0, P = data[0]
    rho0, nu, F = P["rho0"], P["nu"], P["F"]
    dpr = d0[0]["dp"]
    rf = d0[0]["type"] == 0
    z0 = d0[0]["z"][rf].min() - dpr / 2
    L = d0[0]["z"][rf].max() - d0[0]["z"][rf].min() + dpr
    rb = np.isin(d0[0]["type"], (0, 1))  # the root's fluid and buffers tile the channel's length
    xa = d0[0]["x"][rb].min() - dpr / 2
    Lx = d0[0]["x"][rb].max() - d0[0]["x"][rb].min() + dpr
    if a.mode == "poiseuille":
        U = F * L * L / (8 * nu)
        K = 2 * np.arange(200) + 1

        def uex(z, t):
            y = z - z0
            s = F / (2 * nu) * y * (L - y)
            c = 4 * F * L * L / (nu * np.pi ** 3 * K ** 3) * np.exp(-K * K * np.pi ** 2 * nu * t / (L * L))
            return s - np.sin(np.outer(y, K) * np.pi / L) @ c
    else:
        U = a.U

        def uex(z, t):
            return np.full_like(z, U)
    tend = data[-1][0]

    # the reference error, and the x profile (bins dp_root wide from xa)
    nb = int(round(Lx / dpr))
    num_b = den_b = num_g = den_g = rr = 0.0
    nrr = 0
    su = np.zeros(nb); sr = np.zeros(nb); sn = np.zeros(nb); nprof = 0
    for t, doms, _ in data:
        if t <= 0:
            continue
        masks = owned(doms)
        X = np.concatenate([d["x"][m] for d, m in zip(doms, masks)])
        Z = np.concatenate([d["z"][m] for d, m in zip(doms, masks)])
        Uu = np.concatenate([d["u"][m] for d, m in zip(doms, masks)])
        W = np.concatenate([d["w"][m] for d, m in zip(doms, masks)])
        R = np.concatenate([d["rho"][m] for d, m in zip(doms, masks)])
        ue = uex(Z, t)
        e2 = (Uu - ue) ** 2 + W ** 2
        inb = (X >= X0) & (X <= X1)
        num_b += e2[inb].sum(); den_b += (ue[inb] ** 2).sum()
        num_g += e2.sum(); den_g += (ue ** 2).sum()
        rr += (((R[inb] - rho0) / rho0) ** 2).sum(); nrr += int(inb.sum())
        if t > tend / 2:
            b = np.clip(((X - xa) / dpr).astype(int) % nb, 0, nb - 1)
            cnt = np.bincount(b, minlength=nb).astype(float)
            ok = cnt > 0
            su[ok] += np.bincount(b, (Uu - ue) / U, nb)[ok] / cnt[ok]
            sr[ok] += np.bincount(b, (R - rho0) / rho0, nb)[ok] / cnt[ok]
            sn[ok] += 1
            nprof += 1
    if den_b <= 0 or nprof == 0:
        fail(f"{a.rundir}: no owned fluid in the box after t = 0")
    print(f"channel_L_m\t{L:.6g}\nchannel_Lx_m\t{Lx:.6g}\nU_ref_m_s\t{U:.6g}")
    print(f"error_global\t{np.sqrt(num_g / den_g):.5g}")
    print(f"rho_rms_box\t{np.sqrt(rr / max(nrr, 1)):.3e}")
    bu, br = su / np.maximum(sn, 1), sr / np.maximum(sn, 1)
    xc = xa + (np.arange(nb) + 0.5) * dpr
    with open(os.path.join(a.rundir, "xprofile.tsv"), "w") as o:
        o.write("# x_m\t(u-u_ex)/U\t(rho-rho0)/rho0\t(time average over t > t_end/2, owned fluid)\n")
        for i in range(nb):
            o.write(f"{xc[i]:.6g}\t{bu[i]:.6g}\t{br[i]:.6g}\n")
    faces = [int(round((X0 - xa) / dpr)), int(round((X1 - xa) / dpr))]  # the bin that starts at the face

    def near(i):
        return min(min(abs(i - f), abs(i + 1 - f)) for f in faces) < 2

    pairs = [i for i in range(nb - 1) if not near(i)]
    noise_u = np.sqrt(np.mean((bu[1:] - bu[:-1])[pairs] ** 2))
    noise_r = np.sqrt(np.mean((br[1:] - br[:-1])[pairs] ** 2))
    ratio = 0.0
    for name, f in (("x0", faces[0]), ("x1", faces[1])):
        ju, jr = abs(bu[f] - bu[f - 1]), abs(br[f] - br[f - 1])
        print(f"jump_u_{name}\t{ju:.3e}\njump_rho_{name}\t{jr:.3e}")
        ratio = max(ratio, ju / (3 * noise_u) if noise_u > 0 else (np.inf if ju > 0 else 0),
                    jr / (3 * noise_r) if noise_r > 0 else (np.inf if jr > 0 else 0))
    print(f"noise_u\t{noise_u:.3e}\nnoise_rho\t{noise_r:.3e}\njump_ratio\t{ratio:.3f}")

    # profile.tsv for vres_compare.sh
    with open(os.path.join(a.rundir, "profile.tsv"), "w") as o:
        if a.mode == "poiseuille":
            t, doms, _ = data[-1]
            masks = owned(doms)
            X = np.concatenate([d["x"][m] for d, m in zip(doms, masks)])
            Z = np.concatenate([d["z"][m] for d, m in zip(doms, masks)])
            Uu = np.concatenate([d["u"][m] for d, m in zip(doms, masks)])
            inb = (X >= X0) & (X <= X1)
            nz = int(round(L / dpr))
            b = np.clip(((Z[inb] - z0) / dpr).astype(int), 0, nz - 1)
            cnt = np.bincount(b, minlength=nz)
            zm = np.bincount(b, Z[inb], nz)
            um = np.bincount(b, Uu[inb], nz)
            for i in range(nz):
                if cnt[i]:
                    zz = zm[i] / cnt[i]
                    o.write(f"{zz:.6g}\t{um[i] / cnt[i]:.6g}\t{uex(np.array([zz]), t)[0]:.6g}\n")
        else:
            for i in range(nb):
                o.write(f"{xc[i]:.6g}\t{1 + bu[i]:.9g}\t1\n")

    led = ledger(a.rundir)
    drift = 0.0
    if led is not None:
        drift = led[0][-1]["total_mass_drift"]
    print(f"mass_drift\t{drift:.6g}")
    if len(d0) < 2:
        print(f"error\t{np.sqrt(num_b / den_b):.5g}")
        return
    if led is None:
        fail(f"{a.rundir}: {len(d0)} domains but no ledger.tsv")

    # the crossing, by id, between consecutive snapshots: root (k = 0) and its child (k = 1)
    xm = (X0 + X1) / 2
    cin_c = cin_f = cout_f = cout_c = 0.0
    worst = 0.0
    col = rho0 * L * dpr
    books = 0
    times = {round(r["time_s"], 9): r for r in led[0]}
    for (ta, da, _), (tb, db, _) in zip(data[:-1], data[1:]):
        for k in (0, 1):
            A, B = da[k], db[k]
            fa = dict(zip(A["id"][A["type"] == 0], np.nonzero(A["type"] == 0)[0]))
            fb = dict(zip(B["id"][B["type"] == 0], np.nonzero(B["type"] == 0)[0]))
            left = [i for i in fa if i not in fb]     # fluid at a, not fluid at b
            came = [i for i in fb if i not in fa]     # fluid at b, not at a
            ml_in = sum(A["m"][fa[i]] for i in left if A["x"][fa[i]] < xm)
            ml_out = sum(A["m"][fa[i]] for i in left if A["x"][fa[i]] >= xm)
            mc_in = sum(B["m"][fb[i]] for i in came if B["x"][fb[i]] < xm)
            mc_out = sum(B["m"][fb[i]] for i in came if B["x"][fb[i]] >= xm)
            if k == 0:   # root fluid lost into the box at X0, gained from it at X1
                cin_c += ml_in - mc_in
                cout_c += mc_out - ml_out
            else:        # child fluid gained at X0, lost at X1
                cin_f += mc_in - ml_in
                cout_f += ml_out - mc_out
        worst = max(worst, abs(cin_c - cin_f) / col, abs(cout_c - cout_f) / col)
    # the ledger against the snapshots' own contents, output by output
    for k in (0, 1):
        rows = led[k]
        nf0 = rows[0]["n_fluid"] + rows[0]["n_buffer"]
        for (t, doms, _), r in zip(data, rows):
            d = doms[k]
            nfl = int((d["type"] == 0).sum()); nbu = int((d["type"] == 1).sum())
            dele = r["deleted_buffer"] + r["deleted_fluid"] + r["deleted_nosupport"]
            books = max(books, abs((nfl + nbu) - (nf0 + r["created"] - dele)),
                        abs(nfl - (rows[0]["n_fluid"] + r["buffer_to_fluid"] - r["fluid_to_buffer"] - r["deleted_fluid"])),
                        abs(nfl - r["n_fluid"]), abs(nbu - r["n_buffer"]))
    end = {k: led[k][-1] for k in (0, 1)}

    def deleted(r):
        return r["deleted_buffer_kg"] + r["deleted_fluid_kg"] + r["deleted_nosupport_kg"]

    c1, x1d, c0, x0d = end[1]["created_kg"], deleted(end[1]), end[0]["created_kg"], deleted(end[0])
    # the mass a band can hold between its segments and the face: its width (buffer edge to box
    # face for the child, box face to inner edge for the root) times L times rho0
    with h5py.File(snaps[0], "r") as f:
        g1, g0 = f["Domains/D1"].attrs, f["Domains/D0"].attrs
        w1 = float(g1["box_min"][0]) - float(np.ravel(g1["buffer_min"])[0]) if "buffer_min" in g1 else None
        w0 = float(np.ravel(g1["inner_min"])[0]) - float(np.ravel(g1["hole_min"])[0]) if "inner_min" in g1 else None
    if w1 is None or w0 is None:
        w1, w0 = 2 * np.sqrt(2) * d0[1]["dp"], 2 * np.sqrt(2) * dpr
    band1, band0 = rho0 * L * abs(w1), rho0 * L * abs(w0)
    lvc = max(abs(c1 - cin_c) / band1, abs(x0d - cin_c) / band0, abs(c0 - cout_f) / band0, abs(x1d - cout_f) / band1)
    print(f"cross_in_coarse_kg\t{cin_c:.6g}\ncross_in_fine_kg\t{cin_f:.6g}")
    print(f"cross_out_fine_kg\t{cout_f:.6g}\ncross_out_coarse_kg\t{cout_c:.6g}")
    print(f"cross_mismatch\t{worst:.4f}")
    print(f"created_D1_kg\t{c1:.6g}\ndeleted_D1_kg\t{x1d:.6g}\ncreated_D0_kg\t{c0:.6g}\ndeleted_D0_kg\t{x0d:.6g}")
    print(f"band_mass_D1_kg\t{band1:.6g}\nband_mass_D0_kg\t{band0:.6g}")
    print(f"ledger_vs_crossing\t{lvc:.4f}")
    print(f"ledger_books\t{books:g}")
    print(f"error\t{np.sqrt(num_b / den_b):.5g}")


if __name__ == "__main__":
    main()
