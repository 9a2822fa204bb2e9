#!/usr/bin/env python3
"""veslide's adhesive solve ('gcg') against Tamaas on the same discrete problem.

Usage:
    python bench/tamaas_adhesion.py VESLIDE_EXE MEAN_GAP_OVER_H [RANGE_IN_CELLS]

Johnson's JKR wave (amplitude h = 1 um, wavelength 100 um, E* = 10 MPa, alpha = 0.2) on 4096
cells with the exponential law of range RANGE_IN_CELLS cells (default h/64, 0.64 cell):
- Tamaas 2.9 (PolonskyKeerRey on the gap, gap constraint, ExponentialAdhesionFunctional,
  tolerance 1e-10) is solved at the given mean gap;
- veslide is then solved at the load Tamaas found (load control, tolerance 1e-10).
It prints the largest pressure difference over p* = pi E* h/lambda and both contact sizes.

Needs Python 3 with numpy, h5py and tamaas (tested with tamaas 2.9.0). The conventions are those
of bench/tamaas_parity.py (heights toward the solid, u = 2 p/(E* |q|), nu = 0 so that Tamaas's
E is E*).
"""
import os
import subprocess
import sys
import tempfile

import h5py
import numpy as np
import tamaas as tm

N, L, A, E, ALPHA = 4096, 1.0e-4, 1.0e-6, 1.0e7, 0.2


def main():
    exe, gap_over_h = sys.argv[1], float(sys.argv[2])
    w = ALPHA**2*np.pi**2*E*A**2/(2*L)
    rho = float(sys.argv[3])*L/N if len(sys.argv) > 3 else A/64
    pstar = np.pi*E*A/L
    x = np.arange(N)*L/N
    surface = A*np.cos(2*np.pi*x/L)

    model = tm.ModelFactory.createModel(tm.model_type.basic_1d, [L], [N])
    model.E, model.nu = E, 0.0
    solver = tm.PolonskyKeerRey(model, surface, 1e-10, tm.PolonskyKeerRey.gap, tm.PolonskyKeerRey.gap)
    adhesion = tm.ExponentialAdhesionFunctional(surface)
    adhesion.parameters = {'rho': rho, 'surface_energy': w}
    solver.addFunctionalTerm(adhesion)
    solver.max_iter = 200000
    solver.solve(gap_over_h*A)
    p_t = np.array(model.traction).ravel()
    gap_t = np.array(model.displacement).ravel() - surface
    closed_t = np.count_nonzero(gap_t - gap_t.min() <= 1e-12*A)

    with tempfile.TemporaryDirectory() as work:
        nml = os.path.join(work, 'case.nml')
        with open(nml, 'w') as f:
            f.write(f"""&grid nx = {N}, ny = 1, lx_m = {L!r}, ly_m = {L/N!r} /
&surface kind = 'cosine', amplitude_m = {A!r}, wavelength_m = {L!r} /
&material model = 'elastic', young_pa = {E!r}, poisson = 0.0 /
&load mean_pressure_pa = {float(p_t.mean())!r} /
&adhesion law = 'exponential', energy_j_m2 = {float(w)!r}, range_m = {float(rho)!r} /
&solver tolerance = 1e-10 /
""")
        subprocess.run([exe, nml, '--quiet'], check=True, cwd=work)
        with h5py.File(os.path.join(work, 'case.h5')) as f:
            p_v = f['fields/pressure_pa'][...].ravel()
            closed_v = np.count_nonzero(f['fields/gap_m'][...] <= 0.0)
    print(f"range {rho/(L/N):.3g} cells, mean gap {gap_over_h} h: load {p_t.mean()/pstar:.6f} p*, "
          f"closed cells veslide {closed_v}, Tamaas {closed_t}, "
          f"max |p_veslide - p_Tamaas|/p* = {np.max(np.abs(p_v - p_t))/pstar:.3e}")


if __name__ == '__main__':
    main()
