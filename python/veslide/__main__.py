"""python -m veslide refine NAMELIST NX NX NX ... [--output-dir DIR] [--threads N]
python -m veslide topography SCAN --out SURF.h5 [--nx N] [--ny N] [--detrend curvature|plane|none]
                             [--periodic tukey|mirror|crop|none] [--taper F] [--k-cut K]
                             [--fill auto|harmonic|none] [--crop-valid] ...
python -m veslide material EXPORT --reference-temperature T [--out material.nml]
                           [--shift table|wlf|arrhenius] [--temperature T] [--drop-bad] ...

refine: runs one case on several grids (or reuses the files already there from the same input)
and prints the table and the error estimate of `veslide.refine`; exit status 1 on bad input, 2
when a solve did not converge, 3 when a file could not be written, 4 when the numbers broke down
(as the program's).

topography: reads a measured scan (any format SurfaceTopography reads), prepares it as
`veslide.topography.prepare` does and writes the height file for `&surface kind='file'`, printing
one line per choice with what it cost, and a line `warning: ...` on stderr for each
VeslideWarning of the preparation; exit status 1 on bad input (one line on stderr, no file).

material: reads a DMA export of isothermal sweeps (`veslide.material.read_dma`), shifts them into
a master curve at the reference temperature (`master_curve`), fits WLF and Arrhenius to the
shift factors and a Prony series to the master curve, and writes the `&material` group a study
takes, printing one line per step and a line `warning: ...` on stderr for each VeslideWarning;
exit status 1 on bad input (one line on stderr, no file)."""
import argparse
import os
import re
import sys
import warnings

import pandas as pd

from .refinement import refine
from ._warning import VeslideWarning
from .runner import ConvergenceWarning, InputError, NumericalError, WriteError


def main(argv=None):
    ap = argparse.ArgumentParser(prog="python -m veslide")
    sub = ap.add_subparsers(dest="command", required=True)
    r = sub.add_parser("refine", help="run one case on several grids and estimate the discretisation error "
                                      "of its scalars")
    r.add_argument("namelist", help="the case's namelist file (one case: no &sweep)")
    r.add_argument("sizes", nargs="+", type=int, help="nx of each grid (ny scaled with it)")
    r.add_argument("--output-dir", default="refine", help="where refine-NXxNY.h5 go (default: ./refine)")
    r.add_argument("--threads", type=int, default=None, help="OMP_NUM_THREADS of each run")
    t = sub.add_parser(
        "topography", help="make a measured scan a periodic height file for &surface kind='file'",
        formatter_class=argparse.RawDescriptionHelpFormatter,
        description="Read a measured scan (any format SurfaceTopography reads; a line scan makes a grid of\n"
                    "ny = 1), prepare it (undefined points, detrend, periodic cell, band and grid) and write\n"
                    "the height file, printing one line per choice with what it cost.",
        epilog="refused (exit status 1, one line on stderr, no file written):\n"
               "  more than 2 % of the points undefined, unless --crop-valid or --fill harmonic;\n"
               "  a prepared rms slope above 10 (heights in another unit: --unit, --height-scale;\n"
               "  a channel that is not heights: --channel); a file without its unit or size.\n"
               "warned (a line 'warning: [code] ...' on stderr, the file written):\n"
               "  filled-scan         more than 2 % of the points filled (--fill harmonic)\n"
               "  band-slope-removed  k_cut and the grid remove more than half of the slope\n"
               "                      variance; says which --nx (and k_cut) keeps half\n"
               "the height file's dataset has the attributes length_x_m, length_y_m, preparation (JSON),\n"
               "filled_fraction and band_slope_variance_removed; writing the same surface again is a no-op.")
    t.add_argument("scan", help="the instrument's file (x3p, sdf, sur, datx, opd, plu, gwy, nc, asc, ...)")
    t.add_argument("--out", required=True, help="the height file to write (HDF5)")
    t.add_argument("--dataset", default="/height_m", help="its dataset (default /height_m)")
    t.add_argument("--format", default=None, help="the file's format when not found from its content (e.g. x3p)")
    t.add_argument("--channel", default=None, help="the channel, by index or name (default: the reader's)")
    t.add_argument("--unit", default=None, help="length unit for a file that gives none (e.g. um)")
    t.add_argument("--size", nargs="+", type=float, metavar=("LX", "LY"), default=None,
                   help="the scan's sides in that unit, for a file that gives none (a line scan: LX)")
    t.add_argument("--height-scale", type=float, default=None, metavar="F",
                   help="multiply the heights by F (heights in another unit than the file's sides)")
    t.add_argument("--nx", type=int, default=None, help="points of the solve grid along x (default: the cell's)")
    t.add_argument("--ny", type=int, default=None,
                   help="along y (default: from nx and the cell's aspect ratio; a line scan: 1)")
    t.add_argument("--detrend", default="curvature", choices=["curvature", "plane", "none"])
    t.add_argument("--periodic", default="tukey", choices=["tukey", "mirror", "crop", "none"])
    t.add_argument("--taper", type=float, default=0.1,
                   help="tukey: fraction of each side in the taper; crop: the most cut from each side (0.1)")
    t.add_argument("--k-cut", type=float, default=None,
                   help="modes kept: |q| <= k_cut 2 pi/lx (default: half the solve grid's Nyquist)")
    t.add_argument("--fill", default="auto", choices=["auto", "harmonic", "none"],
                   help="undefined points: auto fills up to 2 %% of the points harmonically and refuses more; "
                        "harmonic fills any share (the filled heights are invented; a warning above 2 %%); "
                        "none refuses any (default auto)")
    t.add_argument("--crop-valid", action="store_true",
                   help="crop the scan to its largest fully measured rectangle before the detrending")
    t.add_argument("--overwrite", action="store_true", help="replace the dataset if the file has it")
    mt = sub.add_parser(
        "material", help="make a DMA export of isothermal sweeps the &material group of a study",
        formatter_class=argparse.RawDescriptionHelpFormatter,
        description="Read a DMA export (CSV, TSV or Excel: columns found by name, units from a units row or\n"
                    "the names), shift its sweeps into a master curve at the reference temperature (shift\n"
                    "factors from the sweeps' overlap), fit WLF and Arrhenius to them and a Prony series to\n"
                    "the master curve, and write the &material group, printing one line per step.",
        epilog="refused (exit status 1, one line on stderr, no file written):\n"
               "  a column missing, two columns for one role, a unit missing or of the wrong kind\n"
               "  (--column, --unit); bad points (not positive, not numbers), unless --drop-bad;\n"
               "  the reference outside the sweeps' temperatures; --shift table with shift factors\n"
               "  that do not fall as the temperature rises; an existing --out without --overwrite.\n"
               "warned (a line 'warning: [code] ...' on stderr, the file written):\n"
               "  dma-dropped-points   the points --drop-bad dropped, each named\n"
               "  poor-superposition   two sweeps that do not superpose (rms above 10 %)\n"
               "  uncertain-shift      a shift factor known to worse than 0.1 decade\n"
               "  shift-not-monotone   log10 a_T rising with temperature somewhere\n"
               "  prony-fit-error      the series misses the master curve by more than 10 % rms\n"
               "  rubbery-plateau      the data do not reach the rubbery plateau\n"
               "  extrapolated-loss-peak  the series' tan delta peaks outside the data")
    mt.add_argument("export", help="the instrument's export (.csv, .txt, .tsv, .xlsx)")
    mt.add_argument("--reference-temperature", type=float, required=True, metavar="T",
                    help="the master curve's reference temperature [C], within the sweeps' range")
    mt.add_argument("--out", default=None, help="the namelist file to write (default: EXPORT's name with .nml)")
    mt.add_argument("--shift", default="table", choices=["table", "wlf", "arrhenius"],
                    help="the temperature law of the group: the measured shift factors (table, default), or "
                         "the WLF or Arrhenius law fitted to them")
    mt.add_argument("--temperature", type=float, default=None, metavar="T",
                    help="temperature_c of the group (default: none, the reference; &sweep temperatures_c "
                         "then gives a study's)")
    mt.add_argument("--vertical", action="store_true", help="fit a vertical shift b_T too")
    mt.add_argument("--drop-bad", action="store_true", help="drop bad points (each named in a warning)")
    mt.add_argument("--column", action="append", default=[], metavar="ROLE=NAME",
                    help="a column by name or 0-based index: frequency, storage, loss, temperature, sweep")
    mt.add_argument("--unit", action="append", default=[], metavar="ROLE=UNIT",
                    help="a column's unit: frequency Hz|rad/s, storage|loss Pa|kPa|MPa|GPa, temperature C|K")
    mt.add_argument("--sheet", default="0", help="Excel: the sheet, by index or name (default 0)")
    mt.add_argument("--form", default="relaxation", choices=["relaxation", "creep"], help="the series' form")
    mt.add_argument("--terms-per-decade", type=float, default=None, help="Prony terms a decade (default 3)")
    mt.add_argument("--poisson", type=float, default=0.5, help="Poisson ratio (default 0.5)")
    mt.add_argument("--plot", default=None, metavar="FILE",
                    help="draw the master curve and the shift factors into FILE (png, pdf, svg)")
    mt.add_argument("--overwrite", action="store_true", help="replace --out if it exists")
    args = ap.parse_args(argv)
    if args.command == "topography":
        return _topography(args)
    if args.command == "material":
        return _material(args)
    warnings.simplefilter("ignore", ConvergenceWarning)       # the exit status and the notes say it
    try:
        ref = refine(args.namelist, args.sizes, args.output_dir, threads=args.threads, progress=None)
    except (WriteError, NumericalError) as e:
        print("veslide refine: %s" % e.message, file=sys.stderr)
        return e.returncode
    except (InputError, ValueError, FileNotFoundError, FileExistsError) as e:
        print("veslide refine: %s" % (getattr(e, "message", None) or e), file=sys.stderr)
        return 1
    with pd.option_context("display.width", 200, "display.max_columns", 20, "display.max_colwidth", 90):
        print(ref.table.to_string())
        print()
        print(ref.estimate.to_string())
    return 0 if ref.converged else 2      # as the program: 2 when a solve did not converge


def _cli_words(text):
    """The package's messages name an option as "python=value (--option value)": here the option alone."""
    return re.sub(r"\b[a-z_]+=(?:True|'[^']*'|\([^)]*\)|[0-9.]+)? \((--[a-z-]+(?: [^();]+)?)\)", r"\1", text)


def _topography(args):
    from .topography import prepare, read
    channel = args.channel
    if channel is not None and channel.isdigit():
        channel = int(channel)
    try:
        if args.size is not None and len(args.size) > 2:
            raise ValueError("--size takes LX LY (a line scan: LX), got %d numbers" % len(args.size))
        scan = read(args.scan, format=args.format, channel=channel, unit=args.unit, physical_sizes=args.size,
                    height_scale_factor=args.height_scale)
        with warnings.catch_warnings(record=True) as caught:
            warnings.simplefilter("always", VeslideWarning)
            s = prepare(scan, nx=args.nx, ny=args.ny, detrend=args.detrend, periodic=args.periodic,
                        taper=args.taper, k_cut=args.k_cut, fill=None if args.fill == "none" else args.fill,
                        crop_valid=args.crop_valid)
        for line in s.lines:
            print(line)
        before = os.stat(args.out).st_mtime_ns if os.path.exists(args.out) else None
        path = s.write(args.out, args.dataset, overwrite=args.overwrite)
        unchanged = before is not None and os.stat(path).st_mtime_ns == before
    except ImportError as e:
        print("veslide topography: %s" % e, file=sys.stderr)
        return 1
    except Exception as e:           # the readers raise their own kinds: each is a refused input here
        msg = _cli_words(str(e))
        print("veslide topography: %s" % (msg if args.scan in msg else "%s: %s" % (args.scan, msg)), file=sys.stderr)
        return 1
    print("%s %s:%s (%d x %d, %.6g x %.6g m; layout [iy, ix] in h5py, the solver's (nx, ny)); "
          "the preparation in its attribute 'preparation'%s"
          % ("unchanged:" if unchanged else "written:  ", path, args.dataset, s.nx, s.ny, s.length_x_m, s.length_y_m,
             " (the file held these heights already)" if unchanged else ""))
    print("use:       &grid nx = %d, ny = %d /  &surface kind = 'file', file = '%s', dataset = '%s' /"
          % (s.nx, s.ny, path, args.dataset))
    sys.stdout.flush()
    for w in caught:                 # last, where they are seen
        if issubclass(w.category, VeslideWarning):
            print("warning: %s" % _cli_words(str(w.message)), file=sys.stderr)
        else:
            warnings.warn_explicit(w.message, w.category, w.filename, w.lineno)
    return 0


def _pairs(items, what):
    out = {}
    for item in items:
        role, sep, value = item.partition("=")
        if not sep or not value:
            raise ValueError("--%s takes ROLE=VALUE, got %r" % (what, item))
        out[role.strip()] = int(value) if what == "column" and value.strip().isdigit() else value.strip()
    return out


def _material(args):
    """python -m veslide material: the route from a DMA export to the &material group."""
    from .material import DmaError, master_curve, read_dma
    out = args.out or os.path.splitext(args.export)[0] + ".nml"
    lines, caught = [], []
    try:
        if os.path.exists(out) and not args.overwrite:
            raise ValueError("%s exists: pass --overwrite to replace it" % out)
        with warnings.catch_warnings(record=True) as caught:
            warnings.simplefilter("always", VeslideWarning)
            sheet = int(args.sheet) if args.sheet.isdigit() else args.sheet
            table = read_dma(args.export, columns=_pairs(args.column, "column") or None,
                             units=_pairs(args.unit, "unit") or None, sheet=sheet, drop_bad=args.drop_bad)
            lines += table.attrs["lines"]
            mc = master_curve(table, args.reference_temperature, vertical=args.vertical)
            lines += mc.lines
            wlf = arr = None
            try:
                wlf = mc.fit_wlf()
                lines.append("WLF:      C1 = %.4g +- %.2g, C2 = %.4g +- %.2g K at %g C; misses log10 a_T by %.3f rms, "
                             "%.3f at most" % (wlf.wlf_c1, wlf.wlf_c1_error, wlf.wlf_c2_k, wlf.wlf_c2_k_error,
                                               wlf.reference_temperature_c, wlf.rms, wlf.max))
            except (ValueError, RuntimeError) as e:
                lines.append("WLF:      not fitted (%s)" % e)
            arr = mc.fit_arrhenius()
            lines.append("Arrhenius: Ea = %.4g +- %.2g kJ/mol; misses log10 a_T by %.3f rms, %.3f at most"
                         % (1e-3 * arr.activation_energy_j_mol, 1e-3 * arr.activation_energy_error, arr.rms, arr.max))
            law = {"wlf": wlf, "arrhenius": arr}.get(args.shift)
            m = mc.fit_prony(args.shift, law=law, form=args.form, terms_per_decade=args.terms_per_decade,
                             poisson=args.poisson)
            r = m.fit
            lines.append("series:   %d %s terms of %d candidates, times %.3g to %.3g s, E0 %.4g Pa, Einf %.4g Pa; "
                         "over %d points E' %.2f %% rms (%.2f %% max), E'' %.2f %% rms (%.2f %% max)"
                         % (r.n_terms, m.form, r.candidates, m.times_s.min(), m.times_s.max(), m.e0_pa, m.einf_pa,
                            r.frequency_hz.size, 100 * r.rms_error_storage, 100 * r.max_error_storage,
                            100 * r.rms_error_loss, 100 * r.max_error_loss))
            f_peak, tan_peak = m.loss_peak(args.temperature)
            lines.append("peak:     tan delta %.3g at %.3g Hz at %g C (within the data)"
                         % (tan_peak, f_peak, args.temperature if args.temperature is not None
                            else args.reference_temperature))
            text = m.namelist_text(args.temperature)
            if args.plot:
                import matplotlib
                matplotlib.use("Agg")
                fig = mc.plot()
                fig.savefig(args.plot, dpi=150)
                lines.append("plot:     %s" % args.plot)
        with open(out, "w") as fh:
            fh.write(text if text.endswith("\n") else text + "\n")
    except ImportError as e:
        print("veslide material: %s" % e, file=sys.stderr)
        return 1
    except (DmaError, ValueError, OSError) as e:
        for line in lines:
            print(line)
        print("veslide material: %s" % _cli_words(str(e)), file=sys.stderr)
        return 1
    for line in lines:
        print(line)
    t = m.shift_temperatures_c
    span = " (temperature_c, &sweep temperatures_c within %.1f to %.1f C)" % (t[0], t[-1]) if t is not None else ""
    print("written:  %s: &material model = '%s', %d terms, shift = '%s'%s" % (out, m.form, m.coefficients.size,
                                                                              m.shift, span))
    sys.stdout.flush()
    for w in caught:
        if issubclass(w.category, VeslideWarning):
            print("warning: %s" % _cli_words(str(w.message)), file=sys.stderr)
        else:
            warnings.warn_explicit(w.message, w.category, w.filename, w.lineno)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
