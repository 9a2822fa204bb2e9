// veslide's device layer, shared by every .cu file: the launch helpers of the solvers' passes,
// written once for two builds of the same sources:
//  - nvcc (the GPU build, gpu/build.sh): CUDA kernels on the GPU;
//  - a host C++ compiler with -DVESLIDE_EMULATE (gpu/build.sh --emulate): the same passes run
//    on the host, thread block by thread block, in the order the GPU sums in. This "emulated
//    device" lets every pass and the whole device path of the solvers be tested where no GPU is
//    (CI, a laptop); its results are the GPU's up to the FFT (FFTW there, cuFFT here).
//
// Two kinds of pass:
//  - for_each(f, n): f(idx) for idx = 0..n-1, each element on its own (no order);
//  - reduce_rows<NS, NM>(f, nx, ny, rows): f(i, j, s, m) over a field of nx x ny (i fastest)
//    accumulates NS sums s[] and NM minima m[]; row j is summed by one thread block of `block`
//    threads, thread t taking i = t, t + block, ... and the threads' values combined by a fixed
//    tree (warp shuffles, then the warps' results), so the partials are the same bits on every
//    run; the NS + NM row partials come back to the host, row-major per row: rows[j*(NS+NM)+k].
// The host adds the row partials in order (veslide_collective), as the CPU passes do, so a case
// repeats bitwise on one device. Device arithmetic is compiled without contracting a*b + c into
// fused multiply-adds (--fmad=false), so element-wise passes round as their CPU twins do.
#pragma once
#include <stddef.h>
#include <math.h>
#include <typeinfo>

#ifdef VESLIDE_EMULATE
#define VS_HD
struct double2 {
    double x, y;
};
#else
#include <cuda_runtime.h>
#define VS_HD __host__ __device__
#endif

namespace vs {

constexpr int block = 256;     // threads per block of every pass
constexpr int warps = block / 32;

// ---- errors: the first failure of any device call is kept (sticky) until read --------------
void note_error(const char *what, const char *detail);
bool failed();
#ifndef VESLIDE_EMULATE
bool check(cudaError_t e, const char *what);   // true when e is cudaSuccess; notes it otherwise
#endif

// ---- memory (counted: veslide_device_peak_bytes) -------------------------------------------
void *alloc(size_t bytes);              // NULL (and the error noted) when it fails
void release(void *p);

// ---- transfers between the host and the device (veslide_device.cu) --------------------------
void host_copy(void *dest, const void *src, size_t bytes);   // all the host's threads
#ifndef VESLIDE_EMULATE
int transfer(void *dest, const void *src, size_t bytes, bool up);
#endif

// ---- per-row partials: a device buffer, and pinned host memory they are copied through -----
double *row_buffer(size_t n);           // device, at least n doubles (kept, grown when needed)
double *host_buffer(size_t n);          // host staging (pinned on a GPU), at least n doubles
int copy_rows(double *rows_h, const double *rows_d, size_t n);   // device -> caller's array

// ---- profiling: with VESLIDE_DEVICE_PROFILE=1 every launch is timed (the device synchronised
// around it) and its time added under the pass's name; veslide_device_profile prints the table
bool profiling();
double now();                                   // seconds, after the device has finished
void profile_add(const char *name, double seconds);
template <class F>
const char *pass_name() {
    return typeid(F).name();
}

// ---- complex arithmetic (double2 = Fortran's complex(dp), (re, im)) -------------------------
VS_HD inline double2 cx(double re, double im) {
    double2 z;
    z.x = re;
    z.y = im;
    return z;
}
VS_HD inline double2 cadd(double2 a, double2 b) { return cx(a.x + b.x, a.y + b.y); }
VS_HD inline double2 csub(double2 a, double2 b) { return cx(a.x - b.x, a.y - b.y); }
VS_HD inline double2 cmul(double2 a, double2 b) { return cx(a.x * b.x - a.y * b.y, a.x * b.y + a.y * b.x); }
VS_HD inline double2 cscale(double s, double2 a) { return cx(a.x * s, a.y * s); }   // complex * real
VS_HD inline double2 cdivr(double2 a, double s) { return cx(a.x / s, a.y / s); }    // complex / real
VS_HD inline double cabs2(double2 a) { return a.x * a.x + a.y * a.y; }
// a / b by Smith's algorithm (what gfortran does for complex division)
VS_HD inline double2 cdiv(double2 a, double2 b) {
    if (fabs(b.y) <= fabs(b.x)) {
        double r = b.y / b.x, d = b.x + b.y * r;
        return cx((a.x + a.y * r) / d, (a.y - a.x * r) / d);
    }
    double r = b.x / b.y, d = b.y + b.x * r;
    return cx((a.x * r + a.y) / d, (a.y * r - a.x) / d);
}

// ---- the contact solvers' metric M/N, formed where it is read --------------------------------
// f |K_d| (modulus) or f Re K_d from the kernel's multiplier, instead of an array of its own (4
// bytes per cell fewer on the device): the same operations as the array's pass, the same bits
struct metric_v {
    const double2 *kd;
    double f;
    int modulus;
    VS_HD double operator[](long n) const { return modulus ? f * hypot(kd[n].x, kd[n].y) : kd[n].x * f; }
};

// ---- for_each ------------------------------------------------------------------------------
#ifdef VESLIDE_EMULATE
template <class F>
int for_each(const F &f, long n) {
    double t0 = profiling() ? now() : 0.0;
#pragma omp parallel for schedule(static)
    for (long idx = 0; idx < n; ++idx) f(idx);
    if (profiling()) profile_add(pass_name<F>(), now() - t0);
    return 0;
}
#else
template <class F>
__global__ void __launch_bounds__(block) each_kernel(F f, long n) {
    for (long idx = blockIdx.x * (long)blockDim.x + threadIdx.x; idx < n; idx += (long)gridDim.x * blockDim.x)
        f(idx);
}
int grid_size(long n);   // blocks of a grid-stride launch over n elements
template <class F>
int for_each(const F &f, long n) {
    if (n <= 0 || failed()) return failed();
    double t0 = profiling() ? now() : 0.0;
    each_kernel<<<grid_size(n), block>>>(f, n);
    bool good = check(cudaGetLastError(), "for_each launch");
    if (profiling()) profile_add(pass_name<F>(), now() - t0);
    return good ? 0 : 1;
}
#endif

// ---- reduce_rows ---------------------------------------------------------------------------
template <int NS, int NM>
struct acc_t {
    double s[NS > 0 ? NS : 1];
    double m[NM > 0 ? NM : 1];
    VS_HD void init() {
        for (int k = 0; k < NS; ++k) s[k] = 0.0;
        for (int k = 0; k < NM; ++k) m[k] = HUGE_VAL;
    }
    VS_HD void add(const acc_t &o) {
        for (int k = 0; k < NS; ++k) s[k] += o.s[k];
        for (int k = 0; k < NM; ++k) m[k] = fmin(m[k], o.m[k]);
    }
};

#ifdef VESLIDE_EMULATE
// The block's tree, as the GPU forms it: within each warp, lane l takes lane l + o for
// o = 16, 8, 4, 2, 1 (all lanes read before any writes: ascending lanes read the old values);
// then lanes 0..warps-1 of the first warp take the warps' results and combine them alike.
template <int NS, int NM>
void tree(acc_t<NS, NM> *v, int n) {
    for (int o = n / 2; o > 0; o /= 2)
        for (int l = 0; l + o < n; ++l) v[l].add(v[l + o]);
}
template <int NS, int NM, class F>
int reduce_rows(const F &f, int nx, int ny, double *rows_h) {
    constexpr int K = NS + NM;
    double t0 = profiling() ? now() : 0.0;
#pragma omp parallel for schedule(static)
    for (int j = 0; j < ny; ++j) {
        acc_t<NS, NM> t[block], w[warps];
        for (int tt = 0; tt < block; ++tt) {
            t[tt].init();
            for (int i = tt; i < nx; i += block) f(i, j, t[tt].s, t[tt].m);
        }
        for (int wi = 0; wi < warps; ++wi) {
            tree(t + 32 * wi, 32);
            w[wi] = t[32 * wi];
        }
        tree(w, warps);
        for (int k = 0; k < NS; ++k) rows_h[(size_t)j * K + k] = w[0].s[k];
        for (int k = 0; k < NM; ++k) rows_h[(size_t)j * K + NS + k] = w[0].m[k];
    }
    if (profiling()) profile_add(pass_name<F>(), now() - t0);
    return 0;
}
#else
template <int NS, int NM>
__device__ inline void warp_tree(acc_t<NS, NM> &a) {
    for (int o = 16; o > 0; o /= 2) {
        for (int k = 0; k < NS; ++k) a.s[k] += __shfl_down_sync(0xffffffffu, a.s[k], o);
        for (int k = 0; k < NM; ++k) a.m[k] = fmin(a.m[k], __shfl_down_sync(0xffffffffu, a.m[k], o));
    }
}
template <int NS, int NM, class F>
__global__ void __launch_bounds__(block) rows_kernel(F f, int nx, double *out) {
    constexpr int K = NS + NM;
    __shared__ acc_t<NS, NM> sh[warps];
    const int j = blockIdx.x, lane = threadIdx.x % 32, warp = threadIdx.x / 32;
    acc_t<NS, NM> a;
    a.init();
    for (int i = threadIdx.x; i < nx; i += block) f(i, j, a.s, a.m);
    warp_tree(a);
    if (lane == 0) sh[warp] = a;
    __syncthreads();
    if (warp == 0) {
        if (lane < warps) {
            a = sh[lane];
        } else {
            a.init();
        }
        // the warps' results: lanes 0..warps-1 hold them, the others are identities
        for (int o = warps / 2; o > 0; o /= 2) {
            for (int k = 0; k < NS; ++k) a.s[k] += __shfl_down_sync(0xffffffffu, a.s[k], o);
            for (int k = 0; k < NM; ++k) a.m[k] = fmin(a.m[k], __shfl_down_sync(0xffffffffu, a.m[k], o));
        }
        if (lane == 0) {
            for (int k = 0; k < NS; ++k) out[(size_t)j * K + k] = a.s[k];
            for (int k = 0; k < NM; ++k) out[(size_t)j * K + NS + k] = a.m[k];
        }
    }
}
template <int NS, int NM, class F>
int reduce_rows(const F &f, int nx, int ny, double *rows_h) {
    constexpr int K = NS + NM;
    if (failed()) return 1;
    double *rows_d = row_buffer((size_t)K * ny);
    if (!rows_d) return 1;
    double t0 = profiling() ? now() : 0.0;
    rows_kernel<NS, NM><<<ny, block>>>(f, nx, rows_d);
    if (!check(cudaGetLastError(), "reduce_rows launch")) return 1;
    int r = copy_rows(rows_h, rows_d, (size_t)K * ny);
    if (profiling()) profile_add(pass_name<F>(), now() - t0);
    return r;
}
#endif

}  // namespace vs
