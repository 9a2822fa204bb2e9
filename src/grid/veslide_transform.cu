// The device twin of veslide_fftw's fft2d_t: 2-D real transforms of an nx x ny field (i fastest,
// Fortran order) into its half-spectrum (nx/2+1) x ny, unnormalised, forward exp(-i q.x), on
// buffers the caller allocated on the device (veslide_transform.F90). On a GPU: cuFFT's D2Z and
// Z2D plans (one-dimensional when ny = 1) sharing one work area, allocated and counted by
// veslide (veslide_device_peak_bytes). The work area is scratch only while a transform runs: the
// caller may lend one of its own arrays that is dead whenever a transform runs (lend_work: the
// contact fields lend u, veslide_contact.f90), else the transform allocates its own at its first
// use. On the emulated device: FFTW's 2-D plans on the same buffers (veslide_device.cuh), and the
// work area modelled: nx ny doubles (what cuFFT holds from 4096^2 up), written over with NaN by
// every transform, so that a lent array that was not dead spoils the result where it is tested.
#include "../core/veslide_device.cuh"
#include <stdio.h>
#include <stdlib.h>
#ifdef VESLIDE_EMULATE
#include <fftw3.h>
#else
#include <cufft.h>
#include <cufftXt.h>
#endif
#include <string.h>

namespace {

#ifndef VESLIDE_EMULATE
const char *cufft_text(cufftResult r) {
    switch (r) {
    case CUFFT_SUCCESS: return "success";
    case CUFFT_INVALID_PLAN: return "invalid plan";
    case CUFFT_ALLOC_FAILED: return "allocation failed";
    case CUFFT_INVALID_VALUE: return "invalid value";
    case CUFFT_INTERNAL_ERROR: return "internal error";
    case CUFFT_EXEC_FAILED: return "execution failed";
    case CUFFT_SETUP_FAILED: return "setup failed (no usable GPU?)";
    case CUFFT_INVALID_SIZE: return "invalid size";
    default: return "error";
    }
}

bool ok(cufftResult r, const char *what) {
    if (r == CUFFT_SUCCESS) return true;
    vs::note_error(what, cufft_text(r));
    return false;
}
#endif

struct plan_t {
    int nx, ny;
    double *x;      // real buffer (nx, ny)
    double2 *k;     // half-spectrum buffer (nx/2+1, ny)
#ifdef VESLIDE_EMULATE
    fftw_plan f, b;
#else
    cufftHandle f, b;
#endif
    size_t work_bytes;   // the work area the plans need
    void *work;          // where it is now: lent by the caller, or own_work (NULL: not yet given)
    void *own_work;      // the transform's own, allocated at a first use without a lent one
};

// the work area given to the plans (a lent one, or the transform's own, allocated now)
bool bind_work(plan_t *p, void *area) {
    if (p->work_bytes == 0) return true;
    if (!area) {
        if (!p->own_work) p->own_work = vs::alloc(p->work_bytes);
        if (!p->own_work) return false;
        area = p->own_work;
    } else if (p->own_work) {   // lent one now: its own given back
        vs::release(p->own_work);
        p->own_work = NULL;
    }
    p->work = area;
#ifndef VESLIDE_EMULATE
    return ok(cufftSetWorkArea(p->f, area), "cufftSetWorkArea") && ok(cufftSetWorkArea(p->b, area), "cufftSetWorkArea");
#else
    return true;
#endif
}

// before a transform: a work area bound
bool work_ready(plan_t *p) { return p->work_bytes == 0 || p->work || bind_work(p, NULL); }
#ifdef VESLIDE_EMULATE
// after it (emulated): the work area spoilt, as cuFFT leaves it
void work_spoilt(plan_t *p) {
    if (p->work) memset(p->work, 0xff, p->work_bytes);   // all bits set: NaN
}
#endif

}  // namespace

extern "C" {

// A transform of nx x ny on the device buffers x (nx ny doubles) and k ((nx/2+1) ny complex);
// *work_bytes: the work area it needs (given at its first use, or lent: veslide_transform_lend_work).
// policy: 1 cuFFT's smallest work area (CUFFT_WORKAREA_MINIMAL), 0 its default (the fastest plans), -1 as the environment's
// VESLIDE_CUFFT_WORKAREA says ('minimal' or 'performance'; unset: the default)
int veslide_transform_create(void **handle, int nx, int ny, double *x, void *k, int policy, double *work_bytes) {
    *handle = NULL;
    *work_bytes = 0;
    if (vs::failed()) return 1;
    plan_t *p = (plan_t *)calloc(1, sizeof(plan_t));
    if (!p) return 1;
    p->nx = nx;
    p->ny = ny;
    p->x = x;
    p->k = (double2 *)k;
#ifdef VESLIDE_EMULATE
    (void)policy;
    p->work_bytes = (size_t)nx * (size_t)ny * sizeof(double);   // the model: cuFFT's from 4096^2 up
    p->f = fftw_plan_dft_r2c_2d(ny, nx, x, (fftw_complex *)k, FFTW_ESTIMATE);
    p->b = fftw_plan_dft_c2r_2d(ny, nx, (fftw_complex *)k, x, FFTW_ESTIMATE);
    if (!p->f || !p->b) {
        vs::note_error("transform", "FFTW returned a null plan");
        free(p);
        return 1;
    }
#else
    size_t wf = 0, wb = 0;
    if (policy < 0) {
        const char *e = getenv("VESLIDE_CUFFT_WORKAREA");
        policy = (e && strcmp(e, "minimal") == 0) ? 1 : 0;
    }
    bool good = ok(cufftCreate(&p->f), "cufftCreate") && ok(cufftCreate(&p->b), "cufftCreate") &&
                ok(cufftSetAutoAllocation(p->f, 0), "cufftSetAutoAllocation") &&
                ok(cufftSetAutoAllocation(p->b, 0), "cufftSetAutoAllocation");
    // (refused by some cuFFT versions for these plans: then the default, and work_bytes says so)
    if (good && policy == 1) {
        size_t ws = 0;
        if (cufftXtSetWorkAreaPolicy(p->f, CUFFT_WORKAREA_MINIMAL, &ws) != CUFFT_SUCCESS ||
            cufftXtSetWorkAreaPolicy(p->b, CUFFT_WORKAREA_MINIMAL, &ws) != CUFFT_SUCCESS)
            policy = 0;
    }
    if (good) {
        if (ny == 1) {
            good = ok(cufftMakePlan1d(p->f, nx, CUFFT_D2Z, 1, &wf), "cufftMakePlan1d (D2Z)") &&
                   ok(cufftMakePlan1d(p->b, nx, CUFFT_Z2D, 1, &wb), "cufftMakePlan1d (Z2D)");
        } else {
            // cuFFT is row-major: the slowest dimension (y, ny) first
            good = ok(cufftMakePlan2d(p->f, ny, nx, CUFFT_D2Z, &wf), "cufftMakePlan2d (D2Z)") &&
                   ok(cufftMakePlan2d(p->b, ny, nx, CUFFT_Z2D, &wb), "cufftMakePlan2d (Z2D)");
        }
    }
    // the two plans never run at once: one work area for both, given at the first use
    if (good) p->work_bytes = wf > wb ? wf : wb;
    if (!good) {
        cufftDestroy(p->f);
        cufftDestroy(p->b);
        free(p);
        return 1;
    }
#endif
    *work_bytes = (double)p->work_bytes;
    *handle = p;
    return 0;
}

// The work area of the transform: `area` (device memory of `bytes` bytes that the caller lends:
// dead whenever a transform runs, until it lends another or none) when it is at least the plans'
// need, else the transform's own (allocated now, kept until destroyed). area NULL: its own.
// Returns 1 when `area` was lent (0: the transform's own, or none needed)
int veslide_transform_lend_work(void *handle, void *area, double bytes) {
    plan_t *p = (plan_t *)handle;
    if (!p || vs::failed()) return 0;
    bool lent = area && bytes >= (double)p->work_bytes;
    bind_work(p, lent ? area : NULL);
    return lent && p->work_bytes > 0 ? 1 : 0;
}

// k <- transform of x (x is kept)
int veslide_transform_forward(void *handle) {
    plan_t *p = (plan_t *)handle;
    if (vs::failed() || !work_ready(p)) return 1;
    double t0 = vs::profiling() ? vs::now() : 0.0;
#ifdef VESLIDE_EMULATE
    fftw_execute(p->f);
    work_spoilt(p);
    int r = 0;
#else
    int r = ok(cufftExecD2Z(p->f, p->x, (cufftDoubleComplex *)p->k), "cufftExecD2Z") ? 0 : 1;
#endif
    if (vs::profiling()) vs::profile_add("transform forward (D2Z)", vs::now() - t0);
    return r;
}

// x <- unnormalised inverse transform of k (k is destroyed)
int veslide_transform_backward(void *handle) {
    plan_t *p = (plan_t *)handle;
    if (vs::failed() || !work_ready(p)) return 1;
    double t0 = vs::profiling() ? vs::now() : 0.0;
#ifdef VESLIDE_EMULATE
    fftw_execute(p->b);
    work_spoilt(p);
    int r = 0;
#else
    int r = ok(cufftExecZ2D(p->b, (cufftDoubleComplex *)p->k, p->x), "cufftExecZ2D") ? 0 : 1;
#endif
    if (vs::profiling()) vs::profile_add("transform backward (Z2D)", vs::now() - t0);
    return r;
}

int veslide_transform_destroy(void *handle) {
    plan_t *p = (plan_t *)handle;
    if (!p) return 0;
#ifdef VESLIDE_EMULATE
    fftw_destroy_plan(p->f);
    fftw_destroy_plan(p->b);
#else
    cufftDestroy(p->f);
    cufftDestroy(p->b);
#endif
    if (p->own_work) vs::release(p->own_work);
    free(p);
    return vs::failed();
}

}  // extern "C"
