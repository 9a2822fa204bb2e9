"""Measured materials: a DMA export read (`read_dma`), its isothermal sweeps shifted into a master
curve (`master_curve`), a Prony series fitted to it, time-temperature superposition, and the
`&material` group that hands the series to the program.

    import veslide.material as vm
    table = vm.read_dma("export.csv")           # frequency_hz, storage_pa, loss_pa, temperature_c, sweep
    mc = vm.master_curve(table, reference_temperature_c=20)   # shift factors from the sweeps' overlap
    mc.fit_wlf()                                # WLF constants of the measured shift factors
    m = mc.fit_prony(shift="table")             # the series, with the measured a_T as its shift law
    m = vm.fit_prony(f_hz, storage_pa, loss_pa, reference_temperature_c=20, shift="wlf",
                     wlf_c1=17.44, wlf_c2_k=51.6)   # or: a master curve at 20 C given as such
    m.fit                                       # its error over the data
    m.modulus(f_hz)                             # E*(f) = E' + i E'' [Pa] at the reference
    m40 = m.at_temperature(40)                  # the same solid at 40 C (times shifted by a_T)
    veslide.run({"material": m40.to_namelist(), ...})

Conventions are the program's (README, Conventions): time dependence exp(+i w t), so
E*(w) = E' + i E'' with E'' > 0 and the compliance C(w) = 1/E*(w) has Im C < 0. A relaxation
(generalized Maxwell) series is E(t) = E0 + sum_j e_j exp(-t/rho_j),
E*(w) = E0 + sum_j e_j i w rho_j/(1 + i w rho_j); a creep series is
J(t) = 1/E0 - sum_k c_k exp(-t/tau_k), C(w) = 1/Einf + sum_k c_k/(1 + i w tau_k),
1/Einf = 1/E0 - sum_k c_k (src/physics/veslide_material.f90). E is Young's modulus.

Time-temperature superposition: E*(w, T) = E*(a_T w, Tref), i.e. every relaxation or retardation
time is multiplied by the shift factor a_T (`shift_factor`). The program applies the same shift
from `&material temperature_c, reference_temperature_c, shift, wlf_c1, wlf_c2_k,
activation_energy_j_mol, shift_temperatures_c, shift_log10_at`, which `Material.to_namelist`
writes.
"""
import copy
import math
import warnings
from dataclasses import dataclass, field

import numpy as np

__all__ = ["Material", "FitReport", "fit_prony", "shift_factor", "SHIFTS", "GAS_CONSTANT_J_MOL_K",
           "ZERO_CELSIUS_K", "WLF_UNIVERSAL_C1", "WLF_UNIVERSAL_C2_K", "MAX_TERMS", "MAX_TIME_S", "FIT_ERROR_WARN",
           "read_dma", "master_curve", "MasterCurve", "ShiftFit", "SAMPLE_DMA", "DmaError"]

#: the shift laws of `shift_factor` and of `&material shift`
SHIFTS = ("none", "wlf", "arrhenius", "table")
#: molar gas constant [J/(mol K)] (CODATA 2018, exact)
GAS_CONSTANT_J_MOL_K = 8.314462618
#: 0 degC in kelvin
ZERO_CELSIUS_K = 273.15
#: WLF's "universal" constants, for the glass transition temperature as the reference
#: (Williams, Landel & Ferry, J. Am. Chem. Soc. 77 (1955) 3701)
WLF_UNIVERSAL_C1 = 17.44
WLF_UNIVERSAL_C2_K = 51.6
#: most terms a `&material` list takes, and most points of a shift table (the reader's max_terms)
MAX_TERMS = 256
#: longest time [s] `&material` takes (the reader's max_time: w tau stays finite in the kernel)
MAX_TIME_S = 1.0e200
#: `fit_prony` warns (`prony-fit-error`) when the rms relative error of E' or E'' over the data
#: exceeds this: DMA data scatter by 1-5 %, which a good fit follows; 10 % is a fit that does not
#: follow its data (sweeps that did not superpose, a unit mixed up, a spectrum the grid of times
#: cannot hold)
FIT_ERROR_WARN = 0.10
# the reader's bounds on moduli [Pa] and times [s] (src/io/veslide_config_material.f90)
_MAX_MODULUS = 1.0e15
_MAX_TIME = MAX_TIME_S
# generalized cross validation counts each degree of freedom this many times: plain GCV (1)
# now and then undersmooths; 1.4 is the remedy of Kim & Gu (J. R. Stat. Soc. B 66 (2004) 337)
_GCV_GAMMA = 1.4
_FORMS = ("relaxation", "creep")
# most candidate times a fit offers (so its non-zero terms are MAX_TERMS at most)
_MAX_CANDIDATES = MAX_TERMS


def shift_factor(temperature_c, reference_temperature_c, shift="wlf", c1=WLF_UNIVERSAL_C1,
                 c2_k=WLF_UNIVERSAL_C2_K, activation_energy_j_mol=None, temperatures_c=None, log10_at=None):
    """The time-temperature shift factor a_T: E*(w, T) = E*(a_T w, Tref), every relaxation and
    retardation time at T being a_T times its value at Tref (a_T < 1 above Tref).

    - `shift='wlf'` (Williams, Landel & Ferry, J. Am. Chem. Soc. 77 (1955) 3701):
      log10 a_T = -c1 (T - Tref)/(c2_k + T - Tref); `c2_k` in kelvin (a temperature difference).
      The universal constants c1 = 17.44, c2 = 51.6 K hold for Tref = Tg. Defined for
      c2_k + T - Tref > 0 only (a ValueError otherwise).
    - `shift='arrhenius'`: ln a_T = (Ea/R)(1/T - 1/Tref), T in kelvin (T[C] + 273.15),
      R = 8.314462618 J/(mol K), Ea = `activation_energy_j_mol` (> 0).
    - `shift='table'`: measured shift factors, `log10_at` at `temperatures_c` (2 or more,
      temperatures strictly increasing, log10 a_T strictly decreasing: every relaxation is faster
      when warmer): log10 a_T = P(T) - P(Tref), P the monotone cubic through them (scipy's
      PchipInterpolator: Fritsch & Carlson, SIAM J. Numer. Anal. 17 (1980) 238); P(Tref) = 0
      when the table is relative to the reference. T and Tref outside the table are refused (a
      ValueError): measured shift factors are not extrapolated.
    - `shift='none'`: 1.

    `temperature_c` may be an array (the result is then an array of its shape); temperatures in
    degrees Celsius. The program computes the same from `&material` (same formulas, same
    constants; its PCHIP is the same as scipy's to 1e-15)."""
    shift = _shift_name(shift)
    t = np.asarray(temperature_c, dtype=float)
    tref = float(reference_temperature_c)
    if not (np.all(np.isfinite(t)) and math.isfinite(tref)):
        raise ValueError("shift_factor: temperatures must be finite, got %r and %r" % (temperature_c, tref))
    if shift == "none":
        out = np.ones_like(t)
    elif shift == "wlf":
        c1, c2 = float(c1), float(c2_k)
        if not (math.isfinite(c1) and math.isfinite(c2) and c2 > 0):
            raise ValueError("shift_factor: WLF needs finite c1 and c2_k > 0, got c1=%r, c2_k=%r" % (c1, c2))
        dt = t - tref
        if np.any(c2 + dt <= 0):
            raise ValueError("shift_factor: WLF is undefined at or below T = Tref - c2 = %g C (got T = %s)"
                             % (tref - c2, np.min(t)))
        out = 10.0 ** (-c1 * dt / (c2 + dt))
    elif shift == "table":
        tc, la = _shift_table(temperatures_c, log10_at)
        outside = [v for v in np.atleast_1d(t).ravel().tolist() + [tref] if not tc[0] <= v <= tc[-1]]
        if outside:
            raise ValueError("shift_factor: T = %g C is outside the shift table (shift_temperatures_c %g to %g C): "
                             "measured shift factors are not extrapolated" % (outside[0], tc[0], tc[-1]))
        from scipy.interpolate import PchipInterpolator
        p = PchipInterpolator(tc, la)
        out = 10.0 ** (p(t) - p(tref))
    else:
        ea = activation_energy_j_mol
        if ea is None or not (math.isfinite(float(ea)) and float(ea) > 0):
            raise ValueError("shift_factor: Arrhenius needs activation_energy_j_mol > 0, got %r" % (ea,))
        tk, trefk = t + ZERO_CELSIUS_K, tref + ZERO_CELSIUS_K
        if np.any(tk <= 0) or trefk <= 0:
            raise ValueError("shift_factor: temperatures must be above absolute zero")
        out = np.exp(float(ea) / GAS_CONSTANT_J_MOL_K * (1.0 / tk - 1.0 / trefk))
    return out if out.ndim else float(out)


def _shift_table(temperatures_c, log10_at):
    """A shift table checked as the program's reader checks it (one line naming the offending
    entry, 1-based as the namelist's): 2 to MAX_TERMS points, finite, temperatures above 0 K and
    strictly increasing, log10 a_T within +-300 and strictly decreasing."""
    if temperatures_c is None or log10_at is None:
        raise ValueError("shift 'table' needs shift_temperatures_c and shift_log10_at")
    tc = np.atleast_1d(np.asarray(temperatures_c, dtype=float)).ravel()
    la = np.atleast_1d(np.asarray(log10_at, dtype=float)).ravel()
    if not (2 <= tc.size <= MAX_TERMS and tc.size == la.size):
        raise ValueError("shift_temperatures_c and shift_log10_at must list the same number (2 to %d) of points, "
                         "got %d and %d" % (MAX_TERMS, tc.size, la.size))
    for k in range(tc.size):
        if not (math.isfinite(tc[k]) and tc[k] > -ZERO_CELSIUS_K):
            raise ValueError("shift_temperatures_c(%d) = %r must be finite and above -273.15 C" % (k + 1, tc[k]))
        if not (math.isfinite(la[k]) and abs(la[k]) <= 300):
            raise ValueError("shift_log10_at(%d) = %r must be finite and within -300 to 300" % (k + 1, la[k]))
        if k and not tc[k] > tc[k - 1]:
            raise ValueError("shift_temperatures_c(%d) = %g must be above shift_temperatures_c(%d) = %g: temperatures "
                             "strictly increasing" % (k + 1, tc[k], k, tc[k - 1]))
        if k and not la[k] < la[k - 1]:
            raise ValueError("shift_log10_at(%d) = %g must be below shift_log10_at(%d) = %g: a_T falls as the "
                             "temperature rises (every relaxation is faster when warmer)" % (k + 1, la[k], k, la[k - 1]))
    return tc, la


def _shift_name(shift):
    s = "none" if shift is None else str(shift).lower()
    if s not in SHIFTS:
        raise ValueError("shift must be one of %s, got %r" % (", ".join(map(repr, SHIFTS)), shift))
    return s


@dataclass
class FitReport:
    """How a fitted series meets its data (relative errors of the series as written, over the
    data points): `max_error_storage` = max |E'_fit/E'_data - 1|, likewise `loss` for E'', and
    their root mean squares. `frequency_hz` are the data's frequencies at the reference
    temperature (reduced by a_T when the data came at other temperatures), with `storage_pa`,
    `loss_pa` (Young's moduli: shear data are multiplied by 2(1 + poisson)).
    `candidates` relaxation times were offered, `n_terms` are non-zero (`dropped` zero ones left
    out); `smoothing` is the weight of the spectrum's smoothness (chosen by generalized cross
    validation unless given), `dof` the fit's effective number of parameters, and `floor_active`
    says that the relaxed (creep: glassy) modulus sits on its floor (the data do not reach the
    plateau; see `fit_prony`)."""
    frequency_hz: np.ndarray
    storage_pa: np.ndarray
    loss_pa: np.ndarray
    max_error_storage: float
    max_error_loss: float
    rms_error_storage: float
    rms_error_loss: float
    candidates: int
    n_terms: int
    dropped: int
    smoothing: float
    dof: float
    floor_active: bool = False
    temperature_c: object = None

    def __str__(self):
        return ("Prony fit: %d terms of %d candidates (%d zero, dropped), smoothing %.3g (%.1f dof); "
                "relative error over %d points: E' rms %.2f %%, max %.2f %%; E'' rms %.2f %%, max %.2f %%%s"
                % (self.n_terms, self.candidates, self.dropped, self.smoothing, self.dof, self.frequency_hz.size,
                   100 * self.rms_error_storage, 100 * self.max_error_storage, 100 * self.rms_error_loss,
                   100 * self.max_error_loss, "; relaxed modulus on its floor" if self.floor_active else ""))


@dataclass(eq=False)
class Material:
    """A linear viscoelastic solid given by a Prony series, as the program's `&material` takes it.

    `form` is 'relaxation' (`coefficients` e_j [Pa], `times_s` rho_j) or 'creep' (`coefficients`
    c_k [1/Pa], `times_s` tau_k); `e0_pa` is the relaxed (w -> 0) modulus in both; `poisson` the
    Poisson ratio. The series holds at `reference_temperature_c` (None: no temperature given);
    `shift` ('none', 'wlf', 'arrhenius', 'table') with `wlf_c1`, `wlf_c2_k`,
    `activation_energy_j_mol` or the measured `shift_temperatures_c`, `shift_log10_at` moves it
    to other temperatures; `temperature_c` is the temperature this object stands for (None: the
    reference). `fit` is the `FitReport` of a fitted series (None otherwise). Checked as the
    program's reader checks them: 1 to 256 terms, all positive and finite, E0 > 0, moduli at
    most 1e15 Pa and times at most 1e200 s, for creep sum c_k < 1/E0; a shift table as
    `shift_factor` says."""
    form: str
    e0_pa: float
    coefficients: np.ndarray
    times_s: np.ndarray
    poisson: float = 0.5
    reference_temperature_c: object = None
    shift: str = "none"
    wlf_c1: float = WLF_UNIVERSAL_C1
    wlf_c2_k: float = WLF_UNIVERSAL_C2_K
    activation_energy_j_mol: object = None
    temperature_c: object = None
    fit: object = field(default=None, repr=False)
    shift_temperatures_c: object = None
    shift_log10_at: object = None

    def __post_init__(self):
        if self.form not in _FORMS:
            raise ValueError("Material: form must be 'relaxation' or 'creep', got %r" % (self.form,))
        cn, tn = self._list_names()
        self.coefficients = np.atleast_1d(np.asarray(self.coefficients, dtype=float)).copy()
        self.times_s = np.atleast_1d(np.asarray(self.times_s, dtype=float)).copy()
        self.e0_pa, self.poisson = float(self.e0_pa), float(self.poisson)
        n = self.coefficients.size
        if self.coefficients.ndim != 1 or n != self.times_s.size or not 1 <= n <= MAX_TERMS:
            raise ValueError("Material: %s and %s must list the same number (1 to %d) of terms, got %d and %d"
                             % (cn, tn, MAX_TERMS, n, self.times_s.size))
        if not (0 < self.e0_pa <= _MAX_MODULUS):
            raise ValueError("Material: e0_pa = %r must be > 0 and <= 1e15 [Pa]" % self.e0_pa)
        for k, (c, t) in enumerate(zip(self.coefficients.tolist(), self.times_s.tolist())):
            if not (0 < c <= _MAX_MODULUS):
                raise ValueError("Material: %s(%d) = %r must be > 0 and finite" % (cn, k + 1, c))
            if not (0 < t <= _MAX_TIME):
                raise ValueError("Material: %s(%d) = %r must be > 0 and <= 1e200 [s]" % (tn, k + 1, t))
        if self.form == "creep" and not self.coefficients.sum() < 1.0 / self.e0_pa:
            raise ValueError("Material: sum of creep_c_per_pa %r must be below 1/e0_pa = %r (so that Einf > E0)"
                             % (self.coefficients.sum(), 1.0 / self.e0_pa))
        if not (0 <= self.poisson <= 0.5):
            raise ValueError("Material: poisson = %r must be 0 to 0.5" % self.poisson)
        self.shift = _shift_name(self.shift)
        if self.shift == "table":
            try:
                self.shift_temperatures_c, self.shift_log10_at = _shift_table(self.shift_temperatures_c,
                                                                              self.shift_log10_at)
            except ValueError as e:
                raise ValueError("Material: %s" % e) from None
        elif self.shift_temperatures_c is not None or self.shift_log10_at is not None:
            raise ValueError("Material: shift_temperatures_c and shift_log10_at have no use with shift %r"
                             % self.shift)
        if self.shift != "none" and self.reference_temperature_c is None:
            raise ValueError("Material: shift %r needs reference_temperature_c" % self.shift)
        if self.reference_temperature_c is not None:
            self.reference_temperature_c = float(self.reference_temperature_c)
            self.shift_factor(self.reference_temperature_c)          # checks the shift's constants
        if self.temperature_c is not None:
            if self.reference_temperature_c is None:
                raise ValueError("Material: temperature_c needs reference_temperature_c (and a shift)")
            self.temperature_c = float(self.temperature_c)
            self.shift_factor(self.temperature_c)

    # ---- constructors
    @classmethod
    def relaxation(cls, e0_pa, e_pa, rho_s, poisson=0.5, **tts):
        """Relaxation series E(t) = E0 + sum e_j exp(-t/rho_j); `tts`: the temperature keywords."""
        return cls("relaxation", e0_pa, e_pa, rho_s, poisson, **tts)

    @classmethod
    def creep(cls, e0_pa, c_per_pa, tau_s, poisson=0.5, **tts):
        """Creep series J(t) = 1/E0 - sum c_k exp(-t/tau_k); `tts`: the temperature keywords."""
        return cls("creep", e0_pa, c_per_pa, tau_s, poisson, **tts)

    @classmethod
    def from_namelist(cls, group):
        """A Material from a `&material` group (a dict or an f90nml group; 'relaxation', 'creep' or
        'one_term', with the program's defaults for what is not given)."""
        g = {str(k).lower(): v for k, v in dict(group).items()}
        model = str(g.get("model", "elastic")).lower()
        tts = {k: g[k] for k in ("reference_temperature_c", "shift", "wlf_c1", "wlf_c2_k",
                                 "activation_energy_j_mol", "temperature_c", "shift_temperatures_c",
                                 "shift_log10_at") if k in g}
        if "temperature_c" in tts and "reference_temperature_c" not in tts:
            tts["reference_temperature_c"] = tts["temperature_c"]     # no reference: no shift
        poisson = g.get("poisson", 0.5)
        if model == "relaxation":
            return cls.relaxation(g.get("e0_pa", 0.0), g.get("relax_e_pa", []), g.get("relax_rho_s", []), poisson,
                                  **tts)
        if model == "creep":
            return cls.creep(g.get("e0_pa", 0.0), g.get("creep_c_per_pa", []), g.get("creep_tau_s", []), poisson,
                             **tts)
        if model == "one_term":
            einf, ratio, tau = (float(g.get(k, d)) for k, d in (("einf_pa", 1e8), ("ratio", 11.0), ("tau_s", 0.01)))
            e0 = einf / ratio
            return cls.creep(e0, [1.0 / e0 - 1.0 / einf], [tau], poisson, **tts)
        raise ValueError("Material.from_namelist: model %r is not a Prony series" % model)

    # ---- the series
    def _list_names(self):
        return ("relax_e_pa", "relax_rho_s") if self.form == "relaxation" else ("creep_c_per_pa", "creep_tau_s")

    @property
    def einf_pa(self):
        """Glassy (w -> infinity) modulus [Pa]."""
        if self.form == "relaxation":
            return self.e0_pa + float(self.coefficients.sum())
        return 1.0 / (1.0 / self.e0_pa - float(self.coefficients.sum()))

    def shift_factor(self, temperature_c=None):
        """a_T of `temperature_c` (default: this object's temperature) against the reference;
        1 without a temperature."""
        t = self.temperature_c if temperature_c is None else temperature_c
        if t is None:
            return 1.0
        if self.reference_temperature_c is None:
            raise ValueError("Material: a temperature needs reference_temperature_c (and a shift)")
        return shift_factor(t, self.reference_temperature_c, self.shift, self.wlf_c1, self.wlf_c2_k,
                            self.activation_energy_j_mol, self.shift_temperatures_c, self.shift_log10_at)

    def modulus(self, frequency_hz, temperature_c=None):
        """Complex Young's modulus E*(f) = E' + i E'' [Pa] at frequencies [Hz], at `temperature_c`
        (default: this object's temperature): the series at a_T 2 pi f."""
        w = 2 * np.pi * np.asarray(frequency_hz, dtype=float) * self.shift_factor(temperature_c)
        x = np.multiply.outer(w, self.times_s)
        if self.form == "relaxation":
            return self.e0_pa + (self.coefficients * (1j * x) / (1 + 1j * x)).sum(-1)
        c = 1.0 / self.einf_pa + (self.coefficients / (1 + 1j * x)).sum(-1)
        return 1.0 / c

    def compliance(self, frequency_hz, temperature_c=None):
        """Complex compliance C = 1/E* [1/Pa] (Im C < 0), the program's C(w) at w = 2 pi f."""
        return 1.0 / self.modulus(frequency_hz, temperature_c)

    def tan_delta(self, frequency_hz, temperature_c=None):
        """Loss tangent E''/E'."""
        e = self.modulus(frequency_hz, temperature_c)
        return e.imag / e.real

    def loss_peak(self, temperature_c=None, *, within_data=None):
        """(frequency [Hz], tan delta) of the loss tangent's highest peak at `temperature_c`
        (default: this object's): a scan over log frequency (20 points a decade), refined by a
        bounded scalar search. A fitted series (`fit` set) is searched within its data's
        frequencies only (moved to the temperature: f / a_T), where the data vouch for it; where
        the series peaks higher outside them it warns (`extrapolated-loss-peak`, a VeslideWarning)
        with that peak, which no measurement confirms. `within_data=False`: over every time by two
        decades either side, as the program's `material_loss_peak`."""
        from scipy.optimize import minimize_scalar
        a_t = self.shift_factor(temperature_c)
        times = self.times_s * a_t
        lo = math.log(0.01 / times.max() / (2 * np.pi))
        hi = math.log(100.0 / times.min() / (2 * np.pi))

        def peak(lo, hi):
            lf = np.linspace(lo, hi, max(801, int(20 * (hi - lo) / math.log(10)) + 1))
            td = self.tan_delta(np.exp(lf), temperature_c)
            k = int(np.argmax(td))
            a, b = lf[max(k - 1, 0)], lf[min(k + 1, lf.size - 1)]
            r = minimize_scalar(lambda u: -self.tan_delta(math.exp(u), temperature_c), bounds=(a, b),
                                method="bounded", options={"xatol": 1e-10})
            return (math.exp(r.x), float(-r.fun)) if -r.fun >= td[k] else (math.exp(lf[k]), float(td[k]))

        every = peak(lo, hi)
        if within_data is False or self.fit is None:
            return every
        f_data = np.asarray(self.fit.frequency_hz, dtype=float) / a_t
        dlo, dhi = math.log(f_data.min()), math.log(f_data.max())
        inside = peak(dlo, dhi)
        if not dlo <= math.log(every[0]) <= dhi and every[1] > 1.01 * inside[1]:
            from ._warning import warn
            warn("the series' loss tangent peaks at %.3g (%.3g Hz) outside its data (%.3g to %.3g Hz), where it is "
                 "extrapolated and no measurement confirms it; within the data it peaks at %.3g (%.3g Hz)"
                 % (every[1], every[0], f_data.min(), f_data.max(), inside[1], inside[0]),
                 "extrapolated-loss-peak", every[1], inside[1], source="material")
        return inside

    # ---- temperature
    def at_temperature(self, temperature_c):
        """The same solid at `temperature_c` [C] (a copy; its series stays at the reference, and
        `modulus`, `to_namelist` apply the shift)."""
        if self.reference_temperature_c is None:
            raise ValueError("Material.at_temperature: this material has no reference_temperature_c")
        out = copy.copy(self)
        out.temperature_c = float(temperature_c)
        out.shift_factor()
        return out

    def shifted(self):
        """The same solid at its temperature as a series whose times already carry a_T, with that
        temperature as its reference (the WLF constants moved to it: c2' = c2 + T - Tref,
        c1' = c1 c2/c2'; Arrhenius keeps Ea; a shift table made relative to T, log10 a_T minus
        its value at T). For a program without `&material temperature_c`."""
        if self.temperature_c is None:
            return copy.copy(self)
        a_t, t, tref = self.shift_factor(), self.temperature_c, self.reference_temperature_c
        c1, c2 = self.wlf_c1, self.wlf_c2_k
        if self.shift == "wlf":
            c2 = self.wlf_c2_k + t - tref
            c1 = self.wlf_c1 * self.wlf_c2_k / c2
        table = {}
        if self.shift == "table":
            table = dict(shift_temperatures_c=self.shift_temperatures_c,
                         shift_log10_at=self.shift_log10_at - math.log10(a_t))
        return Material(self.form, self.e0_pa, self.coefficients, self.times_s * a_t, self.poisson,
                        reference_temperature_c=t, shift=self.shift, wlf_c1=c1, wlf_c2_k=c2,
                        activation_energy_j_mol=self.activation_energy_j_mol, fit=self.fit, **table)

    # ---- the namelist
    def to_namelist(self, temperature_c=None, *, shift_in_times=False):
        """The `&material` group as a dict (for `veslide.run({"material": m.to_namelist(), ...})`):
        model, poisson, e0_pa and the series; with a temperature law also reference_temperature_c,
        shift and its constants (or its table), and temperature_c (`temperature_c`, else this object's, else
        none: the program then takes the reference). `shift_in_times=True` writes instead the
        series at that temperature, its times multiplied by a_T, and no temperature variable
        (the same solid, for a program without `&material temperature_c`)."""
        t = self.temperature_c if temperature_c is None else float(temperature_c)
        if shift_in_times:
            m = self if t is None else self.at_temperature(t).shifted()
            return Material(m.form, m.e0_pa, m.coefficients, m.times_s, m.poisson).to_namelist()
        cn, tn = self._list_names()
        g = {"model": self.form, "poisson": self.poisson, "e0_pa": self.e0_pa,
             cn: [float(v) for v in self.coefficients], tn: [float(v) for v in self.times_s]}
        if self.reference_temperature_c is None:
            if t is not None:
                raise ValueError("Material.to_namelist: a temperature needs reference_temperature_c")
            return g
        self.shift_factor(t)                                  # the program would refuse it too
        g["reference_temperature_c"] = self.reference_temperature_c
        g["shift"] = self.shift
        if self.shift == "wlf":
            g["wlf_c1"], g["wlf_c2_k"] = float(self.wlf_c1), float(self.wlf_c2_k)
        elif self.shift == "arrhenius":
            g["activation_energy_j_mol"] = float(self.activation_energy_j_mol)
        elif self.shift == "table":
            g["shift_temperatures_c"] = [float(v) for v in self.shift_temperatures_c]
            g["shift_log10_at"] = [float(v) for v in self.shift_log10_at]
        if t is not None:
            g["temperature_c"] = t
        return g

    def namelist_text(self, temperature_c=None, *, shift_in_times=False):
        """The `&material ... /` group of `to_namelist` as namelist text (every number to full
        precision)."""
        import f90nml
        nml = f90nml.Namelist()
        g = self.to_namelist(temperature_c, shift_in_times=shift_in_times)
        nml["material"] = f90nml.Namelist(list(g.items()))                           # in this order
        return str(nml)

    def __str__(self):
        t = "" if self.reference_temperature_c is None else ", Tref %g C, shift %s%s" % (
            self.reference_temperature_c, self.shift,
            "" if self.temperature_c is None else ", at %g C (a_T %.4g)" % (self.temperature_c, self.shift_factor()))
        return ("%s series of %d terms, E0 %.4g Pa, Einf %.4g Pa, times %.3g..%.3g s%s"
                % (self.form, self.coefficients.size, self.e0_pa, self.einf_pa, self.times_s.min(),
                   self.times_s.max(), t))


def fit_prony(frequency_hz, storage_pa, loss_pa, *, form="relaxation", terms_per_decade=None, smoothing=None,
              poisson=0.5, shear=False, temperature_c=None, reference_temperature_c=None, shift="none",
              wlf_c1=WLF_UNIVERSAL_C1, wlf_c2_k=WLF_UNIVERSAL_C2_K, activation_energy_j_mol=None,
              floor=1e-3, shift_temperatures_c=None, shift_log10_at=None):
    """Fit a Prony series with non-negative terms to dynamic data: storage E' and loss E'' [Pa]
    at `frequency_hz` [Hz]. Returns a `Material` (its `.fit` is the `FitReport`).

    The relaxation (or, `form='creep'`, retardation) times are fixed on a log grid,
    `terms_per_decade` per decade (default 3; creep 6: a solid of a large Einf/E0 has a narrow
    retardation spectrum, which a coarser grid misses by a few per cent; even so the creep form
    fits less well: on the 20-term solid of the tests, with 3 % noise, E'' to 3-7 % against 1-3 %
    for the relaxation form, which is the one to use for DMA data; a spectrum narrower than
    the grid, such as a single Debye term, is met to 7-10 % at 3 a decade, 1-2 % at 6, 0.3 % at
    20) from a
    decade below 1/(2 pi f_max) to a decade above
    1/(2 pi f_min) (creep: further by the ratio of the largest to the smallest E', as retardation
    times exceed relaxation times by up to Einf/E0; 256 candidates at most); the terms and the relaxed
    modulus E0 (creep: 1/Einf and the c_k) then enter linearly, and are found by bounded linear
    least squares (scipy's `lsq_linear`, method 'bvls', an exact active-set solver) on the
    relative errors of E' and E'' (creep: of J' and J'' of J* = 1/E*), every unknown >= 0. A
    penalty `smoothing` * |second differences of the terms|^2 keeps the spectrum from fitting the
    noise; by default its weight is chosen by generalized cross validation (Golub, Heath & Wahba,
    Technometrics 21 (1979) 215; each degree of freedom counted 1.4 times against undersmoothing,
    Kim & Gu, J. R. Stat. Soc. B 66 (2004) 337) over 1e-4..1e6; `smoothing=0` fits without it. Terms that come
    out zero (or below 1e-12 of the largest) are dropped.

    E0 (creep: 1/Einf) is kept at or above `floor` times the smallest measured E' (J'): the
    program needs it positive. When the data do not reach the rubbery plateau it sits on that
    floor; the fit warns and says so (`fit.floor_active`, a VeslideWarning `rubbery-plateau`):
    the series is then not to be trusted below the data's frequencies. When the rms relative
    error of E' or E'' over the data exceeds `FIT_ERROR_WARN` (10 %) it warns
    (`prony-fit-error`): the series does not follow its data.

    `shear=True`: the data are shear moduli G', G'' and are turned into Young's moduli with
    E = 2 (1 + poisson) G. `temperature_c` (a number or one per point, [C]): the temperatures
    the data were measured at; each frequency is then reduced to the reference temperature,
    f a_T (`shift_factor` with `reference_temperature_c`, `shift` and its constants), so that a
    DMA table of isothermal sweeps gives the master curve at the reference (`master_curve` finds
    the shift factors from the sweeps themselves; `shift='table'` with `shift_temperatures_c`,
    `shift_log10_at` takes measured ones). Without it the data are taken as the master curve at
    `reference_temperature_c` (None: no temperature law).

    Refused (a ValueError, one line): a point whose frequency, E' or E'' is not positive and
    finite, named by its index (and temperature); times beyond 1e200 s (the message names the
    reference temperature at which the data's lowest frequency would fit); more than
    `MAX_TERMS` non-zero terms."""
    from scipy.optimize import lsq_linear

    f = np.asarray(frequency_hz, dtype=float).ravel()
    s = np.asarray(storage_pa, dtype=float).ravel()
    ls = np.asarray(loss_pa, dtype=float).ravel()
    if not (f.size == s.size == ls.size) or f.size < 3:
        raise ValueError("fit_prony: frequency_hz, storage_pa and loss_pa must have the same length (3 or more), "
                         "got %d, %d and %d" % (f.size, s.size, ls.size))
    t_given = None if temperature_c is None else np.broadcast_to(np.asarray(temperature_c, dtype=float), f.shape)
    for name, v in (("frequency_hz", f), ("storage_pa", s), ("loss_pa", ls)):
        bad = np.flatnonzero(~(np.isfinite(v) & (v > 0)))
        if bad.size:
            k = int(bad[0])
            at = "" if t_given is None else ", %g C" % t_given[k]
            raise ValueError("fit_prony: %s[%d] = %r is not positive and finite (point %d: %g Hz%s); %d such point%s: "
                             "drop them (read_dma(..., drop_bad=True) names and drops them)"
                             % (name, k, float(v[k]), k, f[k], at, bad.size, "" if bad.size == 1 else "s"))
    if form not in _FORMS:
        raise ValueError("fit_prony: form must be 'relaxation' or 'creep', got %r" % (form,))
    if terms_per_decade is None:
        terms_per_decade = 3.0 if form == "relaxation" else 6.0
    if not terms_per_decade > 0:
        raise ValueError("fit_prony: terms_per_decade must be positive, got %r" % (terms_per_decade,))
    if shear:
        s, ls = 2 * (1 + poisson) * s, 2 * (1 + poisson) * ls
    tts = dict(reference_temperature_c=reference_temperature_c, shift=shift, wlf_c1=wlf_c1, wlf_c2_k=wlf_c2_k,
               activation_energy_j_mol=activation_energy_j_mol)
    if _shift_name(shift) == "table":
        tts.update(shift_temperatures_c=shift_temperatures_c, shift_log10_at=shift_log10_at)
    temps = None
    if temperature_c is not None:
        if reference_temperature_c is None:
            raise ValueError("fit_prony: temperature_c needs reference_temperature_c (and a shift)")
        temps = t_given.copy()
        f = f * shift_factor(temps, reference_temperature_c, shift, wlf_c1, wlf_c2_k, activation_energy_j_mol,
                             shift_temperatures_c, shift_log10_at)
    order = np.argsort(f, kind="stable")
    f, s, ls = f[order], s[order], ls[order]
    temps = None if temps is None else temps[order]

    # candidate times: a decade beyond the data's either side, at most MAX_TERMS of them
    lo, hi = 0.1 / (2 * np.pi * f[-1]), 10.0 / (2 * np.pi * f[0])
    if form == "creep":          # retardation times lie up to Einf/E0 beyond the relaxation times
        hi *= max(1.0, float(s.max() / s.min()))
    decades = math.log10(hi / lo)
    n = int(min(_MAX_CANDIDATES, max(3, math.ceil(decades * terms_per_decade) + 1)))
    times = np.geomspace(lo, hi, n)
    if times.max() > _MAX_TIME:
        raise ValueError("fit_prony: the data's lowest frequency %g Hz (at the reference) needs times up to %.3g s, "
                         "beyond the program's 1e200 s%s" % (f[0], times.max(), _warmer_reference(times.max(), tts)))

    # unknowns u = [k0, a_1..a_n] in units of `scale`: relaxation E0 = scale k0, e_j = scale a_j;
    # creep 1/Einf = scale k0, c_k = scale a_k. Rows: the relative errors of the real and the
    # (sign-free) imaginary part.
    x = np.outer(2 * np.pi * f, times)
    if form == "relaxation":
        re_data, im_data = s, ls
        re_cols, im_cols = x ** 2 / (1 + x ** 2), x / (1 + x ** 2)
    else:
        mag2 = s ** 2 + ls ** 2
        re_data, im_data = s / mag2, ls / mag2
        re_cols, im_cols = 1 / (1 + x ** 2), x / (1 + x ** 2)
    scale = float(re_data.max())
    a_re = np.hstack([np.ones((f.size, 1)), re_cols]) * (scale / re_data)[:, None]
    a_im = np.hstack([np.zeros((f.size, 1)), im_cols]) * (scale / im_data)[:, None]
    a_mat = np.vstack([a_re, a_im])
    rhs = np.ones(a_mat.shape[0])
    k0_min = floor * float(re_data.min()) / scale
    lower = np.zeros(n + 1)
    lower[0] = k0_min
    d2 = np.zeros((n - 2, n + 1))
    for i in range(n - 2):
        d2[i, 1 + i:4 + i] = (1.0, -2.0, 1.0)

    def solve(lam):
        a_aug = np.vstack([a_mat, math.sqrt(lam) * d2]) if lam > 0 else a_mat
        b_aug = np.concatenate([rhs, np.zeros(d2.shape[0])]) if lam > 0 else rhs
        r = lsq_linear(a_aug, b_aug, bounds=(lower, np.inf), method="bvls", tol=1e-12, max_iter=50 * (n + 1))
        u = np.maximum(r.x, lower)
        free = u > lower
        af, lf = a_mat[:, free], d2[:, free]
        gram = af.T @ af
        dof = float(np.trace(np.linalg.pinv(gram + lam * (lf.T @ lf)) @ gram)) if free.any() else 0.0
        rss = float(np.sum((a_mat @ u - rhs) ** 2))
        return u, rss, dof

    m_rows = a_mat.shape[0]
    if smoothing is None:
        best = None
        for lam in np.logspace(-4, 6, 21):
            u, rss, dof = solve(lam)
            gcv = m_rows * rss / max(m_rows - _GCV_GAMMA * dof, 1.0) ** 2
            if best is None or gcv < best[0]:
                best = (gcv, lam, u, dof)
        _, lam, u, dof = best
    else:
        lam = float(smoothing)
        if not (lam >= 0 and math.isfinite(lam)):
            raise ValueError("fit_prony: smoothing must be >= 0 or None, got %r" % (smoothing,))
        u, _, dof = solve(lam)

    floor_active = bool(u[0] <= k0_min * (1 + 1e-9))
    terms = u[1:]
    keep = terms > 1e-12 * terms.max() if terms.max() > 0 else np.zeros(n, bool)
    if not keep.any():
        raise ValueError("fit_prony: the data show no relaxation (every term zero): an elastic solid?")
    if keep.sum() > MAX_TERMS:        # (not reached: at most _MAX_CANDIDATES = MAX_TERMS are offered)
        raise ValueError("fit_prony: %d non-zero terms, more than the program's %d: lower terms_per_decade (%g)"
                         % (keep.sum(), MAX_TERMS, terms_per_decade))
    coef, k0 = scale * terms[keep], scale * u[0]
    if form == "relaxation":
        e0 = k0
    else:
        e0 = 1.0 / (k0 + coef.sum())
    mat = Material(form, e0, coef, times[keep], poisson, **tts)
    fitted = mat.modulus(f, mat.reference_temperature_c)
    es, el = fitted.real / s - 1, fitted.imag / ls - 1
    mat.fit = FitReport(frequency_hz=f, storage_pa=s, loss_pa=ls, max_error_storage=float(np.abs(es).max()),
                        max_error_loss=float(np.abs(el).max()), rms_error_storage=float(np.sqrt(np.mean(es ** 2))),
                        rms_error_loss=float(np.sqrt(np.mean(el ** 2))), candidates=n, n_terms=int(keep.sum()),
                        dropped=int(n - keep.sum()), smoothing=float(lam), dof=dof, floor_active=floor_active,
                        temperature_c=temps)
    from ._warning import warn
    if floor_active:
        warn("fit_prony: the data do not reach the %s plateau: %s set to its floor %.3g Pa (floor=%g); "
             "the series is not to be trusted below %.3g Hz"
             % ("rubbery" if form == "relaxation" else "glassy", "E0" if form == "relaxation" else "Einf",
                k0 if form == "relaxation" else 1.0 / k0, floor, f[0]),
             "rubbery-plateau" if form == "relaxation" else "glassy-plateau", float(floor), float(floor),
             source="material")
    worst = max(mat.fit.rms_error_storage, mat.fit.rms_error_loss)
    if worst > FIT_ERROR_WARN:
        warn("fit_prony: the series misses its data by %.1f %% rms (E' %.1f %%, E'' %.1f %%; above %g %%): it does "
             "not follow them. Sweeps shifted with wrong shift factors (master_curve finds them from the data), "
             "moduli in mixed units, or a spectrum beyond the grid of times (terms_per_decade) leave such errors"
             % (100 * worst, 100 * mat.fit.rms_error_storage, 100 * mat.fit.rms_error_loss, 100 * FIT_ERROR_WARN),
             "prony-fit-error", worst, FIT_ERROR_WARN, source="material")
    return mat


def _warmer_reference(longest_s, tts):
    """'; at a reference of T C or warmer they fit' for a fit whose times exceed MAX_TIME_S, from
    its shift law (empty without one, or when no temperature of the law brings them in)."""
    law = {k: tts.get(k) for k in ("shift", "wlf_c1", "wlf_c2_k", "activation_energy_j_mol", "shift_temperatures_c",
                                   "shift_log10_at")}
    tref = tts.get("reference_temperature_c")
    if tref is None or _shift_name(law["shift"]) == "none":
        return ": the data span too many decades for one series (give a temperature law and a warmer reference)"
    target = math.log10(MAX_TIME_S / longest_s) - 1.0            # a decade to spare

    def g(t):
        return math.log10(shift_factor(t, tref, law["shift"], law["wlf_c1"], law["wlf_c2_k"],
                                       law["activation_energy_j_mol"], law["shift_temperatures_c"],
                                       law["shift_log10_at"])) - target
    top = float(np.max(law["shift_temperatures_c"])) if law["shift"] == "table" else tref + 1000.0
    try:
        if g(top) > 0:
            return ""
        from scipy.optimize import brentq
        return "; at a reference_temperature_c of %.1f C or warmer they fit" % (math.ceil(10 * brentq(g, tref, top)) / 10)
    except ValueError:
        return ""


# the route from an instrument's export: reading it and shifting its sweeps (veslide/_dma.py)
from ._dma import DmaError, MasterCurve, SAMPLE_DMA, ShiftFit, master_curve, read_dma  # noqa: E402
