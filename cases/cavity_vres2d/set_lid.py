#!/usr/bin/env python3
"""cases/cavity_vres2d/set_lid.py - give the cavity's lid its velocity in a vres store.

    python3 set_lid.py STORE [--mk MK] [--U U]

cavity_vres2d draws its lid (the walls of mkbound MK, default 1) as fixed walls over the
cavity; this sets their velocity to (U, 0, 0) (default U = 1 m/s) in every domain of the store
(D0, D1, ...: run it after vres-partition, which redraws each domain at its own dp), in place,
with h5py (vres-store(5)). vres-run never moves a fixed wall, and with mDBC SlipMode 1 a wall's
velocity is the particle's own, so the lid keeps its place and drags the fluid at U: the
cavity's moving lid without a body sliding across the domain. A line naming this command is
put at the top of the store's history. Exit 0 on success, 1 when the store has no such walls
(or is not a vres store), 2 on a usage error.
"""
import argparse
import sys
import time

import h5py
import numpy as np

FIXED = 2  # vres-store(5) Type of a fixed wall particle


def fail(msg):
    """Print one message naming this tool and exit 1."""
    print(f"set_lid.py: {msg}", file=sys.stderr)
    sys.exit(1)


def main():
    """Outline: in each domain, the fixed walls of mkbound MK get velocity (U, 0, 0); note the history."""
    ap = argparse.ArgumentParser(prog="set_lid.py", description=__doc__.split("\n")[0])
    ap.add_argument("store")
    ap.add_argument("--mk", type=int, default=1, help="mkbound of the lid's walls")
    ap.add_argument("--U", type=float, default=1.0, help="lid velocity along +x (m/s)")
    args = ap.parse_args()
    try:
        f = h5py.File(args.store, "r+")
    except OSError as e:
        fail(f"{args.store}: cannot open: {e}")
    with f:
        if f.attrs.get("format", b"") not in (b"vres-store", "vres-store") or "Domains" not in f:
            fail(f"{args.store}: not a vres store")
        total = 0
        for name in sorted(k for k in f["Domains"].keys() if k[0] == "D" and k[1:].isdigit()):
            d = f["Domains"][name]
            lid = (d["Type"][:] == FIXED) & (d["Mk"][:] == args.mk)
            if not lid.any():
                continue
            vel = d["Velocity"][:]
            vel[lid] = (args.U, 0.0, 0.0)
            d["Velocity"][...] = vel
            total += int(lid.sum())
        if total == 0:
            fail(f"{args.store}: no fixed wall particles of mkbound {args.mk} in any domain")
        old = f.attrs.get("history", b"")
        old = old.decode() if isinstance(old, bytes) else str(old)
        line = time.strftime("%Y-%m-%dT%H:%M:%SZ", time.gmtime()) + " " + " ".join(["set_lid.py"] + sys.argv[1:])
        f.attrs.create("history", np.bytes_(line + ("\n" + old if old else "")))


if __name__ == "__main__":
    main()
