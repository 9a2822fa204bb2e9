// CUDA twins of veslide_anderson_passes.F90 (Anderson mixing's two passes). The products with the
// history are summed in registers, so the memory mk is a template parameter (0..8); the contact
// law the Douglas-Rachford reflection goes through is another (vs::with_law, once per call).
#include "../core/veslide_device.cuh"
#include "veslide_contact_law.cuh"

namespace {

constexpr int max_memory = 8;

// sums: [|f|^2, dF_k.dF_slot (k < MK), dF_k.f (k < MK)]; minima: [-|x| where y is out of contact,
// -|f| where it is in contact]
template <int MK, class Law>
struct columns_f {
    Law law;
    const double *src, *z, *zprev, *fprev;
    float *df, *gm;
    long history;   // leading dimension of df and gm
    int slot;       // 1-based, as in Fortran
    int nx, reflect;
    VS_HD void operator()(int i, int j, double *s, double *m) const {
        long n = i + (long)nx * j;
        double zv = z[n], fv;
        if (reflect) {
            double xv = src[n];
            double yv = law.project(2.0 * xv - zv);
            fv = yv - xv;
            if (law.in_contact(yv))
                m[1] = fmin(m[1], -fabs(fv));
            else
                m[0] = fmin(m[0], -fabs(xv));
        } else {
            fv = src[n];
        }
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

template <int MK, class Law>
void columns(Law law, int nx, int ny, const double *src, const double *z, float *df, float *gm, const double *zprev,
             const double *fprev, int slot, long history, int reflect, double *rows) {
    vs::reduce_rows<1 + 2 * MK, 2>(columns_f<MK, Law>{law, src, z, zprev, fprev, df, gm, history, slot, nx, reflect},
                                   nx, ny, rows);
}

template <class Law>
struct update_f {
    Law law;
    double *src, *z, *zprev, *fprev;
    const float *gm;
    long n_all;
    double coef[max_memory];
    int mk, reflect;
    VS_HD void operator()(long n) const {
        double zv = z[n], fv;
        if (reflect) {
            double xv = src[n];
            fv = law.project(2.0 * xv - zv) - xv;
        } else {
            fv = src[n];
        }
        double zn = zv + fv;
        for (int k = 0; k < mk; ++k) zn = zn - (double)gm[n + n_all * k] * coef[k];
        zprev[n] = zv;
        fprev[n] = fv;
        z[n] = zn;
        if (reflect) src[n] = zn;
    }
};

}  // namespace

extern "C" {

void veslide_anderson_columns(int law, const double *param, int nx, int ny, const double *src, const double *z,
                              float *df, float *gm, const double *zprev, const double *fprev, int slot, int mk,
                              int history, int reflect, double *rows) {
    long h = history;
    vs::with_law(law, param, "Anderson columns", [&](auto l) {
        switch (mk) {
        case 0: columns<0>(l, nx, ny, src, z, df, gm, zprev, fprev, slot, h, reflect, rows); break;
        case 1: columns<1>(l, nx, ny, src, z, df, gm, zprev, fprev, slot, h, reflect, rows); break;
        case 2: columns<2>(l, nx, ny, src, z, df, gm, zprev, fprev, slot, h, reflect, rows); break;
        case 3: columns<3>(l, nx, ny, src, z, df, gm, zprev, fprev, slot, h, reflect, rows); break;
        case 4: columns<4>(l, nx, ny, src, z, df, gm, zprev, fprev, slot, h, reflect, rows); break;
        case 5: columns<5>(l, nx, ny, src, z, df, gm, zprev, fprev, slot, h, reflect, rows); break;
        case 6: columns<6>(l, nx, ny, src, z, df, gm, zprev, fprev, slot, h, reflect, rows); break;
        case 7: columns<7>(l, nx, ny, src, z, df, gm, zprev, fprev, slot, h, reflect, rows); break;
        case 8: columns<8>(l, nx, ny, src, z, df, gm, zprev, fprev, slot, h, reflect, rows); break;
        default: vs::note_error("Anderson columns", "memory above 8 on the device");
        }
    });
}

void veslide_anderson_update(int law, const double *param, long n, double *src, double *z, const float *gm,
                             double *zprev, double *fprev, const double *coef, int mk, int reflect) {
    vs::with_law(law, param, "Anderson update", [&](auto l) {
        update_f<decltype(l)> f{l, src, z, zprev, fprev, gm, n, {0}, mk, reflect};
        for (int k = 0; k < mk && k < max_memory; ++k) f.coef[k] = coef[k];
        vs::for_each(f, n);
    });
}

}  // extern "C"
