#!/usr/bin/env python3
"""Join the per-rank files of veslide-batch into one study file.

usage: python postproc/merge_ranks.py OUT.h5 STUDY.rank0000.h5 [STUDY.rank0001.h5 ...]
Copies every /cases group and the provenance of the first part, concatenates /summary sorted by
case number, and recomputes /ensemble (mean and standard error over seeds of every scalar, for
each eccentricity, angle, pressure and speed) as a serial study writes it.
"""
import sys

import h5py
import numpy as np

PARAMS = ("eccentricity", "alpha_deg", "pressure_pa", "speed_m_s")


def main(out, *parts):
    rows = []
    with h5py.File(out, "w") as dst:
        for i, part in enumerate(parts):
            with h5py.File(part, "r") as src:
                if i == 0:
                    for k, v in src.attrs.items():
                        dst.attrs[k] = v
                    src.copy("/input", dst)
                for name in src["/cases"]:
                    src.copy("/cases/" + name, dst, name="/cases/" + name)
                rows.append(src["/summary"][()])
        summary = np.concatenate(rows)
        summary = summary[np.argsort(summary["case"])]
        dst.create_dataset("/summary", data=summary)
        seeds = np.unique(summary["seed"])
        if len(seeds) > 1:
            keys = np.stack([summary[p] for p in PARAMS], axis=1)
            combos, inverse = np.unique(keys, axis=0, return_inverse=True)
            values = [n for n in summary.dtype.names if n not in ("case", "seed") + PARAMS]
            dtype = [(p, "f8") for p in PARAMS] + [("mean_" + v, "f8") for v in values] + \
                    [("sem_" + v, "f8") for v in values]
            ens = np.zeros(len(combos), dtype=dtype)
            for j, combo in enumerate(combos):
                sel = summary[inverse.ravel() == j]
                for p, x in zip(PARAMS, combo):
                    ens[p][j] = x
                for v in values:
                    ens["mean_" + v][j] = sel[v].mean()
                    ens["sem_" + v][j] = sel[v].std(ddof=1) / np.sqrt(len(sel)) if len(sel) > 1 else 0.0
            dst.create_dataset("/ensemble", data=ens)
    print("wrote %s: %d cases from %d parts" % (out, len(summary), len(parts)))


if __name__ == "__main__":
    if len(sys.argv) < 3:
        sys.exit(__doc__)
    main(*sys.argv[1:])
