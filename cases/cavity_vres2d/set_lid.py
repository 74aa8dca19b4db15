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
import os
import sys


sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "pipelines"))
from vresstore import domains, fail, note_history, open_rw  # noqa: E402

TOOL = "set_lid.py"

FIXED = 2  # vres-store(5) Type of a fixed wall particle


def main():
    """Outline: in each domain, the fixed walls of mkbound MK get velocity (U, 0, 0); note the history."""
    ap = argparse.ArgumentParser(prog="set_lid.py", description=__doc__.split("\n")[0])
    ap.add_argument("store")
    ap.add_argument("--mk", type=int, default=1, help="mkbound of the lid's walls")
    ap.add_argument("--U", type=float, default=1.0, help="lid velocity along +x (m/s)")
    args = ap.parse_args()
    with open_rw(TOOL, args.store) as f:
        total = 0
        for name in domains(f):
            d = f["Domains"][name]
            lid = (d["Type"][:] == FIXED) & (d["Mk"][:] == args.mk)
            if not lid.any():
                continue
            vel = d["Velocity"][:]
            vel[lid] = (args.U, 0.0, 0.0)
            d["Velocity"][...] = vel
            total += int(lid.sum())
        if total == 0:
            fail(TOOL, f"{args.store}: no fixed wall particles of mkbound {args.mk} in any domain")
        note_history(f, TOOL)


if __name__ == "__main__":
    main()
