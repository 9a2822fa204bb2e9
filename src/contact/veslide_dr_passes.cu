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
        default:   // add_gap: z = z + s x / t
            z[n] = z[n] + s * x[n] / t;
        }
    }
};

}  // namespace

extern "C" {

void veslide_dr_elementwise(long n, int mode, double *x, double *z, double *p, const double *a, const double *b,
                            double s, double t) {
    vs::for_each(elementwise_f{x, z, p, a, b, s, t, mode}, n);
}

}  // extern "C"
