#!/usr/bin/env python3
"""Do two builds of veslide write the same results, bit for bit?

    python scripts/same_outputs.py [--device D] BASE_EXE NEW_EXE [WORKDIR]

Runs both programs on a set of small inputs (written into WORKDIR, default a temporary
directory) that cover the four methods (bccg, pk, pdr, dr) and 'auto', elastic and viscoelastic
solids at rest and in motion, anisotropic surfaces and directions, a layer, a one-row profile,
kernel variants, Anderson memories, the analyses (anisotropy, patches, Persson), a study
with fields and the adhesive laws' solver (gcg: at rest, in motion, tensile, under approach
control, along a load path), and compares every dataset and every attribute of the two output files: floats by
their bytes (NaN equal to NaN), strings (variable length too) by value. What a run measures of
itself is left out: the wall-clock times (*_seconds, datasets and attributes), the measured memory peak (also as columns
of a study's tables), and the provenance (the root's creation time, compiler options, git revision). Prints one line per
input and exits 1 when any file differs. With --device D (auto, cpu, gpu: the programs'
--device) the runs go where D says, e.g. the emulated device of two `gpu/build.sh --emulate`
builds; an input both programs refuse (pk on the device) counts as the same when both exit alike. Used to check that a refactoring keeps every output
of the hard-wall contact law as it was (docs/development.md).
"""
import os
import subprocess
import sys
import tempfile

import h5py
import numpy as np

SKIP_NAMES = ('_seconds', 'memory_peak_bytes')
SKIP_ROOT_ATTRS = {'created', 'compiler_options', 'git_revision', 'compiler'}

SELF_AFFINE = "&surface kind = 'self_affine', seed = 3, hurst = 0.8, k_cut = {k_cut}, rms_slope = 0.025 {extra}/"
VISCO = "&material model = 'one_term', einf_pa = 1.0e8, ratio = 11.0, tau_s = 0.01, poisson = 0.5 {extra}/"
ELASTIC = "&material model = 'elastic', young_pa = 3.0e6, poisson = 0.5 {extra}/"
HARD = "&material model = 'one_term', einf_pa = 1.0e8, ratio = 100.0, tau_s = 0.01, poisson = 0.5 /"
ADHESION = "&adhesion law = '{law}', energy_j_m2 = 0.05, range_m = 2.0e-5 /"
ANALYSES = "&analysis anisotropy = .true., patches = .true., persson = .true. /"


def case(n, material, method, speed=0.13, surface='', solver='', grid='', motion='', study='', analysis=ANALYSES,
         load="&load mean_pressure_pa = 32.0e3 /", adhesion=''):
    """A namelist: n x n cells (or `grid`), the self-affine surface, `material`, `method`"""
    lines = [grid or f"&grid nx = {n}, ny = {n}, lx_m = 0.01 /",
             (surface or SELF_AFFINE).format(extra='', k_cut=min(16.0, n/4)),
             material, load,
             f"&motion speed_m_s = {speed} {motion}/",
             f"&solver method = '{method}' {solver}/",
             analysis]
    if adhesion:
        lines.append(ADHESION.format(law=adhesion))
    if study:
        lines.append(study)
    return "\n".join(lines) + "\n"


INPUTS = {
    # the four methods and 'auto' on an elastic solid
    'elastic_bccg': case(64, ELASTIC.format(extra=''), 'bccg'),
    'elastic_pk': case(64, ELASTIC.format(extra=''), 'pk'),
    'elastic_dr': case(64, ELASTIC.format(extra=''), 'dr'),
    'elastic_pdr': case(64, ELASTIC.format(extra=''), 'pdr'),
    'elastic_auto': case(64, ELASTIC.format(extra=''), 'auto'),
    # a viscoelastic solid in motion: the splittings, 'auto' (dr below 256^2, pdr from it)
    'visco_dr': case(64, VISCO.format(extra=''), 'dr'),
    'visco_pdr': case(64, VISCO.format(extra=''), 'pdr'),
    'visco_auto_dr': case(64, VISCO.format(extra=''), 'auto'),
    'visco_auto_pdr_256': case(256, VISCO.format(extra=''), 'auto', analysis="&analysis patches = .true. /"),
    # a viscoelastic solid at rest: symmetric, so bccg and pk take it
    'visco_rest_bccg': case(64, VISCO.format(extra=''), 'bccg', speed=0.0),
    'visco_rest_pk': case(64, VISCO.format(extra=''), 'pk', speed=0.0),
    # Anderson memories: none for dr, mixing for pdr
    'visco_dr_m0': case(64, VISCO.format(extra=''), 'dr', solver=", anderson_memory = 0"),
    'visco_pdr_m3': case(64, VISCO.format(extra=''), 'pdr', solver=", anderson_memory = 3"),
    # anisotropic surfaces, sliding at an angle
    'aniso_dr': case(64, VISCO.format(extra=''), 'dr', motion=", direction_deg = 30.0",
                     surface=SELF_AFFINE.replace('{extra}', ", eccentricity = 0.3, alpha_deg = 30.0 ")),
    'aniso_pdr': case(64, VISCO.format(extra=''), 'pdr', motion=", direction_deg = 60.0",
                      surface=SELF_AFFINE.replace('{extra}', ", eccentricity = 0.4, alpha_deg = 100.0 ")),
    'aniso_elastic_pk': case(64, ELASTIC.format(extra=''), 'pk',
                             surface=SELF_AFFINE.replace('{extra}', ", eccentricity = 0.3, alpha_deg = 30.0 ")),
    # a layer on a rigid base
    'layer_visco_dr': case(64, VISCO.format(extra=", thickness_m = 1.0e-3 "), 'dr'),
    'layer_visco_pdr': case(64, VISCO.format(extra=", thickness_m = 1.0e-3, base = 'frictionless' "), 'pdr'),
    'layer_elastic_bccg': case(64, ELASTIC.format(extra=", thickness_m = 5.0e-4 "), 'bccg'),
    # one-row profiles (ny = 1)
    'profile_dr': case(0, VISCO.format(extra=''), 'dr', grid="&grid nx = 512, ny = 1, lx_m = 0.01, ly_m = 2.0e-5 /",
                       surface="&surface kind = 'cosine', amplitude_m = 2.0e-5, wavelength_m = 0.005 /",
                       analysis="&analysis patches = .true. /"),
    'profile_pk': case(0, ELASTIC.format(extra=''), 'pk', grid="&grid nx = 512, ny = 1, lx_m = 0.01, ly_m = 2.0e-5 /",
                       surface="&surface kind = 'cosine', amplitude_m = 2.0e-5, wavelength_m = 0.005 /",
                       analysis="&analysis patches = .true. /"),
    'profile_bccg': case(0, ELASTIC.format(extra=''), 'bccg',
                         grid="&grid nx = 512, ny = 1, lx_m = 0.01, ly_m = 2.0e-5 /",
                         surface="&surface kind = 'cosine', amplitude_m = 2.0e-5, wavelength_m = 0.005 /",
                         analysis="&analysis patches = .true. /"),
    # other surfaces and kernels
    'paraboloid_bccg': case(64, ELASTIC.format(extra=''), 'bccg', surface="&surface kind = 'paraboloid', radius_m = 0.05 /",
                            load="&load mean_pressure_pa = 2.0e3 /"),
    'bisinusoid_pdr': case(64, VISCO.format(extra=''), 'pdr',
                           surface="&surface kind = 'bisinusoid', amplitude_m = 1.0e-5, wavelength_m = 0.005 /"),
    'galerkin_dr': case(32, VISCO.format(extra=''), 'dr', solver=", kernel = 'galerkin'"),
    'collocation_bccg': case(32, ELASTIC.format(extra=''), 'bccg', solver=", kernel = 'collocation'"),
    # harder scenes: a wide loss peak in motion (Einf/E0 = 100) at small contact, the splittings'
    # step balancing and safeguards at work; the paper's scene at 128^2
    'hard_dr': case(128, HARD, 'dr', speed=0.05, load="&load mean_pressure_pa = 5.0e3 /"),
    'hard_pdr': case(128, HARD, 'pdr', speed=0.05, load="&load mean_pressure_pa = 5.0e3 /"),
    'hard_elastic_pk': case(128, ELASTIC.format(extra=''), 'pk', load="&load mean_pressure_pa = 3.0e3 /"),
    'hard_elastic_bccg': case(128, ELASTIC.format(extra=''), 'bccg', load="&load mean_pressure_pa = 3.0e3 /"),
    'paper_128_auto': case(128, VISCO.format(extra=''), 'auto', analysis="&analysis anisotropy = .true., patches = .true. /"),
    # a study: speeds warm-started, two seeds, with the fields
    'study_speeds': case(32, VISCO.format(extra=''), 'auto', analysis="&analysis patches = .true. /",
                         study="&sweep speeds_m_s = 0.0, 0.01, 0.13, 1.0, n_seeds = 2 /\n&output fields = .true. /"),
    'study_pdr': case(32, VISCO.format(extra=''), 'pdr', analysis="&analysis /",
                      study="&sweep speeds_m_s = 0.05, 0.5, pressures_pa = 2.0e4, 4.0e4 /"),
    # adhesive laws ('gcg'): at rest and in motion (its splitting), Dugdale's zone, a tensile load,
    # approach control, a load path warm-started both ways
    'adhesive_elastic': case(64, ELASTIC.format(extra=''), 'gcg', adhesion='exponential'),
    'adhesive_visco': case(64, VISCO.format(extra=''), 'gcg', adhesion='exponential'),
    'adhesive_rest_dugdale': case(64, VISCO.format(extra=''), 'gcg', speed=0.0, adhesion='dugdale'),
    'adhesive_tensile': case(64, ELASTIC.format(extra=''), 'gcg', adhesion='exponential',
                             load="&load mean_pressure_pa = -1.0e3 /"),
    'adhesive_approach': case(64, VISCO.format(extra=''), 'gcg', adhesion='exponential',
                              load="&load approach_m = 1.0e-5 /"),
    'adhesive_load_path': case(32, VISCO.format(extra=''), 'gcg', adhesion='exponential', analysis="&analysis /",
                               study="&sweep pressures_pa = 3.0e4, 1.0e4, 0.0, 1.0e4 /"),
}


def run(exe, path, out, device=None):
    env = dict(os.environ, OMP_NUM_THREADS=os.environ.get('OMP_NUM_THREADS', '1'))
    extra = ['--device', device] if device else []
    r = subprocess.run([exe, '-q', '--overwrite', '-o', out, path] + extra, env=env, capture_output=True, text=True)
    return r.returncode, r.stderr.strip()


def same_value(a, b):
    a = np.asarray(a)
    b = np.asarray(b)
    if a.dtype.names or b.dtype.names:       # a table: column by column, its timings left out
        if a.dtype.names != b.dtype.names:
            return False
        return all(same_value(a[k], b[k]) for k in a.dtype.names if not k.endswith(SKIP_NAMES))
    if a.dtype.kind in 'OSU' or b.dtype.kind in 'OSU':
        la = [x.decode() if isinstance(x, bytes) else str(x) for x in np.ravel(a)]
        lb = [x.decode() if isinstance(x, bytes) else str(x) for x in np.ravel(b)]
        return a.shape == b.shape and la == lb
    return a.dtype == b.dtype and a.shape == b.shape and a.tobytes() == b.tobytes()


def compare(fa, fb):
    """The differences between two open HDF5 files (empty when the same); the names compared"""
    diffs, names = [], []

    def attrs(name, oa, ob, skip=()):
        ka = {k for k in oa.attrs if k not in skip and not k.endswith(SKIP_NAMES)}
        kb = {k for k in ob.attrs if k not in skip and not k.endswith(SKIP_NAMES)}
        if ka != kb:
            diffs.append(f"{name}: attributes {sorted(ka ^ kb)} in one file only")
        for k in sorted(ka & kb):
            if not same_value(oa.attrs[k], ob.attrs[k]):
                diffs.append(f"{name}@{k}: {oa.attrs[k]!r} != {ob.attrs[k]!r}")

    attrs('/', fa, fb, SKIP_ROOT_ATTRS)
    seen_a, seen_b = [], []
    fa.visit(seen_a.append)
    fb.visit(seen_b.append)
    keep = [n for n in seen_a if not n.endswith(SKIP_NAMES)]
    if set(keep) != {n for n in seen_b if not n.endswith(SKIP_NAMES)}:
        diffs.append(f"objects in one file only: {sorted(set(keep) ^ {n for n in seen_b if not n.endswith(SKIP_NAMES)})}")
    for n in keep:
        if n not in fb:
            continue
        oa, ob = fa[n], fb[n]
        names.append(n)
        attrs(n, oa, ob)
        if isinstance(oa, h5py.Dataset):
            va, vb = oa[()], ob[()]
            if not same_value(va, vb):
                diffs.append(f"{n}: values differ")
    return diffs, names


def main():
    args = sys.argv[1:]
    device = None
    if args[:1] == ['--device']:
        device, args = args[1], args[2:]
    if len(args) < 2:
        sys.exit(__doc__)
    base, new = os.path.abspath(args[0]), os.path.abspath(args[1])
    work = args[2] if len(args) > 2 else tempfile.mkdtemp(prefix='veslide-same-')
    os.makedirs(work, exist_ok=True)
    bad = 0
    total_names = 0
    for tag, text in INPUTS.items():
        nml = os.path.join(work, tag + '.nml')
        with open(nml, 'w') as f:
            f.write(text)
        outs = [os.path.join(work, tag + s + '.h5') for s in ('.base', '.new')]
        for o in outs:
            if os.path.exists(o):
                os.remove(o)
        codes = [run(exe, nml, out, device) for exe, out in zip((base, new), outs)]
        if codes[0][0] != codes[1][0]:
            print(f"{tag}: exit {codes[0][0]} against {codes[1][0]}: {codes[0][1][-300:]} | {codes[1][1][-300:]}")
            bad += 1
            continue
        if not any(os.path.exists(o) for o in outs) and codes[0][0] != 0:
            print(f"{tag}: refused by both (exit {codes[0][0]}): {codes[1][1][-200:]}")
            continue
        if not all(os.path.exists(o) for o in outs):
            print(f"{tag}: no output (exit {codes[0][0]}): {codes[0][1][-300:]}")
            bad += 1
            continue
        with h5py.File(outs[0], 'r') as fa, h5py.File(outs[1], 'r') as fb:
            diffs, names = compare(fa, fb)
        total_names += len(names)
        if diffs:
            bad += 1
            print(f"{tag}: DIFFERENT ({len(diffs)}): " + "; ".join(diffs[:8]))
        else:
            print(f"{tag}: same ({len(names)} objects, every dataset and attribute; exit {codes[0][0]})")
    print(f"{len(INPUTS) - bad} of {len(INPUTS)} inputs the same, {total_names} objects compared; work in {work}")
    sys.exit(1 if bad else 0)


if __name__ == '__main__':
    main()
