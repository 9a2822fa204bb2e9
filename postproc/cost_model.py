#!/usr/bin/env python3
"""Cost model of one distributed solve (docs/distributed.md, "A cost model for a cluster").

usage: python postproc/cost_model.py [--pair-local S] [--pass S] [--pairs-4096 P]

Predicts the solve time of the paper scene's metric splitting ('pdr', the method 'auto' takes on
large grids) on N x N cells over R processes (c per node, n = R/c nodes):

  T_solve = P(N) * T_pair + I(N) * (T_passes + T_sums)

  T_pair   = local FFT work + 2 global transposes (FFTW-MPI, transposed layout)
           = a N^2 log2(N^2) / R + 2 (V / (n beta) + (R - 1) alpha),  V = 16 N (N/2 + 1) bytes
  T_passes = the solver's memory-bound passes over the process's N^2/R cells
           = b N^2 / R   (b: seconds per cell and iteration, measured on one process)
  T_sums   = an inner iteration's ordered sums (five MPI_Allgatherv of per-row or per-column
             partials, 6 values per row of the grid in all: every process receives 48 N bytes, a
             node c times that, no shared-memory shortcut assumed) and its three MPI_Allreduce
             (counts, extrema): c 48 N / beta + 8 log2(R) alpha

The constants a and b are measured on this machine (one process, one thread:
veslide-bench-mpi transforms / case); the network constants are assumptions for a typical
cluster node (stated below and printed). P(N), the FFT pairs of a solve, and I(N), its (inner)
iterations, are extrapolated from the measured paper-scene counts (docs/solver-scaling.md) with
their measured growth per doubling of the side.
"""
import argparse
import math

# --- measured on this machine (docs/distributed.md gives the runs) -------------------------------
PAIR_LOCAL_S_PER_NLOGN = 7.0e-10   # a: one FFT pair, one process, per N^2 log2(N^2) (7.4e-10 at 1024^2, 6.5e-10 at 2048^2)
PASS_S_PER_CELL = 1.2e-8           # b: passes of one pdr inner iteration, per cell, one process (1024^2: 73 ms
                                   #    per iteration less 2.6 pairs of 23 ms)
PAIRS_4096, ITS_4096 = 456, 174    # paper scene, tolerance 1e-8, 4096^2 (pdr)
GROWTH_PAIRS = 1.12                # measured growth of the FFT pairs per doubling (2048 -> 4096)
COLLECTIVES_PER_ITERATION = 8      # bccg: ordered sums of passes 1, 2, 4 and two spectral ones; 3 allreduces
SUM_VALUES_PER_ROW = 6             # values per grid row gathered by an inner iteration's ordered sums

# --- assumed cluster node ----------------------------------------------------------------------------
CORES_PER_NODE = 64                # two 32-core CPUs, one MPI process per core
BETA = 10.0e9                      # all-to-all bandwidth per node [B/s] (HDR InfiniBand, 100 Gb/s, ~80 %)
ALPHA = 2.0e-6                     # per-message latency of the all-to-all [s]
CORE_SPEEDUP = 1.0                 # a cluster core against one core here (1: the same)


def predict(n_side, nodes, a=PAIR_LOCAL_S_PER_NLOGN, b=PASS_S_PER_CELL, pairs4096=PAIRS_4096,
            its4096=ITS_4096, growth=GROWTH_PAIRS):
    """The terms of the model for one solve of n_side^2 cells on `nodes` nodes [s]"""
    r = nodes * CORES_PER_NODE
    cells = float(n_side) ** 2
    doublings = math.log2(n_side / 4096)
    pairs = pairs4096 * growth ** doublings
    its = its4096 * growth ** doublings
    v = 16.0 * n_side * (n_side // 2 + 1)
    local = a * cells * math.log2(cells) / r / CORE_SPEEDUP
    transpose = v / (nodes * BETA) + (r - 1) * ALPHA
    t_pair = local + 2 * transpose
    passes = b * cells / r / CORE_SPEEDUP
    t_sum = CORES_PER_NODE * 8.0 * SUM_VALUES_PER_ROW * n_side / BETA + COLLECTIVES_PER_ITERATION * math.log2(r) * ALPHA
    total = pairs * t_pair + its * (passes + t_sum)
    return dict(ranks=r, pairs=pairs, its=its, local=local, transpose=transpose, t_pair=t_pair,
                passes=passes, t_sum=t_sum, fft=pairs * local, comm=pairs * 2 * transpose,
                pass_total=its * passes, sum_total=its * t_sum, total=total,
                memory_per_rank=(210.0 + 8.0) * cells / r + 100e6)


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--pair-local", type=float, default=PAIR_LOCAL_S_PER_NLOGN,
                    help="seconds per N^2 log2(N^2) of one local FFT pair (measured)")
    ap.add_argument("--pass", dest="pass_", type=float, default=PASS_S_PER_CELL,
                    help="seconds per cell of one inner iteration's passes (measured)")
    args = ap.parse_args()
    print("assumed node: %d cores, all-to-all bandwidth %.0f GB/s, latency %.1f us; measured a = %.2e s, "
          "b = %.2e s" % (CORES_PER_NODE, BETA / 1e9, ALPHA * 1e6, args.pair_local, args.pass_))
    print("| N | nodes | ranks | FFT pairs | inner its | FFT [s] | transposes [s] | passes [s] | ordered sums [s] "
          "| solve [s] | memory per rank [MB] |")
    print("|---|---|---|---|---|---|---|---|---|---|---|")
    for n_side in (32768, 65536):
        for nodes in (64, 256):
            m = predict(n_side, nodes, a=args.pair_local, b=args.pass_)
            print("| %d | %d | %d | %.0f | %.0f | %.1f | %.1f | %.1f | %.1f | %.0f | %.0f |" % (
                n_side, nodes, m["ranks"], m["pairs"], m["its"], m["fft"], m["comm"], m["pass_total"],
                m["sum_total"], m["total"], m["memory_per_rank"] / 1e6))


if __name__ == "__main__":
    main()
