// CUDA twins of veslide_gcg_passes.F90 (the conjugate gradients on the gap, for the adhesive
// laws); each functor does for one element what the CPU twin's loop body does, in the same order
// of operations. The passes of the law's attraction take the law as their functor's template
// argument (vs::exponential, vs::dugdale_zone), chosen once per call.
#include "../core/veslide_device.cuh"
#include "veslide_contact_law.cuh"
#include <stdint.h>

namespace {

// veslide_gcg_passes.F90's ROWS_* ids
enum { ATTRACT, FREE_SET, CENTRE, MASK, DOT, SHIFT_DOT, DIRECTION, CURVATURE, STEP, GAP_SUMS, SHIFT_OPEN, EXTREMES };

// at = r + sigma(g); Dugdale: edge = (g == rho). sums: [at, 1] over the open cells off the
// edge, [1] over the edge
template <class Law>
struct attract_f {
    Law law;
    const double *g, *r;
    double *at;
    int8_t *edge;
    int nx;
    VS_HD void operator()(int i, int j, double *s, double *) const {
        long n = i + (long)nx * j;
        double a = r[n] + law.attraction(g[n]);
        at[n] = a;
        bool e = Law::dugdale && g[n] == law.rho;
        edge[n] = e ? 1 : 0;
        if (e) {
            s[2] += 1.0;
        } else if (g[n] > 0.0) {
            s[0] += a;
            s[1] += 1.0;
        }
    }
};

// the free set; sums: [at, 1] over it
struct free_set_f {
    const double *g, *r;
    double *at;
    int8_t *free;
    const int8_t *edge;
    double lam, s0;
    bool held;
    int nx;
    VS_HD void operator()(int i, int j, double *s, double *) const {
        long n = i + (long)nx * j;
        double a = at[n];
        bool f = (g[n] > 0.0 && edge[n] == 0) || (g[n] <= 0.0 && a - lam < 0.0);
        if (held && edge[n] == 1) {
            double d = r[n] - lam;
            f = d > 0.0 || d < -s0;
            a = r[n] + (d > 0.0 ? s0 : (d < -s0 ? 0.0 : lam - r[n]));
            at[n] = a;
        }
        free[n] = f ? 1 : 0;
        if (f) {
            s[0] += a;
            s[1] += 1.0;
        }
    }
};

// at = at - lam on the free set, 0 off it; minima: [-violation]
struct centre_f {
    const double *g;
    double *at;
    const int8_t *free, *edge;
    double lam;
    int nx;
    VS_HD void operator()(int i, int j, double *, double *m) const {
        long n = i + (long)nx * j;
        double a = at[n] - lam;
        if (edge[n] == 1 && free[n] == 0) a = 0.0;
        double v = g[n] > 0.0 ? fabs(a) : fmax(-a, 0.0);
        m[0] = fmin(m[0], -v);
        at[n] = free[n] == 1 ? a : 0.0;
    }
};

// a = 0 off the free set; sums: [a, 1] over it
struct mask_f {
    double *a;
    const int8_t *free;
    int nx;
    VS_HD void operator()(int i, int j, double *s, double *) const {
        long n = i + (long)nx * j;
        if (free[n] == 1) {
            s[0] += a[n];
            s[1] += 1.0;
        } else {
            a[n] = 0.0;
        }
    }
};

// sums: [a b]; with `shift`: a = a - c on the free set first (sums: [b a])
struct dot_f {
    double *a;
    const double *b;
    const int8_t *free;
    double c;
    bool shift;
    int nx;
    VS_HD void operator()(int i, int j, double *s, double *) const {
        long n = i + (long)nx * j;
        if (shift) {
            if (free[n] == 1) a[n] = a[n] - c;
            s[0] += b[n] * a[n];
        } else {
            s[0] += a[n] * b[n];
        }
    }
};

// t = z + beta t on the free set, 0 off it; sums: [at t]
struct direction_f {
    const double *z, *at;
    double *t;
    const int8_t *free;
    double beta;
    int nx;
    VS_HD void operator()(int i, int j, double *s, double *) const {
        long n = i + (long)nx * j;
        double v = free[n] == 1 ? z[n] + beta * t[n] : 0.0;
        t[n] = v;
        s[0] += at[n] * v;
    }
};

// sums over the free set: [pz t, pz, 1, t]
struct curvature_f {
    const double *pz, *t;
    const int8_t *free;
    int nx;
    VS_HD void operator()(int i, int j, double *s, double *) const {
        long n = i + (long)nx * j;
        if (free[n] == 1) {
            s[0] += pz[n] * t[n];
            s[1] += pz[n];
            s[2] += 1.0;
            s[3] += t[n];
        }
    }
};

// g = max(g - tau t, 0), stopped at Dugdale's edge; sums: [cells stopped, cells clipped];
// minima: [g - tau t]
struct step_f {
    double *g;
    const double *t;
    int8_t *edge;
    double tau, rho;
    bool dugdale;
    int nx;
    VS_HD void operator()(int i, int j, double *s, double *m) const {
        long n = i + (long)nx * j;
        bool below = g[n] < rho;
        double v = g[n] - tau * t[n];
        m[0] = fmin(m[0], v);
        if (v < 0.0) s[1] += 1.0;
        v = fmax(v, 0.0);
        if (dugdale) {
            bool stop = (below && v > rho) || (!below && v < rho && v - (-(tau * t[n])) > rho);
            if (stop) {
                v = rho;
                s[0] += 1.0;
            }
            edge[n] = stop ? 1 : 0;
        }
        g[n] = v;
    }
};

// (g = max(g, 0) first where `clip`) sums: [g, 1 where g > 0]
struct gap_sums_f {
    double *g;
    bool clip;
    int nx;
    VS_HD void operator()(int i, int j, double *s, double *) const {
        long n = i + (long)nx * j;
        double v = g[n];
        if (clip) {
            v = fmax(v, 0.0);
            g[n] = v;
        }
        s[0] += v;
        if (v > 0.0) s[1] += 1.0;
    }
};

// g = g + c where g > 0; minima: [g]
struct shift_open_f {
    double *g;
    double c;
    int nx;
    VS_HD void operator()(int i, int j, double *, double *m) const {
        long n = i + (long)nx * j;
        double v = g[n];
        if (v > 0.0) {
            v = v + c;
            g[n] = v;
        }
        m[0] = fmin(m[0], v);
    }
};

// minima: [a, -a]
struct extremes_f {
    const double *a;
    int nx;
    VS_HD void operator()(int i, int j, double *, double *m) const {
        long n = i + (long)nx * j;
        m[0] = fmin(m[0], a[n]);
        m[1] = fmin(m[1], -a[n]);
    }
};

// the Fourier multipliers (veslide_gcg_passes.F90's SPECTRAL_*)
struct spectral_f {
    double2 *k;
    const double *ainv;
    const double2 *kinv;
    double c1, cells;
    int mode;
    VS_HD void operator()(long n) const {
        switch (mode) {
        case 0:   // A
            k[n] = vs::cscale(ainv[n], k[n]);
            break;
        case 1:   // K: 1/((A N + c1) N)
            k[n] = ainv[n] != 0.0 ? vs::cdivr(k[n], (ainv[n] * cells + c1) * cells) : vs::cx(0.0, 0.0);
            break;
        case 2:   // the operator
            k[n] = vs::cmul(k[n], kinv[n]);
            break;
        case 3: {   // the resolvent: k/((1 + K/A) N)
            double2 q = kinv[n];
            if (q.x != 0.0 || q.y != 0.0) {
                double2 u = vs::cdivr(q, ainv[n]);
                double2 den = vs::cscale(cells, vs::cx(1.0 + u.x, u.y));
                k[n] = vs::cdiv(k[n], den);
            } else {
                k[n] = vs::cdivr(k[n], cells);
            }
            break;
        }
        default: {   // the start: k (K/A)/N
            double2 q = kinv[n];
            if (q.x != 0.0 || q.y != 0.0) {
                double2 u = vs::cdivr(q, ainv[n]);
                k[n] = vs::cdivr(vs::cmul(k[n], u), cells);
            } else {
                k[n] = vs::cx(0.0, 0.0);
            }
        }
        }
    }
};

// the element-wise combinations (veslide_gcg_passes.F90's COMBINE_*)
struct combine_f {
    double *d;
    const double *a, *b;
    double c1, c2, c3;
    int mode;
    VS_HD void operator()(long n) const {
        switch (mode) {
        case 0: d[n] = a[n] + b[n]; break;
        case 1: d[n] = (a[n] - b[n]) - c1; break;
        case 2: d[n] = a[n] - 2.0 * b[n]; break;
        case 3: d[n] = d[n] + c1*(a[n] - b[n]); break;
        case 4: d[n] = c1 + c2 * (a[n] - c3); break;
        case 5: d[n] = c2 * ((a[n] + b[n]) - c1); break;
        case 6: d[n] = c1 - a[n]; break;
        default: d[n] = d[n] - c1 * a[n];
        }
    }
};

}  // namespace

extern "C" {

// The passes with row values. `flag`: the law's id (ATTRACT, STEP), `held` (FREE_SET), `clip`
// (GAP_SUMS); x1 the pass's scalar (lam, beta, c, tau); the arrays as each pass names them
void veslide_gcg_rows(int mode, int flag, double s0, double rho, int nx, int ny, double *a, double *b, double *c,
                      double *d, int8_t *free, int8_t *edge, double x1, double x2, double *rows) {
    (void)d;
    (void)x2;
    switch (mode) {
    case ATTRACT:
        vs::with_adhesive_law(flag, s0, rho, "gcg attract", [&](auto l) {
            vs::reduce_rows<3, 0>(attract_f<decltype(l)>{l, a, b, c, edge, nx}, nx, ny, rows);
        });
        break;
    case FREE_SET: vs::reduce_rows<2, 0>(free_set_f{a, b, c, free, edge, x1, s0, flag != 0, nx}, nx, ny, rows); break;
    case CENTRE: vs::reduce_rows<0, 1>(centre_f{a, c, free, edge, x1, nx}, nx, ny, rows); break;
    case MASK: vs::reduce_rows<2, 0>(mask_f{a, free, nx}, nx, ny, rows); break;
    case DOT: vs::reduce_rows<1, 0>(dot_f{a, b, free, 0.0, false, nx}, nx, ny, rows); break;
    case SHIFT_DOT: vs::reduce_rows<1, 0>(dot_f{a, b, free, x1, true, nx}, nx, ny, rows); break;
    case DIRECTION: vs::reduce_rows<1, 0>(direction_f{a, b, c, free, x1, nx}, nx, ny, rows); break;
    case CURVATURE: vs::reduce_rows<4, 0>(curvature_f{a, b, free, nx}, nx, ny, rows); break;
    case STEP:
        vs::reduce_rows<2, 1>(step_f{a, b, edge, x1, rho, flag == vs::law_dugdale, nx}, nx, ny, rows);
        break;
    case GAP_SUMS: vs::reduce_rows<2, 0>(gap_sums_f{a, flag != 0, nx}, nx, ny, rows); break;
    case SHIFT_OPEN: vs::reduce_rows<0, 1>(shift_open_f{a, x1, nx}, nx, ny, rows); break;
    case EXTREMES: vs::reduce_rows<0, 2>(extremes_f{a, nx}, nx, ny, rows); break;
    default: vs::note_error("gcg rows", "a pass this library does not have");
    }
}

void veslide_gcg_spectral(long n, int mode, double2 *k, const double *ainv, const double2 *kinv, double c1,
                          double cells) {
    vs::for_each(spectral_f{k, ainv, kinv, c1, cells, mode}, n);
}

void veslide_gcg_combine(long n, int mode, double *d, const double *a, const double *b, double c1, double c2,
                         double c3) {
    vs::for_each(combine_f{d, a, b, c1, c2, c3, mode}, n);
}

}  // extern "C"
