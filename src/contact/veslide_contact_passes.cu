// CUDA twins of veslide_contact_passes.F90 (the contact problem's residual)
#include "../core/veslide_device.cuh"

namespace {

// g = u - (h - h_mean); sums: [g over p > 0, count p > 0]; minima: [-g]
struct gap_sums_f {
    const double *u, *h, *p;
    double *g;
    double h_mean;
    int nx;
    VS_HD void operator()(int i, int j, double *s, double *m) const {
        long n = i + (long)nx * j;
        double gv = u[n] - (h[n] - h_mean);
        g[n] = gv;
        if (p[n] > 0.0) {
            s[1] += 1.0;
            s[0] += gv;
        }
        m[0] = fmin(m[0], -gv);
    }
};

// g = g + d; sums: [p g, |p|, p]; minima: [g, p]
struct gap_measures_f {
    const double *p;
    double *g;
    double d;
    int nx;
    VS_HD void operator()(int i, int j, double *s, double *m) const {
        long n = i + (long)nx * j;
        double gv = g[n] + d, pv = p[n];
        g[n] = gv;
        s[0] += pv * gv;
        s[1] += fabs(pv);
        s[2] += pv;
        m[0] = fmin(m[0], gv);
        m[1] = fmin(m[1], pv);
    }
};

}  // namespace

extern "C" {

void veslide_contact_gap_and_contact_sums(int nx, int ny, const double *u, const double *h, double h_mean,
                                          const double *p, double *g, double *rows) {
    vs::reduce_rows<2, 1>(gap_sums_f{u, h, p, g, h_mean, nx}, nx, ny, rows);
}

void veslide_contact_gap_measures(int nx, int ny, const double *p, double *g, double d, double *rows) {
    vs::reduce_rows<3, 2>(gap_measures_f{p, g, d, nx}, nx, ny, rows);
}

}  // extern "C"
