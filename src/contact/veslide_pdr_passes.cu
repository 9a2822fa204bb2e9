// CUDA twins of veslide_pdr_passes.F90 (the preconditioned splitting's passes); each functor does
// for one element what the CPU twin does, in the same order of operations.
#include "../core/veslide_device.cuh"
#include "veslide_contact_law.cuh"

namespace {

// the spectral passes, one kernel: mode 0 step_constant, 1 resolvent, 2 scaled_product,
// 3 full_contact, 4 gap_to_z
struct pdr_spectral_f {
    double2 *k, *hk, *cm;
    vs::metric_v ks;
    const double2 *kd, *pk;
    double gamma, gs, c;
    int mode;
    VS_HD void operator()(long n) const {
        switch (mode) {
        case 0:   // cm = gamma k/(ks + gs kd)/(c c)
            if (ks[n] > 0.0) {
                double2 den = vs::cx(ks[n] + kd[n].x * gs, kd[n].y * gs);
                cm[n] = vs::cdivr(vs::cdiv(vs::cscale(gamma, k[n]), den), c * c);
            } else {
                cm[n] = vs::cx(0.0, 0.0);
            }
            break;
        case 1: {   // hk = k; k = ks k/((ks + gs kd) c) + cm (or k/c); hk = ks (2 c k - hk)
            double2 z = k[n], x;
            double m = ks[n];
            if (m > 0.0) {
                double2 den = vs::cscale(c, vs::cx(m + kd[n].x * gs, kd[n].y * gs));
                x = vs::cadd(vs::cdiv(vs::cscale(m, z), den), cm[n]);
            } else {
                x = vs::cdivr(z, c);
            }
            k[n] = x;
            hk[n] = vs::cscale(m, vs::csub(vs::cscale(2.0 * c, x), z));
            break;
        }
        case 2:   // k = (c kd) pk
            k[n] = vs::cmul(vs::cscale(c, kd[n]), pk[n]);
            break;
        case 3:   // k = k/(c kd) where ks > 0
            k[n] = ks[n] > 0.0 ? vs::cdiv(k[n], vs::cscale(c, kd[n])) : vs::cx(0.0, 0.0);
            break;
        default:   // k = k (gamma/(ks c c)) where ks > 0
            k[n] = ks[n] > 0.0 ? vs::cscale(gamma / (ks[n] * c * c), k[n]) : vs::cx(0.0, 0.0);
        }
    }
};

// sums: [x - (h - h_mean)/hs over the contact set (the hard wall's: pdr takes that law only), count]
struct residual_sums_f {
    const double *x, *h, *p;
    double h_mean, hs;
    int nx;
    VS_HD void operator()(int i, int j, double *s, double *) const {
        long n = i + (long)nx * j;
        if (vs::hard_wall{}.in_contact(p[n])) {
            s[1] += 1.0;
            s[0] += x[n] - (h[n] - h_mean) / hs;
        }
    }
};

// sums: [p g, p]; minima: [g]
struct residual_gap_f {
    const double *x, *h, *p;
    double h_mean, hs, d;
    int nx;
    VS_HD void operator()(int i, int j, double *s, double *m) const {
        long n = i + (long)nx * j;
        double g = x[n] - (h[n] - h_mean) / hs + d;
        m[0] = fmin(m[0], g);
        s[0] += p[n] * g;
        s[1] += p[n];
    }
};

struct relax_f {
    double *z;
    const double *y, *x;
    double lambda;
    VS_HD void operator()(long n) const { z[n] = z[n] + lambda * (y[n] - x[n]); }
};

struct add_scaled_f {
    double *a;
    const double *b;
    double s;
    VS_HD void operator()(long n) const { a[n] = a[n] + s * b[n]; }
};

struct combine_f {
    double *a;
    const double *b, *c;
    int mode;
    VS_HD void operator()(long n) const {
        if (mode == 0)
            a[n] = b[n] + c[n];
        else if (mode == 1)
            a[n] = 1.0 + b[n];
        else
            a[n] = b[n] - a[n];
    }
};

}  // namespace

extern "C" {

void veslide_pdr_spectral(long n, int mode, double2 *k, double2 *hk, double2 *cm, const double2 *ks_kd, double ks_f,
                          int ks_modulus, const double2 *kd, const double2 *pk, double gamma, double gs, double c) {
    vs::for_each(pdr_spectral_f{k, hk, cm, vs::metric_v{ks_kd, ks_f, ks_modulus}, kd, pk, gamma, gs, c, mode}, n);
}

void veslide_pdr_residual_sums(int nx, int ny, const double *x, const double *h, double h_mean, double hs,
                               const double *p, double *rows) {
    vs::reduce_rows<2, 0>(residual_sums_f{x, h, p, h_mean, hs, nx}, nx, ny, rows);
}

void veslide_pdr_residual_gap(int nx, int ny, const double *x, const double *h, double h_mean, double hs, double d,
                              const double *p, double *rows) {
    vs::reduce_rows<2, 1>(residual_gap_f{x, h, p, h_mean, hs, d, nx}, nx, ny, rows);
}

void veslide_pdr_relax(long n, double *z, const double *y, const double *x, double lambda) {
    vs::for_each(relax_f{z, y, x, lambda}, n);
}

void veslide_pdr_add_scaled(long n, double *a, const double *b, double s) { vs::for_each(add_scaled_f{a, b, s}, n); }

void veslide_pdr_combine(long n, double *a, const double *b, const double *c, int mode) {
    vs::for_each(combine_f{a, b, c, mode}, n);
}

}  // extern "C"
