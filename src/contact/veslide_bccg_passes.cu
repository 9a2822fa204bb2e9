// CUDA twins of veslide_bccg_passes.F90 (the bound-constrained CG's passes); each functor does
// for one element what the CPU twin's loop body does, in the same order of operations, with the
// hard wall's maps (vs::hard_wall: BCCG takes that law only).
#include "../core/veslide_device.cuh"
#include "veslide_contact_law.cuh"
#include <stdint.h>

namespace {

// (the metric's values, formed as each pass forms them: vs::metric_v)
struct metric_f {
    double *ks;
    vs::metric_v m;
    VS_HD void operator()(long n) const { ks[n] = m[n]; }
};

struct set_contact_f {
    int8_t *act;
    const double *p;
    VS_HD void operator()(long n) const { act[n] = vs::hard_wall{}.in_contact(p[n]) ? 1 : 0; }
};

// sums: [g on the set, p g, p, set size]; minima: [g]
struct statistics_f {
    const double *x, *p;
    const int8_t *act;
    double gprev;
    int nx;
    VS_HD void operator()(int i, int j, double *s, double *m) const {
        long n = i + (long)nx * j;
        double g = x[n] - gprev;
        if (act[n] != 0) {
            s[3] += 1.0;
            s[0] += g;
        }
        m[0] = fmin(m[0], g);
        s[1] += p[n] * g;
        s[2] += p[n];
    }
};

struct residual_f {
    double *x;
    int8_t *act;
    const double *v;
    double gbar;
    int nx;
    VS_HD void operator()(int i, int j, double *s, double *) const {
        long n = i + (long)nx * j;
        double g = x[n] - gbar;
        int8_t a = act[n];
        if (a == 0 && vs::hard_wall{}.penetrates(g)) {
            a = 1;
            act[n] = 1;
        }
        if (a != 0) {
            x[n] = -g;
            s[0] -= g * v[n];
            s[1] -= g;
            s[2] += v[n];
            s[3] += 1.0;
        } else {
            x[n] = 0.0;
        }
    }
};

struct precondition_f {
    double2 *k;
    vs::metric_v ks;
    const double *wa;
    double n2;
    int na;
    VS_HD void operator()(int i, int j, double *s, double *) const {
        long n = i + (long)na * j;
        double w = 0.0, m = ks[n];
        if (m > 0.0) w = 1.0 / (m * n2);
        double2 kv = k[n];
        s[0] += wa[i] * w * (kv.x * kv.x + kv.y * kv.y);
        k[n] = vs::cx(kv.x * w, kv.y * w);
    }
};

struct set_sum_f {
    const double *x;
    const int8_t *act;
    int nx;
    VS_HD void operator()(int i, int j, double *s, double *) const {
        long n = i + (long)nx * j;
        if (act[n] != 0) s[0] += x[n];
    }
};

struct direction_f {
    double *x, *v;
    const int8_t *act;
    double beta, shift;
    VS_HD void operator()(long n) const {
        double z = act[n] != 0 ? x[n] + beta * v[n] - shift : 0.0;
        v[n] = z;
        x[n] = z;
    }
};

struct energy_f {
    const double2 *k;
    vs::metric_v ks;
    const double *wa;
    int na;
    VS_HD void operator()(int i, int j, double *s, double *) const {
        long n = i + (long)na * j;
        double2 kv = k[n];
        s[0] += wa[i] * ks[n] * (kv.x * kv.x + kv.y * kv.y);
    }
};

// sums: [p, clipped]
struct step_f {
    double *x, *p, *v;
    int8_t *act;
    double a, alpha;
    int nx;
    VS_HD void operator()(int i, int j, double *s, double *) const {
        long n = i + (long)nx * j;
        double pt, xv = 0.0;
        if (act[n] != 0) {
            pt = a * p[n] + alpha * v[n];
            if (vs::hard_wall{}.below(pt)) {
                xv = -pt;
                s[1] += 1.0;
                pt = vs::hard_wall{}.project(pt);
                act[n] = 0;
                v[n] = 0.0;
            }
        } else {
            pt = 0.0;
        }
        x[n] = xv;
        p[n] = pt;
        s[0] += pt;
    }
};

struct bccg_spectral_f {
    double2 *pk, *k;
    vs::metric_v ks;
    const double2 *hk;
    double a, alpha, b;
    int mode;
    VS_HD void operator()(long n) const {
        if (mode == 2) {   // k = pk (a ks) - hk
            k[n] = vs::csub(vs::cscale(a * ks[n], pk[n]), hk[n]);
            return;
        }
        double2 p = vs::cadd(vs::cscale(a, pk[n]), vs::cscale(alpha, k[n]));
        pk[n] = p;
        if (mode == 1) k[n] = vs::csub(vs::cscale(b * ks[n], p), hk[n]);
    }
};

struct add_points_f {
    double2 *pk;
    const double2 *ex, *ey;
    int na, nb, m;
    VS_HD void operator()(long n) const {
        int a = (int)(n % na), b = (int)(n / na);
        double2 s = vs::cx(0.0, 0.0);
        for (int k = 0; k < m; ++k) s = vs::cadd(s, vs::cmul(ex[a + (long)na * k], ey[b + (long)nb * k]));
        pk[n] = vs::cadd(pk[n], s);
    }
};

// the factors of a few points' transforms: ex(i, k) = c_k exp(-i 2 pi (i (ic_k - 1) mod nx)/nx)
// over the na half-spectrum columns, then ey(j, k) = exp(-i 2 pi (j (jc_k - 1) mod ny)/ny) over
// the ny rows (i, j from 0), each (cos, sin) of the angle the host twin forms, in its order
constexpr int max_points = 8;
struct point_factors_f {
    double2 *ex, *ey;
    int na, nx, ny, m;
    int ic[max_points], jc[max_points];
    double c[max_points];
    VS_HD void operator()(long n) const {
        const double two_pi = 6.283185307179586476925286766559;
        long nex = (long)na * m;
        double s, co;
        if (n < nex) {
            int i = (int)(n % na), k = (int)(n / na);
            double theta = -(two_pi * (double)(((long)i * ic[k]) % nx) / nx);
            sincos(theta, &s, &co);
            ex[n] = vs::cx(c[k] * co, c[k] * s);
        } else {
            long e = n - nex;
            int j = (int)(e % ny), k = (int)(e / ny);
            double theta = -(two_pi * (double)(((long)j * jc[k]) % ny) / ny);
            sincos(theta, &s, &co);
            ey[e] = vs::cx(co, s);
        }
    }
};

}  // namespace

extern "C" {

// The metric M/N is not held on the device: each pass that reads it forms it from K_d (kd, f,
// modulus: vs::metric_v); this pass writes its values into ks (a test's, or a caller's copy)
void veslide_bccg_metric(long n, double *ks, const double2 *kd, double f, int modulus) {
    vs::for_each(metric_f{ks, vs::metric_v{kd, f, modulus}}, n);
}

void veslide_bccg_set_contact(long n, int8_t *act, const double *p) { vs::for_each(set_contact_f{act, p}, n); }

void veslide_bccg_statistics(int nx, int ny, const double *x, const int8_t *act, const double *p, double gprev,
                             double *rows) {
    vs::reduce_rows<4, 1>(statistics_f{x, p, act, gprev, nx}, nx, ny, rows);
}

void veslide_bccg_residual(int nx, int ny, double *x, int8_t *act, const double *v, double gbar, double *rows) {
    vs::reduce_rows<4, 0>(residual_f{x, act, v, gbar, nx}, nx, ny, rows);
}

void veslide_bccg_set_sum(int nx, int ny, const double *x, const int8_t *act, double *rows) {
    vs::reduce_rows<1, 0>(set_sum_f{x, act, nx}, nx, ny, rows);
}

void veslide_bccg_precondition(int na, int nb, double2 *k, const double2 *kd, double f, int modulus,
                               const double *wa, double n2, double *cols) {
    vs::reduce_rows<1, 0>(precondition_f{k, vs::metric_v{kd, f, modulus}, wa, n2, na}, na, nb, cols);
}

void veslide_bccg_direction(long n, double *x, const int8_t *act, double *v, double beta, double shift) {
    vs::for_each(direction_f{x, v, act, beta, shift}, n);
}

void veslide_bccg_energy(int na, int nb, const double2 *k, const double2 *kd, double f, int modulus,
                         const double *wa, double *cols) {
    vs::reduce_rows<1, 0>(energy_f{k, vs::metric_v{kd, f, modulus}, wa, na}, na, nb, cols);
}

void veslide_bccg_step(int nx, int ny, double *x, int8_t *act, double *p, double *v, double a, double alpha,
                       double *rows) {
    vs::reduce_rows<2, 0>(step_f{x, p, v, act, a, alpha, nx}, nx, ny, rows);
}

void veslide_bccg_spectral(long n, double2 *pk, double2 *k, const double2 *kd, double f, int modulus,
                           const double2 *hk, double a, double alpha, double b, int mode) {
    vs::for_each(bccg_spectral_f{pk, k, vs::metric_v{kd, f, modulus}, hk, a, alpha, b, mode}, n);
}

// pk += the transforms of m points pts (i, j, value; i and j from 1) of a grid of nx x nb cells
// on one process (storage (a, b) is half-spectrum entry (a, b)): their factors formed into exy
// ((na + nb) x max_points: ex, then ey), then applied (veslide_bccg_passes.F90's add_points)
void veslide_bccg_point_transforms(int na, int nb, int nx, int m, const double *pts, double2 *pk, double2 *exy) {
    if (m > max_points) {
        vs::note_error("bccg point transforms", "more points than the pass takes");
        return;
    }
    if (m <= 0) return;
    point_factors_f f{exy, exy + (long)na * m, na, nx, nb, m, {}, {}, {}};
    for (int k = 0; k < m; ++k) {
        f.ic[k] = (int)lround(pts[3 * k]) - 1;
        f.jc[k] = (int)lround(pts[3 * k + 1]) - 1;
        f.c[k] = pts[3 * k + 2];
    }
    vs::for_each(f, (long)(na + nb) * m);
    vs::for_each(add_points_f{pk, exy, exy + (long)na * m, na, nb, m}, (long)na * nb);
}

}  // extern "C"
