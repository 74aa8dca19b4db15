#!/usr/bin/env python3
"""cases/channel_uniform_vres2d/init_uniform.py - set a uniform stream in a vres store.

    python3 init_uniform.py STORE [--U U]

GenCase's <initials> is not read by vres-gencase, so check writes the stream into the store
after vres-partition (which redraws each domain at its own dp), in place, with h5py: on the
fluid and buffer particles of every domain, velocity (U, 0, 0) (default U = 1 m/s); density
and pressure are left as drawn (rho0, p = 0: the uniform state). A line naming this command is
put at the top of the store's history. Exit 0 on success, 1 on a store that is not a vres
store with fluid, 2 on a usage error.
"""
import argparse
import os
import sys

import numpy as np

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "pipelines"))
from vresstore import domains, fail, note_history, open_rw  # noqa: E402

TOOL = "init_uniform.py"


def main():
    """Read each domain's types, set the velocity of its fluid and buffer, note the history."""
    ap = argparse.ArgumentParser(prog="init_uniform.py", description=__doc__.split("\n")[0])
    ap.add_argument("store")
    ap.add_argument("--U", type=float, default=1.0, help="stream velocity along x (m/s)")
    args = ap.parse_args()
    with open_rw(TOOL, args.store) as f:
        names = domains(f)
        nset = 0
        for name in names:
            d = f["Domains/" + name]
            sel = np.isin(d["Type"][:], (0, 1))
            vel = d["Velocity"][:]
            vel[sel] = (args.U, 0.0, 0.0)
            d["Velocity"][...] = vel
            nset += int(sel.sum())
        if nset == 0:
            fail(TOOL, f"{args.store}: no fluid particles")
        note_history(f, TOOL)
    print(f"init_uniform.py: {args.store}: u = ({args.U:g}, 0, 0) m/s on {nset} fluid and buffer particles "
          f"in {len(names)} domain(s)", file=sys.stderr)


if __name__ == "__main__":
    main()
