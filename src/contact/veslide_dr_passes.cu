// CUDA twins of veslide_dr_passes.F90 (the splitting's passes besides its map and mixing, which
// are Anderson's: veslide_anderson_passes.cu). The passes through the contact law's proximal map
// take the law as their functor's template argument, chosen once per call (vs::with_law).
#include "../core/veslide_device.cuh"
#include "veslide_contact_law.cuh"

namespace {

// y = prox(2x - z), the law's proximal map; mode 0: rebalance, 1: project
template <class Law>
struct reflect_f {
    Law law;
    double *x, *z, *p;
    double s;
    int mode;
    VS_HD void operator()(long n) const {
        if (mode == 0) {   // rebalance
            double yv = law.project(2.0 * x[n] - z[n]);
            double zn = yv + s * (z[n] - yv);
            z[n] = zn;
            x[n] = zn;
        } else {   // project
            p[n] = s * law.project(2.0 * x[n] - z[n]);
        }
    }
};

struct elementwise_f {
    double *x, *z;
    const double *a, *b;
    double s, t;
    int mode;
    VS_HD void operator()(long n) const {
        switch (mode) {
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

// v = 2x - z; sums: [prox(v - c) over the cells it puts in contact, their count]; minima: [-v]
template <class Law>
struct load_sums_f {
    Law law;
    const double *x, *z;
    double c;
    int nx;
    VS_HD void operator()(int i, int j, double *s, double *m) const {
        long n = i + (long)nx * j;
        double v = 2.0 * x[n] - z[n];
        if (law.in_contact_shifted(v, c)) {
            s[0] += law.project(v - c);
            s[1] += 1.0;
        }
        m[0] = fmin(m[0], -v);
    }
};

}  // namespace

extern "C" {

void veslide_dr_reflect(int law, const double *param, long n, int mode, double *x, double *z, double *p, double s) {
    vs::with_law(law, param, "dr reflect", [&](auto l) {
        vs::for_each(reflect_f<decltype(l)>{l, x, z, p, s, mode}, n);
    });
}

void veslide_dr_elementwise(long n, int mode, double *x, double *z, double *p, const double *a, const double *b,
                            double s, double t) {
    (void)p;
    vs::for_each(elementwise_f{x, z, a, b, s, t, mode}, n);
}

void veslide_dr_load_sums(int law, const double *param, int nx, int ny, const double *x, const double *z, double c,
                          double *rows) {
    vs::with_law(law, param, "dr load_sums", [&](auto l) {
        vs::reduce_rows<2, 1>(load_sums_f<decltype(l)>{l, x, z, c, nx}, nx, ny, rows);
    });
}

}  // extern "C"
