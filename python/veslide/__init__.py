"""veslide from Python: run steady sliding contacts, read their HDF5 results, plot them.

    import veslide
    r = veslide.run({"grid": {"nx": 64, "ny": 64}, "motion": {"speed_m_s": 0.1}})
    r.scalars["friction_coefficient"], r.fields.pressure_pa.sel(x=0.005, y=0.002, method="nearest")
    h = veslide.start("study.nml"); h.progress.fraction; h.wait()   # in the background
    s = veslide.read("study.h5"); s.summary, s.ensemble, s.cases[3].fields
    veslide.read_running("study.h5")          # a study still being written (its part file)
    ref = veslide.refine("case.nml", [256, 512, 1024, 2048]); ref.estimate   # error bands by refinement
    scan = veslide.read_scan("scan.x3p"); veslide.prepare_scan(scan, nx=256).write("surf.h5")   # a measured scan
    m = veslide.fit_prony(f_hz, storage_pa, loss_pa); veslide.run({"material": m.to_namelist(), ...})
    import veslide.material as vm                                    # a DMA export to a material
    mc = vm.master_curve(vm.read_dma("export.csv"), 20); m = mc.fit_prony(shift="table")

Arrays are indexed [ix, iy] everywhere in this package (the file's fields are [iy, ix] in h5py).
"""
from .results import Arrays, Cases, Result, Scalars, read, read_running
from .refinement import Refinement, StudyRefinement, convergence, refine
from .runner import (Cancelled, ConvergenceWarning, InputError, NumericalError, OutputExistsError, Progress, Run,
                     VeslideError, WriteError,
                     find_executable, git_revision, namelist, run, start, write_namelist)
from .topography import (PreparedSurface, Scan, major_axis_deg, psd_2d, psd_radial, read_topography, slope_tensor,
                         write_topography)
from .topography import load as load_topography, prepare as prepare_scan, read as read_scan
from .material import FitReport, Material, fit_prony, shift_factor
from ._warning import VeslideWarning

__version__ = "0.4.0"

__all__ = ["read", "read_running", "run", "start", "Run", "Progress", "git_revision", "write_topography", "read_topography", "find_executable",
           "namelist", "write_namelist", "refine", "convergence", "Refinement", "StudyRefinement",
           "psd_2d", "psd_radial", "slope_tensor", "major_axis_deg",
           "read_scan", "prepare_scan", "load_topography", "Scan", "PreparedSurface",
           "Material", "FitReport", "fit_prony", "shift_factor",
           "Result", "Scalars", "Arrays", "Cases", "InputError", "OutputExistsError", "VeslideError",
           "Cancelled", "ConvergenceWarning", "WriteError", "NumericalError", "VeslideWarning"]


def __getattr__(name):
    # veslide.plot without importing matplotlib until it is used
    if name == "plot":
        import importlib
        return importlib.import_module(".plot", __name__)
    raise AttributeError("module 'veslide' has no attribute %r" % name)
