// CUDA twins of veslide_kernel_passes.F90 (the kernel's resolvent)
#include "../core/veslide_device.cuh"

namespace {

struct multiplier_f {
    double2 *mult;
    const double2 *kd;
    double gamma, s, cells;
    VS_HD void operator()(long n) const {
        double2 t = vs::cscale(gamma, vs::cscale(s, kd[n]));
        t = vs::cx(1.0 + t.x, t.y);
        mult[n] = vs::cdiv(vs::cx(1.0, 0.0), vs::cscale(cells, t));
    }
};

struct apply_f {
    double2 *k;
    const double2 *mult, *rk;
    double gamma, mean_x;
    int owns_mean;
    VS_HD void operator()(long n) const {
        if (n == 0 && owns_mean) {
            k[0] = vs::cx(mean_x, 0.0);
            return;
        }
        k[n] = vs::cmul(mult[n], vs::cadd(k[n], vs::cscale(gamma, rk[n])));
    }
};

}  // namespace

extern "C" {

void veslide_kernel_resolvent_multiplier(long n, double2 *mult, const double2 *kd, double gamma, double s,
                                         double cells) {
    vs::for_each(multiplier_f{mult, kd, gamma, s, cells}, n);
}

void veslide_kernel_resolvent_apply(long n, double2 *k, const double2 *mult, const double2 *rk, double gamma,
                                    int owns_mean, double mean_x) {
    vs::for_each(apply_f{k, mult, rk, gamma, mean_x, owns_mean}, n);
}

}  // extern "C"
