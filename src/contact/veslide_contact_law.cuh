// The contact laws' per-cell maps for the CUDA twins of the passes (their Fortran twins:
// veslide_contact_law_maps.inc; the law itself: veslide_contact_law.f90). Each law is a small
// struct whose VS_HD methods a pass's functor calls through its template parameter; `with_law`
// chooses the struct once per pass call, from the law's id and parameters as the Fortran
// dispatcher passes them (contact_law_t%kind, %param), never per cell.
#pragma once
#include "../core/veslide_device.cuh"

namespace vs {

// veslide_contact_law's LAW_* ids
enum law_kind { law_hard_wall = 1, law_exponential = 2, law_dugdale = 3 };

// The hard wall (Signorini): p >= 0, g >= 0, p g = 0; contact where p > 0
struct hard_wall {
    // the proximal map the splitting solvers apply: the projection onto p >= 0
    VS_HD double project(double v) const { return fmax(v, 0.0); }
    // what counts as contact
    VS_HD bool in_contact(double p) const { return p > 0.0; }
    // does the projection of v - c put the cell in contact (decided without forming v - c)?
    VS_HD bool in_contact_shifted(double v, double c) const { return v > c; }
    // a pressure past the bound p >= 0 (an active-set solver clips it)
    VS_HD bool below(double p) const { return p < 0.0; }
    // a gap past the bound g >= 0 (an active-set solver admits the cell)
    VS_HD bool penetrates(double g) const { return g < 0.0; }
    // the cell's part of the sums its residual measures take: s += [p g, |p|, p], m = min(m, [g, p])
    VS_HD void residual_sums(double p, double g, double *s, double *m) const {
        s[0] += p * g;
        s[1] += fabs(p);
        s[2] += p;
        m[0] = fmin(m[0], g);
        m[1] = fmin(m[1], p);
    }
};

// The adhesive laws' attractions sigma(g) (their Fortran twins: the maps *_attraction), with
// sigma0 and the range rho in the units of the caller (SI, or a solve's)
struct exponential {
    double s0, rho;
    static constexpr bool dugdale = false;
    VS_HD double attraction(double g) const { return s0 * exp(-fmax(g, 0.0) / rho); }
};
struct dugdale_zone {
    double s0, rho;
    static constexpr bool dugdale = true;
    VS_HD double attraction(double g) const { return g < rho ? s0 : 0.0; }
};

// f(law) with the adhesive law of id `kind` (sigma0 `s0`, range `rho`); another id is noted as
// the pass's error
template <class F>
void with_adhesive_law(int kind, double s0, double rho, const char *pass, F &&f) {
    switch (kind) {
    case law_exponential: f(exponential{s0, rho}); break;
    case law_dugdale: f(dugdale_zone{s0, rho}); break;
    default: note_error(pass, "not an adhesive law");
    }
}

// f(law) with the law of id `kind` and parameters `param` (the law's own order; the hard wall
// has none); an id no case names is noted as the pass's error (device_check reports it)
template <class F>
void with_law(int kind, const double *param, const char *pass, F &&f) {
    (void)param;
    switch (kind) {
    case law_hard_wall: f(hard_wall{}); break;
    default: note_error(pass, "a contact law the device passes do not know");
    }
}

}  // namespace vs
