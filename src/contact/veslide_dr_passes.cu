// CUDA twins of veslide_dr_passes.F90 (the splitting's passes besides its map and mixing, which
// are Anderson's: veslide_anderson_passes.cu)
#include "../core/veslide_device.cuh"

namespace {

struct elementwise_f {
    double *x, *z, *p;
    const double *a, *b;
    double s, t;
    int mode;
    VS_HD void operator()(long n) const {
        switch (mode) {
        case 0: {   // rebalance
            double yv = fmax(2.0 * x[n] - z[n], 0.0);
            double zn = yv + s * (z[n] - yv);
            z[n] = zn;
            x[n] = zn;
            break;
        }
        case 1:   // project
            p[n] = s * fmax(2.0 * x[n] - z[n], 0.0);
            break;
        case 2: {   // restore
            double zn = a[n] + b[n];
            z[n] = zn;
            x[n] = zn;
            break;
        }
        case 3:   // add_gap: z = z + s x / t
            z[n] = z[n] + s * x[n] / t;
            break;
        default:   // shift: z = z + s
            z[n] = z[n] + s;
        }
    }
};

// v = 2x - z; sums: [max(v - c, 0), count v > c]; minima: [-v]
struct load_sums_f {
    const double *x, *z;
    double c;
    int nx;
    VS_HD void operator()(int i, int j, double *s, double *m) const {
        long n = i + (long)nx * j;
        double v = 2.0 * x[n] - z[n];
        if (v > c) {
            s[0] += v - c;
            s[1] += 1.0;
        }
        m[0] = fmin(m[0], -v);
    }
};

}  // namespace

extern "C" {

void veslide_dr_elementwise(long n, int mode, double *x, double *z, double *p, const double *a, const double *b,
                            double s, double t) {
    vs::for_each(elementwise_f{x, z, p, a, b, s, t, mode}, n);
}

void veslide_dr_load_sums(int nx, int ny, const double *x, const double *z, double c, double *rows) {
    vs::reduce_rows<2, 1>(load_sums_f{x, z, c, nx}, nx, ny, rows);
}

}  // extern "C"
