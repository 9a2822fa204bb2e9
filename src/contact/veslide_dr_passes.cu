// CUDA twins of veslide_dr_passes.F90 (the splitting with Anderson mixing). The map's products
// with the history are summed in registers, so the memory mk is a template parameter (0..8).
#include "../core/veslide_device.cuh"

namespace {

constexpr int max_memory = 8;

// sums: [|f|^2, dF_k.dF_slot (k < MK), dF_k.f (k < MK)]; minima: [-|x| where y = 0, -|f| where y > 0]
template <int MK>
struct map_f {
    const double *x, *z, *zprev, *fprev;
    float *df, *gm;
    long history;   // leading dimension of df and gm
    int slot;       // 1-based, as in Fortran
    int nx;
    VS_HD void operator()(int i, int j, double *s, double *m) const {
        long n = i + (long)nx * j;
        double xv = x[n], zv = z[n];
        double yv = fmax(2.0 * xv - zv, 0.0);
        double fv = yv - xv;
        if (yv > 0.0)
            m[1] = fmin(m[1], -fabs(fv));
        else
            m[0] = fmin(m[0], -fabs(xv));
        s[0] += fv * fv;
        if (MK > 0) {
            long c = n + history * (slot - 1);
            df[c] = (float)(fv - fprev[n]);
            gm[c] = (float)((zv - zprev[n]) + (fv - fprev[n]));
            double dfv = (double)df[c];
            for (int k = 0; k < MK; ++k) {
                double dk = (double)df[n + history * k];
                s[1 + k] += dk * dfv;
                s[1 + MK + k] += dk * fv;
            }
        }
    }
};

template <int MK>
void map(int nx, int ny, const double *x, const double *z, float *df, float *gm, const double *zprev,
         const double *fprev, int slot, long history, double *rows) {
    vs::reduce_rows<1 + 2 * MK, 2>(map_f<MK>{x, z, zprev, fprev, df, gm, history, slot, nx}, nx, ny, rows);
}

struct update_f {
    double *x, *z, *zprev, *fprev;
    const float *gm;
    long n_all;
    double coef[max_memory];
    int mk;
    VS_HD void operator()(long n) const {
        double xv = x[n], zv = z[n];
        double fv = fmax(2.0 * xv - zv, 0.0) - xv;
        double zn = zv + fv;
        for (int k = 0; k < mk; ++k) zn = zn - (double)gm[n + n_all * k] * coef[k];
        zprev[n] = zv;
        fprev[n] = fv;
        z[n] = zn;
        x[n] = zn;
    }
};

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

void veslide_dr_map(int nx, int ny, const double *x, const double *z, float *df, float *gm, const double *zprev,
                    const double *fprev, int slot, int mk, int history, double *rows) {
    long h = history;
    switch (mk) {
    case 0: map<0>(nx, ny, x, z, df, gm, zprev, fprev, slot, h, rows); break;
    case 1: map<1>(nx, ny, x, z, df, gm, zprev, fprev, slot, h, rows); break;
    case 2: map<2>(nx, ny, x, z, df, gm, zprev, fprev, slot, h, rows); break;
    case 3: map<3>(nx, ny, x, z, df, gm, zprev, fprev, slot, h, rows); break;
    case 4: map<4>(nx, ny, x, z, df, gm, zprev, fprev, slot, h, rows); break;
    case 5: map<5>(nx, ny, x, z, df, gm, zprev, fprev, slot, h, rows); break;
    case 6: map<6>(nx, ny, x, z, df, gm, zprev, fprev, slot, h, rows); break;
    case 7: map<7>(nx, ny, x, z, df, gm, zprev, fprev, slot, h, rows); break;
    case 8: map<8>(nx, ny, x, z, df, gm, zprev, fprev, slot, h, rows); break;
    default: vs::note_error("dr map", "Anderson memory above 8 on the device");
    }
}

void veslide_dr_update(long n, double *x, double *z, const float *gm, double *zprev, double *fprev,
                       const double *coef, int mk) {
    update_f f{x, z, zprev, fprev, gm, n, {0}, mk};
    for (int k = 0; k < mk && k < max_memory; ++k) f.coef[k] = coef[k];
    vs::for_each(f, n);
}

void veslide_dr_elementwise(long n, int mode, double *x, double *z, double *p, const double *a, const double *b,
                            double s, double t) {
    vs::for_each(elementwise_f{x, z, p, a, b, s, t, mode}, n);
}

}  // extern "C"
