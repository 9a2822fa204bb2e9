"""&adhesion: an adhesive contact law beside the hard wall, solved by 'gcg' (docs/adhesion.md).

What is checked, through the Python API on the namelist a user writes:
- Johnson's (1995) JKR wave (alpha = 0.2, exponential law of range h/64, 4096 cells) from a cold
  start at zero and at a tensile load: the contact half-width a (closed cells) obeys
  p/p* = sin^2(pi a) - alpha sqrt(tan(pi a)) within 5e-3 (p* = pi E* h/lambda);
- the adhesion scalars: the mean compressive less the mean tensile traction is the load, the
  law's parameters as given (the third from w = sigma0 rho), the force ratios NaN at a load <= 0;
- the edges' energy release rates (trailing and leading): w for an elastic solid; not measured
  on a two-dimensional contact;
- an adhesive law on a viscoelastic solid in motion is solved (the splitting of 'gcg').
"""
import numpy as np
import pytest

import veslide
from conftest import params

LAMBDA, AMP, E = 1.0e-4, 1.0e-6, 1.0e7
N, ALPHA = 4096, 0.2
PSTAR = np.pi*E*AMP/LAMBDA
W = ALPHA**2*np.pi**2*E*AMP**2/(2.0*LAMBDA)
RHO = AMP/64.0


def jkr_wave(exe, path, load):
    p = params(grid={"nx": N, "ny": 1, "lx_m": LAMBDA, "ly_m": LAMBDA/N},
               surface={"kind": "cosine", "amplitude_m": AMP, "wavelength_m": LAMBDA},
               material={"young_pa": E, "poisson": 0.0}, load={"mean_pressure_pa": load*PSTAR},
               adhesion={"law": "exponential", "energy_j_m2": W, "range_m": RHO},
               solver={"tolerance": 1e-10})
    return veslide.run(p, output=path, exe=exe, progress=None)


@pytest.mark.parametrize("load", [0.0, -0.03])
def test_jkr_wave(exe, tmp_path, load):
    r = jkr_wave(exe, tmp_path/"jkr.h5", load)
    s = r.scalars
    assert s["converged"] == 1 and s["iterations"] > 0
    a = s["contact_area_fraction_cells"]/2.0
    assert abs(load - (np.sin(np.pi*a)**2 - ALPHA*np.sqrt(np.tan(np.pi*a)))) <= 5e-3
    # the closed cells are the contact; the tractions' parts make the load
    g = r.fields.gap_m.values
    assert np.count_nonzero(g <= 0.0)/N == s["contact_area_fraction_cells"]
    assert s["compressive_pressure_pa"] - s["adhesive_pressure_pa"] == pytest.approx(load*PSTAR, abs=1e-9*PSTAR)
    p = r.fields.pressure_pa.values
    # (under a tension larger than the solution's error: the tolerance, or the residual, in units
    # of the pressure scale max(|p_mean|, sigma0))
    error = max(1e-10, s["residual"])*max(abs(load)*PSTAR, s["adhesion_stress_pa"])
    assert s["adhesive_area_fraction"] == np.count_nonzero(p < -error)/N
    assert s["adhesion_energy_j_m2"] == W and s["adhesion_range_m"] == RHO
    assert s["adhesion_stress_pa"] == pytest.approx(W/RHO, rel=1e-15)
    assert np.isnan(s["friction_coefficient"])
    # each edge of an elastic solid releases exactly w (docs/adhesion.md, *Contact edges*)
    assert s["trailing_edges"] == 1 and s["trailing_edge_energy_j_m2"] == pytest.approx(W, rel=1e-12)
    assert s["leading_edges"] == 1 and s["leading_edge_energy_j_m2"] == pytest.approx(W, rel=1e-12)


def test_approach_control_is_the_load_controlled_solution(exe, tmp_path):
    """&load approach_m: the approach is kept as given, the load is the result, and solving at
    that load under load control gives the same contact and pressure (the same branch here)."""
    p = params(grid={"nx": N, "ny": 1, "lx_m": LAMBDA, "ly_m": LAMBDA/N},
               surface={"kind": "cosine", "amplitude_m": AMP, "wavelength_m": LAMBDA},
               material={"young_pa": E, "poisson": 0.0}, load={"approach_m": 0.5*AMP},
               adhesion={"law": "exponential", "energy_j_m2": W, "range_m": 4*LAMBDA/N},
               solver={"tolerance": 1e-10})
    a = veslide.run(p, output=tmp_path/"approach.h5", exe=exe, progress=None)
    assert a.scalars["converged"] == 1 and a.scalars["approach_m"] == pytest.approx(0.5*AMP, rel=1e-12)
    assert a.scalars["mean_separation_m"] == pytest.approx(AMP - 0.5*AMP, rel=1e-12)
    # (a range of 4 cells: the zone at rest 155 cells, the contact 1441, so its edge is a crack's)
    assert a.scalars["trailing_edges"] == 1 and a.scalars["leading_edges"] == 1
    assert a.scalars["trailing_edge_energy_j_m2"] == pytest.approx(W, rel=1e-12)
    assert a.scalars["leading_edge_energy_j_m2"] == pytest.approx(W, rel=1e-12)
    p["load"] = {"mean_pressure_pa": float(a.scalars["mean_pressure_pa"])}
    b = veslide.run(p, output=tmp_path/"load.h5", exe=exe, progress=None)
    assert b.scalars["converged"] == 1
    assert np.array_equal(a.fields.gap_m.values <= 0.0, b.fields.gap_m.values <= 0.0)
    assert np.max(np.abs(a.fields.pressure_pa.values - b.fields.pressure_pa.values)) <= 1e-8*PSTAR
    assert b.scalars["approach_m"] == pytest.approx(0.5*AMP, rel=1e-7)


def test_adhesion_in_motion(exe, tmp_path):
    """A viscoelastic solid in motion with adhesion: 'auto' takes 'gcg' (its splitting, the
    operator not being symmetric), which converges on a small rough scene; the friction opposes
    the motion and the tractions' parts still make the load; the edges of a
    two-dimensional contact are not measured."""
    g = params(grid={"nx": 32, "ny": 32}, surface={"k_cut": 8}, material={"model": "one_term"},
               motion={"speed_m_s": 0.1},
               adhesion={"law": "exponential", "energy_j_m2": 0.05, "range_m": 1e-9})
    r = veslide.run(g, output=tmp_path/"sliding.h5", exe=exe, progress=None)
    s = r.scalars
    assert s["converged"] == 1 and s.attrs["solver_method"] == "gcg"
    assert s["friction_coefficient"] > 0.0
    assert s["adhesive_pressure_pa"] > 0.0 and s["adhesive_area_fraction"] > 0.0
    assert s["compressive_pressure_pa"] - s["adhesive_pressure_pa"] == pytest.approx(s["mean_pressure_pa"],
                                                                                     rel=1e-9)
    # a two-dimensional contact: its edges' energy release rate is not measured (docs/adhesion.md)
    assert s["trailing_edges"] == 0 and np.isnan(s["trailing_edge_energy_j_m2"])
    assert s["leading_edges"] == 0 and np.isnan(s["leading_edge_energy_j_m2"])


def wave_path(approaches, n=1024, **adhesion):
    """Johnson's wave on n cells (range 4 cells unless given), loaded along a path of approaches"""
    law = {"law": "exponential", "energy_j_m2": W, "range_m": 4*LAMBDA/n}
    law.update(adhesion)
    return params(grid={"nx": n, "ny": 1, "lx_m": LAMBDA, "ly_m": LAMBDA/n},
                  surface={"kind": "cosine", "amplitude_m": AMP, "wavelength_m": LAMBDA},
                  material={"young_pa": E, "poisson": 0.0}, adhesion=law,
                  sweep={"approaches_m": list(approaches)}, output={"fields": False})


@pytest.mark.filterwarnings("ignore:.*contact-resolution")       # (the separated cases close no cell)
def test_load_path_read_by_the_api(exe, tmp_path):
    """A path of approaches there and back: /summary holds each case's place on the path and its
    event, /paths the path's jumps and pull-off (the most tensile load at a minimum along the
    path, here where the contact is lost), as `Result.summary` and `Result.paths`."""
    down = [2e-7, 1e-7, 0.0, -5e-8, -1e-7, -1.5e-7, -2e-7, -3e-7]
    r = veslide.run(wave_path(down + down[-2::-1]), output=tmp_path/"path.h5", exe=exe, progress=None)
    s, paths = r.summary, r.paths
    n = 2*len(down) - 1
    assert list(s["path_step"]) == list(range(1, n + 1)) and (s["converged"] == 1).all()
    assert s["approach_m"].to_numpy() == pytest.approx(down + down[-2::-1], rel=1e-12, abs=1e-20)
    assert np.isnan(s["pressure_pa"]).all()          # (approach control: the load is a result)
    assert len(paths) == 1 and paths.attrs["control"] == "approach"
    assert paths.attrs["units"]["pull_off_pa"] == "Pa"
    row = paths.iloc[0]
    k = int(np.argmin(s["mean_pressure_pa"]))
    assert row["pull_off_pa"] == s["mean_pressure_pa"][k] and row["pull_off_case"] == s["case"][k]
    assert row["pull_off_pa"] < 0 and 1 < row["pull_off_case"] < n
    assert row["n_jump_out"] == (s["path_jump"] == -1).sum() >= 1
    assert row["n_jump_in"] == (s["path_jump"] == 1).sum() >= 1
    assert row["first_case"] == 1 and row["last_case"] == n


def periodic_patches(mask):
    """Labels of the 4-neighbour components of `mask` on the periodic grid (union-find; -1 off it)"""
    ny, nx = mask.shape
    parent = np.arange(mask.size)

    def root(a):
        while parent[a] != a:
            parent[a] = parent[parent[a]]
            a = parent[a]
        return a

    for j, i in zip(*np.nonzero(mask)):
        for jj, ii in ((j, (i + 1) % nx), ((j + 1) % ny, i)):
            if mask[jj, ii]:
                parent[root(j*nx + i)] = root(jj*nx + ii)
    labels = np.array([root(a) for a in range(mask.size)]).reshape(mask.shape)
    return np.where(mask, labels, -1)


def apart(mask, other):
    """The components of `mask` that hold no cell of `other`: their number and cells"""
    labels = periodic_patches(mask)
    ids = set(labels[mask].tolist()) - set(labels[mask & other].tolist())
    return len(ids), int(np.isin(labels, list(ids)).sum())


def rough_path(loads, range_m):
    """A rough surface on 32^2 cells (elastic, w = 0.05 J/m^2), loaded along a path of loads"""
    return params(grid={"nx": 32, "ny": 32, "lx_m": 0.01},
                  surface={"seed": 3, "k_cut": 8.0, "rms_slope": 0.025},
                  material={"model": "elastic", "young_pa": 1e7, "poisson": 0.5},
                  adhesion={"law": "exponential", "energy_j_m2": 0.05, "range_m": range_m},
                  solver={"method": "gcg"}, sweep={"pressures_pa": loads}, output={"fields": True})


@pytest.mark.filterwarnings("ignore:.*contact-resolution")
def test_load_path_patches_made_and_lost(exe, tmp_path):
    """A rough surface loaded and unloaded along a path: new patches touch down while the contact
    grows (no jump of the whole contact) and leave as it shrinks. /summary's path_patches_made
    and _lost (and their cells) are those of an independent count from the closed cells of
    consecutive cases (the periodic grid's components, here by union-find)."""
    loads = [1e3, 3e3, 1e4, 3e4, 1e4, 3e3, 1e3]
    r = veslide.run(rough_path(loads, 2e-5), output=tmp_path/"patches.h5", exe=exe, progress=None)
    s = r.summary
    assert (s["converged"] == 1).all() and (s["path_jump"] == 0).all()
    closed = [r.cases[k].fields.gap_m.values <= 0.0 for k in s["case"]]
    for k in range(len(loads)):
        want = (0, 0, 0, 0)
        if k > 0:
            want = apart(closed[k], closed[k - 1]) + apart(closed[k - 1], closed[k])
            want = (want[0], want[2], want[1], want[3])
        got = tuple(int(s[c].iloc[k]) for c in ("path_patches_made", "path_patches_lost",
                                                 "path_patch_cells_made", "path_patch_cells_lost"))
        assert got == want, "case %d" % (k + 1)
    # (the scene makes patches while loading and loses them while unloading)
    assert s["path_patches_made"][:4].sum() > 0 and s["path_patches_lost"][4:].sum() > 0
    row = r.paths.iloc[0]
    assert row["n_patches_made"] == s["path_patches_made"].sum()
    assert row["n_patches_lost"] == s["path_patches_lost"].sum()
    # (the same closed cells at each load both ways: no patch is bistable)
    assert all(np.array_equal(closed[k], closed[len(loads) - 1 - k]) for k in range(3))
    assert (s["path_patches_bistable"] == 0).all() and row["n_patches_bistable"] == 0


def bistable_patches(closed, control, k):
    """The patches made and lost between cases k - 1 and k (0-based) held the other way by an
    earlier case at the same control: a lost one absent at the previous case's control or present
    at this case's, a made one present at the previous case's control or absent at this case's"""
    n = 0
    for mask, other, made in ((closed[k], closed[k - 1], True), (closed[k - 1], closed[k], False)):
        labels = periodic_patches(mask)
        for pid in set(labels[mask].tolist()) - set(labels[mask & other].tolist()):
            cells = labels == pid
            held_before = [closed[j][cells].any() for j in range(k - 1) if control[j] == control[k - 1]]
            held_after = [closed[j][cells].any() for j in range(k) if control[j] == control[k]]
            if made:
                n += any(held_before) or not all(held_after)
            else:
                n += (not all(held_before)) or any(held_after)
    return n


@pytest.mark.filterwarnings("ignore:.*contact-resolution", "ignore:.*adhesion-zone-unresolved")
def test_load_path_bistable_patches(exe, tmp_path):
    """The rough path of test_load_path_patches_made_and_lost with a short range (0.5 um, its
    cohesive zone 0.17 of a cell: the contact at a load depends on the path to it), loaded,
    unloaded and reloaded: at the same load the closed cells differ between the legs, and
    /summary's path_patches_bistable counts the patches made or lost that an earlier case at the
    same load held the other way, as an independent count from the cases' closed cells does;
    /paths sums them."""
    loads = [1e3, 3e3, 1e4, 3e4, 1e4, 3e3, 1e3, 3e3, 1e4, 3e4]
    lines = []
    r = veslide.run(rough_path(loads, 5e-7), output=tmp_path/"bistable.h5", exe=exe, progress=lines.append)
    s = r.summary
    assert (s["converged"] == 1).all() and (s["path_jump"] == 0).all()
    closed = [r.cases[k].fields.gap_m.values <= 0.0 for k in s["case"]]
    want = [0] + [bistable_patches(closed, loads, k) for k in range(1, len(loads))]
    assert list(s["path_patches_bistable"]) == want
    # (hysteresis: the unloading leg keeps cells the loading leg had open; bistable patches on the
    # unloading and on the reloading leg, none on the first, never more than those made and lost)
    assert not np.array_equal(closed[2], closed[4])
    assert sum(want[4:7]) >= 1 and sum(want[7:]) >= 1 and sum(want[:4]) == 0
    assert (s["path_patches_bistable"] <= s["path_patches_made"] + s["path_patches_lost"]).all()
    assert r.paths.iloc[0]["n_patches_bistable"] == sum(want)
    # (each case's progress line names them: ', 1 BISTABLE PATCH', ', 2 BISTABLE PATCHES')
    cases = [line for line in lines if line.startswith("case ")]
    assert len(cases) == len(loads)
    for line, n in zip(cases, want):
        named = {0: "BISTABLE" not in line, 1: ", 1 BISTABLE PATCH," in line}.get(n, ", %d BISTABLE PATCHES," % n in line)
        assert named, line


@pytest.mark.parametrize("sweep, adhesive, words", [
    ({"approaches_m": [1e-7, -1e-7]}, False, ["&sweep approaches_m", "adhesive law"]),
    ({"approaches_m": [1e-7, 2.0]}, True, ["&sweep approaches_m(2)", "allowed", ">= -1 and <= 1 [m]"]),
    ({"approaches_m": [1e-7], "pressures_pa": [1e3]}, True, ["pressures_pa", "approaches_m", "give one"]),
    ({"pressures_pa": [1e3, -1e3]}, False, ["&sweep pressures_pa(2)", "allowed", "&adhesion"]),
])
def test_load_path_refused(exe, tmp_path, sweep, adhesive, words):
    """A path the program cannot run is refused at input: exit status 1, one line naming the
    group, the variable and what is allowed, and no file written."""
    p = wave_path([0.0], n=64)
    p["sweep"] = sweep
    if not adhesive:
        del p["adhesion"]
    out = tmp_path/"refused.h5"
    with pytest.raises(veslide.InputError) as info:
        veslide.run(p, output=out, exe=exe, progress=None)
    message = str(info.value).strip()
    assert "\n" not in message and all(w in message for w in words), message
    assert info.value.returncode == 1 and info.value.group == "sweep"
    assert not out.exists() and not list(tmp_path.glob("refused*"))


@pytest.mark.parametrize("law", ["exponential", "dugdale"])
def test_sliding_approach_is_load_control(exe, tmp_path, law):
    """Johnson's wave sliding over a one-term solid (E0 = E, Einf = 10 E0, creep time 10 ms, at
    v tau/lambda = 0.05, 1024 cells, range 4 cells): gcg's splitting under approach control keeps
    the approach, and under load control at the load it found gives the same solution (the same
    closed cells, and with the exponential law pressures within 1e-6 p*); the friction opposes
    the motion."""
    n = 1024
    base = dict(grid={"nx": n, "ny": 1, "lx_m": LAMBDA, "ly_m": LAMBDA/n},
                surface={"kind": "cosine", "amplitude_m": AMP, "wavelength_m": LAMBDA},
                material={"model": "one_term", "einf_pa": 10*E, "ratio": 10.0, "tau_s": 0.01, "poisson": 0.0},
                motion={"speed_m_s": 0.05*LAMBDA/0.01},
                adhesion={"law": law, "energy_j_m2": W, "range_m": 4*LAMBDA/n},
                solver={"tolerance": 1e-10})
    a = veslide.run(params(load={"approach_m": 0.5*AMP}, **base), output=tmp_path/"a.h5", exe=exe, progress=None)
    assert a.scalars["converged"] == 1 and a.scalars["approach_m"] == pytest.approx(0.5*AMP, rel=1e-12)
    load = a.scalars["mean_pressure_pa"]
    b = veslide.run(params(load={"mean_pressure_pa": load}, **base), output=tmp_path/"b.h5", exe=exe,
                    progress=None)
    assert b.scalars["converged"] == 1
    ga, gb = a.fields.gap_m.values, b.fields.gap_m.values
    assert np.array_equal(ga <= 0.0, gb <= 0.0)
    if law == "exponential":
        # (Dugdale's discrete solution is not unique: a cell held at the zone's edge, g = rho,
        # takes any attraction in [0, sigma0], and the contact's pressures follow it)
        assert np.max(np.abs(a.fields.pressure_pa.values - b.fields.pressure_pa.values)) <= 1e-6*PSTAR
    else:
        # the area under tension is within Dugdale's zone (g <= rho): beyond it the law does not
        # attract and the sign of p is round-off, which adhesive_area_fraction does not count
        # (it counted about half those cells before)
        for r, g in ((a, ga), (b, gb)):
            p = r.fields.pressure_pa.values
            assert 0.0 < r.scalars["adhesive_area_fraction"] <= np.count_nonzero((p < 0.0) & (g <= 4*LAMBDA/n))/n
    assert a.scalars["friction_coefficient"] > 0.0 and b.scalars["friction_coefficient"] > 0.0


def test_the_adhesion_example_input(exe, tmp_path):
    """inputs/adhesion/sliding.nml (the paper's scene with adhesion, in motion) converges under
    'auto' ('gcg') without a warning, its cohesive zone resolved (docs/validity.md (9)), and
    adhesion raises its friction and contact area above those of the same scene without it"""
    import f90nml
    from pathlib import Path
    nml = f90nml.read(Path(__file__).resolve().parents[2]/"inputs"/"adhesion"/"sliding.nml")
    p = {group: dict(values) for group, values in nml.items() if group != "output"}
    a = veslide.run(p, output=tmp_path/"adhesive.h5", exe=exe, progress=None)
    assert a.converged and a.warnings == [] and a.scalars.attrs["solver_method"] == "gcg"
    assert a.validity["adhesion_zone_cells"] > 10
    del p["adhesion"]
    b = veslide.run(p, output=tmp_path/"adhesionless.h5", exe=exe, progress=None)
    assert b.converged
    assert a.scalars["friction_coefficient"] > b.scalars["friction_coefficient"]
    assert a.scalars["contact_area_fraction"] > b.scalars["contact_area_fraction"]


def test_the_trailing_edge_example_input(exe, tmp_path):
    """inputs/adhesion/trailing_edge.nml (Johnson's wave sliding at v tau/lambda = 0.01, range
    h/64) converges without a warning and reports one trailing edge whose energy release rate
    lies between w and (Einf/E0) w (3.69 w), and one leading edge whose energy release rate lies
    between (E0/Einf) w and w (0.33 w: docs/adhesion.md, *Contact edges*)"""
    import f90nml
    from pathlib import Path
    nml = f90nml.read(Path(__file__).resolve().parents[2]/"inputs"/"adhesion"/"trailing_edge.nml")
    p = {group: dict(values) for group, values in nml.items() if group != "output"}
    r = veslide.run(p, output=tmp_path/"edge.h5", exe=exe, progress=None)
    s = r.scalars
    assert r.converged and r.warnings == []
    w = p["adhesion"]["energy_j_m2"]
    assert s["trailing_edges"] == 1
    assert w < s["trailing_edge_energy_j_m2"] < p["material"]["ratio"]*w
    assert s["leading_edges"] == 1
    assert w/p["material"]["ratio"] < s["leading_edge_energy_j_m2"] < w
