// CUDA twins of the shared passes of veslide_passes.F90 (same arguments; arrays in device memory,
// Fortran order: element (i, j) of an n1 x n2 array at i + n1 j).
#include "../core/veslide_device.cuh"

namespace {

struct fill_f {
    double *a;
    double v;
    VS_HD void operator()(long n) const { a[n] = v; }
};

struct scale_f {
    double *a;
    double s;
    int mode;
    VS_HD void operator()(long n) const {
        if (mode == 0)
            a[n] = s * a[n];
        else if (mode == 1)
            a[n] = a[n] / s;
        else
            a[n] = a[n] - s;
    }
};

struct copy_f {
    double *dst;
    const double *src;
    double c, s;
    int mode;
    VS_HD void operator()(long n) const {
        switch (mode) {
        case 0: dst[n] = s * src[n]; break;
        case 1: dst[n] = src[n] / s; break;
        case 2: dst[n] = (src[n] - c) * s; break;
        default: dst[n] = (src[n] - c) / s;
        }
    }
};

struct row_sum_f {
    const double *a;
    int nx;
    VS_HD void operator()(int i, int j, double *s, double *) const { s[0] += a[i + (long)nx * j]; }
};

struct count_below_f {
    const double *a;
    int nx;
    double v;
    VS_HD void operator()(int i, int j, double *s, double *) const {
        if (a[i + (long)nx * j] < v) s[0] += 1.0;
    }
};

struct complex_f {
    double2 *c;
    const double2 *d;
    double s;
    int mode;
    VS_HD void operator()(long n) const {
        if (mode == 0)
            c[n] = vs::cscale(s, c[n]);
        else if (mode == 1)
            c[n] = vs::cdivr(c[n], s);
        else
            c[n] = vs::cadd(c[n], d[n]);
    }
};

struct multiply_f {
    double2 *k;
    const double2 *m;
    double c;
    VS_HD void operator()(long n) const { k[n] = vs::cmul(k[n], vs::cscale(c, m[n])); }
};

}  // namespace

extern "C" {

void veslide_pass_fill(long n, double *a, double v) { vs::for_each(fill_f{a, v}, n); }

void veslide_pass_scale(long n, double *a, double s, int mode) { vs::for_each(scale_f{a, s, mode}, n); }

void veslide_pass_copy(long n, double *dst, const double *src, double c, double s, int mode) {
    vs::for_each(copy_f{dst, src, c, s, mode}, n);
}

void veslide_pass_row_sums(int nx, int ny, const double *a, double *rows) {
    vs::reduce_rows<1, 0>(row_sum_f{a, nx}, nx, ny, rows);
}

void veslide_pass_count_below(int nx, int ny, const double *a, double v, double *rows) {
    vs::reduce_rows<1, 0>(count_below_f{a, nx, v}, nx, ny, rows);
}

void veslide_pass_complex(long n, double2 *c, const double2 *d, double s, int mode) {
    vs::for_each(complex_f{c, d, s, mode}, n);
}

void veslide_pass_multiply(long n, double2 *k, const double2 *m, double c) { vs::for_each(multiply_f{k, m, c}, n); }

}  // extern "C"
