// CUDA twins of veslide_contact_passes.F90 (the contact problem's residual, and the law's
// projection of a field); each functor takes the contact law as its template argument, chosen
// once per call by vs::with_law (veslide_contact_law.cuh)
#include "../core/veslide_device.cuh"
#include "veslide_contact_law.cuh"

namespace {

// g = u - (h - h_mean); sums: [g over the contact set, its size]; minima: [-g]
template <class Law>
struct gap_sums_f {
    Law law;
    const double *u, *h, *p;
    double *g;
    double h_mean;
    int nx;
    VS_HD void operator()(int i, int j, double *s, double *m) const {
        long n = i + (long)nx * j;
        double gv = u[n] - (h[n] - h_mean);
        g[n] = gv;
        if (law.in_contact(p[n])) {
            s[1] += 1.0;
            s[0] += gv;
        }
        m[0] = fmin(m[0], -gv);
    }
};

// g = g + d; sums and minima: the law's residual sums (the hard wall: [p g, |p|, p], [g, p])
template <class Law>
struct gap_measures_f {
    Law law;
    const double *p;
    double *g;
    double d;
    int nx;
    VS_HD void operator()(int i, int j, double *s, double *m) const {
        long n = i + (long)nx * j;
        double gv = g[n] + d;
        g[n] = gv;
        law.residual_sums(p[n], gv, s, m);
    }
};

// a = the law's proximal map of a; sums: [a]
template <class Law>
struct project_sum_f {
    Law law;
    double *a;
    int nx;
    VS_HD void operator()(int i, int j, double *s, double *) const {
        long n = i + (long)nx * j;
        double v = law.project(a[n]);
        a[n] = v;
        s[0] += v;
    }
};

// an adhesive law's candidate (veslide_contact_passes.F90's adhesive_measures): the fresh gap g,
// the repulsive pressure at the solver's gap gs; sums: [p]; minima: [g, -|g - gs|, p_rep,
// -min(|p_rep|/ps, max(g, 0)/hs)]; g kept (0 where gs <= 0, else max(g, 0))
template <class Law>
struct adhesive_measures_f {
    Law law;
    const double *u, *h, *p;
    double *g;
    double h_mean, approach, ps, hs;
    int nx;
    VS_HD void operator()(int i, int j, double *s, double *m) const {
        long n = i + (long)nx * j;
        double gf = u[n] - (h[n] - h_mean) + approach;
        double gs = g[n];
        double prep = p[n] + law.attraction(gs);
        if (Law::dugdale && gs == law.rho) prep = p[n] + fmin(fmax(-p[n], 0.0), law.s0);
        s[0] += p[n];
        m[0] = fmin(m[0], gf);
        m[1] = fmin(m[1], -fabs(gf - gs));
        m[2] = fmin(m[2], prep);
        m[3] = fmin(m[3], -fmin(fabs(prep) / ps, fmax(gf, 0.0) / hs));
        g[n] = gs <= 0.0 ? 0.0 : fmax(gf, 0.0);
    }
};

}  // namespace

extern "C" {

// (param: the law's [w, rho, sigma0], SI)
void veslide_contact_adhesive_measures(int law, const double *param, int nx, int ny, const double *u, const double *h,
                                       double h_mean, const double *p, double *g, double approach, double p_scale,
                                       double hs, double *rows) {
    vs::with_adhesive_law(law, param[2], param[1], "contact adhesive_measures", [&](auto l) {
        vs::reduce_rows<1, 4>(adhesive_measures_f<decltype(l)>{l, u, h, p, g, h_mean, approach, p_scale, hs, nx}, nx,
                              ny, rows);
    });
}

void veslide_contact_gap_and_contact_sums(int law, const double *param, int nx, int ny, const double *u,
                                          const double *h, double h_mean, const double *p, double *g, double *rows) {
    vs::with_law(law, param, "contact gap_and_contact_sums", [&](auto l) {
        vs::reduce_rows<2, 1>(gap_sums_f<decltype(l)>{l, u, h, p, g, h_mean, nx}, nx, ny, rows);
    });
}

void veslide_contact_gap_measures(int law, const double *param, int nx, int ny, const double *p, double *g, double d,
                                  double *rows) {
    vs::with_law(law, param, "contact gap_measures", [&](auto l) {
        vs::reduce_rows<3, 2>(gap_measures_f<decltype(l)>{l, p, g, d, nx}, nx, ny, rows);
    });
}

void veslide_contact_project_and_sum(int law, const double *param, int nx, int ny, double *a, double *rows) {
    vs::with_law(law, param, "contact project_and_sum", [&](auto l) {
        vs::reduce_rows<1, 0>(project_sum_f<decltype(l)>{l, a, nx}, nx, ny, rows);
    });
}

}  // extern "C"
