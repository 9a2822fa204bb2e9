// The device runtime behind veslide_device.F90: devices, memory, copies, errors (a GPU through
// the CUDA runtime, or the emulated device on the host: veslide_device.cuh). Every function
// returns 0 on success; the first failure is kept with its message until
// veslide_device_take_error reads it (the solvers check between iterations, not after each pass).
#include "veslide_device.cuh"
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <unordered_map>
#include <map>
#include <string>
#include <vector>
#include <algorithm>
#include <cxxabi.h>

namespace vs {

static char error_text[512] = "";
static bool error_set = false;

void note_error(const char *what, const char *detail) {
    if (error_set) return;
    snprintf(error_text, sizeof error_text, "%s: %s", what, detail);
    error_set = true;
}

bool failed() { return error_set; }

#ifndef VESLIDE_EMULATE
bool check(cudaError_t e, const char *what) {
    if (e == cudaSuccess) return true;
    note_error(what, cudaGetErrorString(e));
    return false;
}

int grid_size(long n) {
    static int cap = 0;
    if (cap == 0) {
        int dev = 0, sms = 0;
        cudaGetDevice(&dev);
        cudaDeviceGetAttribute(&sms, cudaDevAttrMultiProcessorCount, dev);
        cap = (sms > 0 ? sms : 80) * 16;   // enough blocks in flight to fill every SM, then stride
    }
    long b = (n + block - 1) / block;
    return (int)(b < cap ? b : cap);
}
#endif

// ---- profiling ----------------------------------------------------------------------------
bool profiling() {
    static int on = -1;
    if (on < 0) {
        const char *e = getenv("VESLIDE_DEVICE_PROFILE");
        on = (e && e[0] == '1') ? 1 : 0;
    }
    return on == 1;
}

double now() {
#ifndef VESLIDE_EMULATE
    cudaDeviceSynchronize();
#endif
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return t.tv_sec + 1e-9 * t.tv_nsec;
}

struct profile_entry {
    long calls = 0;
    double seconds = 0.0;
};
static std::map<std::string, profile_entry> profile_table;

void profile_add(const char *name, double seconds) {
    int status = 0;
    char *plain = abi::__cxa_demangle(name, NULL, NULL, &status);
    std::string key = (status == 0 && plain) ? plain : name;
    free(plain);
    // "(anonymous namespace)::resolvent_f" -> "resolvent_f"
    size_t c = key.rfind("::");
    if (c != std::string::npos && key.find('<') == std::string::npos) key = key.substr(c + 2);
    profile_entry &e = profile_table[key];
    e.calls += 1;
    e.seconds += seconds;
}

// ---- memory accounting: everything veslide allocates on the device, cuFFT's work area too ----
static size_t bytes_now = 0, bytes_peak = 0;

static void count_alloc(size_t n) {
    bytes_now += n;
    if (bytes_now > bytes_peak) bytes_peak = bytes_now;
}

static std::unordered_map<void *, size_t> sizes;   // every live allocation and its size

void *alloc(size_t bytes) {
    void *p = NULL;
#ifdef VESLIDE_EMULATE
    if (posix_memalign(&p, 256, bytes) != 0) p = NULL;
#else
    if (cudaMalloc(&p, bytes) != cudaSuccess) {
        cudaGetLastError();
        p = NULL;
    }
#endif
    if (!p) {
        char d[96];
        snprintf(d, sizeof d, "cannot allocate %.3f GB", bytes / 1e9);
        note_error("device memory", d);
        return NULL;
    }
    sizes[p] = bytes;
    count_alloc(bytes);
    return p;
}

void release(void *p) {
    if (!p) return;
    auto it = sizes.find(p);
    if (it != sizes.end()) {
        bytes_now -= it->second;
        sizes.erase(it);
    }
#ifdef VESLIDE_EMULATE
    free(p);
#else
    check(cudaFree(p), "cudaFree");
#endif
}

// ---- per-row partials ----------------------------------------------------------------------
static double *rows_d = NULL, *rows_h = NULL;
static size_t rows_n = 0;

static bool grow_rows(size_t n) {
    if (n <= rows_n) return true;
    size_t m = n < 4096 ? 4096 : n;
    if (rows_d) release(rows_d);
#ifdef VESLIDE_EMULATE
    free(rows_h);
    rows_h = (double *)malloc(m * sizeof(double));
#else
    if (rows_h) cudaFreeHost(rows_h);
    rows_h = NULL;
    if (!check(cudaMallocHost((void **)&rows_h, m * sizeof(double)), "cudaMallocHost")) rows_h = NULL;
#endif
    rows_d = (double *)alloc(m * sizeof(double));
    rows_n = (rows_d && rows_h) ? m : 0;
    return rows_n > 0;
}

double *row_buffer(size_t n) { return grow_rows(n) ? rows_d : NULL; }
double *host_buffer(size_t n) { return grow_rows(n) ? rows_h : NULL; }

int copy_rows(double *dest, const double *src_d, size_t n) {
#ifdef VESLIDE_EMULATE
    memcpy(dest, src_d, n * sizeof(double));
    return 0;
#else
    double *h = host_buffer(n);
    if (!h) return 1;
    if (!check(cudaMemcpy(h, src_d, n * sizeof(double), cudaMemcpyDeviceToHost), "cudaMemcpy (row partials)"))
        return 1;
    memcpy(dest, h, n * sizeof(double));
    return 0;
#endif
}

// ---- transfers ------------------------------------------------------------------------------
// A host array is copied by all the host's threads (which also touch its pages in parallel, the
// first time), in chunks through two pinned buffers, while the copy engine moves the other
// chunk: pageable copies go at one thread's speed, and a first write to fresh pages at the speed
// of one thread's page faults.
void host_copy(void *dest, const void *src, size_t bytes) {
    const size_t piece = (size_t)1 << 20;
    long n = (long)((bytes + piece - 1) / piece);
#pragma omp parallel for schedule(static)
    for (long i = 0; i < n; ++i) {
        size_t off = (size_t)i * piece, m = bytes - off < piece ? bytes - off : piece;
        memcpy((char *)dest + off, (const char *)src + off, m);
    }
}

#ifndef VESLIDE_EMULATE
static const size_t chunk = (size_t)64 << 20;
static char *pinned[2] = {NULL, NULL};
static cudaStream_t copier = NULL;
static cudaEvent_t done[2];

static bool transfer_setup() {
    if (pinned[0]) return true;
    if (!check(cudaMallocHost((void **)&pinned[0], chunk), "cudaMallocHost") ||
        !check(cudaMallocHost((void **)&pinned[1], chunk), "cudaMallocHost") ||
        !check(cudaStreamCreate(&copier), "cudaStreamCreate") || !check(cudaEventCreate(&done[0]), "cudaEventCreate") ||
        !check(cudaEventCreate(&done[1]), "cudaEventCreate"))
        return false;
    return true;
}

int transfer(void *dest, const void *src, size_t bytes, bool up) {
    if (failed()) return 1;
    if (bytes <= chunk) {   // small: one pageable copy
        return check(cudaMemcpy(dest, src, bytes, up ? cudaMemcpyHostToDevice : cudaMemcpyDeviceToHost),
                     up ? "cudaMemcpy (to the device)" : "cudaMemcpy (from the device)") ? 0 : 1;
    }
    if (!transfer_setup()) return 1;
    // (the copier is a blocking stream: ordered with the passes on the default stream)
    size_t nchunks = (bytes + chunk - 1) / chunk;
    auto size_of = [&](size_t i) { return bytes - i * chunk < chunk ? bytes - i * chunk : chunk; };
    bool good = true;
    if (up) {
        for (size_t i = 0; i < nchunks && good; ++i) {
            int b = (int)(i % 2);
            if (i >= 2) good = check(cudaEventSynchronize(done[b]), "cudaEventSynchronize");
            host_copy(pinned[b], (const char *)src + i * chunk, size_of(i));
            good = good && check(cudaMemcpyAsync((char *)dest + i * chunk, pinned[b], size_of(i),
                                                 cudaMemcpyHostToDevice, copier), "cudaMemcpyAsync (to the device)") &&
                   check(cudaEventRecord(done[b], copier), "cudaEventRecord");
        }
    } else {
        good = check(cudaMemcpyAsync(pinned[0], src, size_of(0), cudaMemcpyDeviceToHost, copier),
                     "cudaMemcpyAsync (from the device)") && check(cudaEventRecord(done[0], copier), "cudaEventRecord");
        for (size_t i = 0; i < nchunks && good; ++i) {
            int b = (int)(i % 2);
            if (i + 1 < nchunks)   // the next chunk moves while this one is copied out
                good = check(cudaMemcpyAsync(pinned[1 - b], (const char *)src + (i + 1) * chunk, size_of(i + 1),
                                             cudaMemcpyDeviceToHost, copier), "cudaMemcpyAsync (from the device)") &&
                       check(cudaEventRecord(done[1 - b], copier), "cudaEventRecord");
            good = good && check(cudaEventSynchronize(done[b]), "cudaEventSynchronize");
            if (good) host_copy((char *)dest + i * chunk, pinned[b], size_of(i));
        }
    }
    good = good && check(cudaStreamSynchronize(copier), "cudaStreamSynchronize");
    return good ? 0 : 1;
}
#endif

}  // namespace vs

extern "C" {

// 1 when this library is the emulated device (host memory, no GPU)
int veslide_device_emulated(void) {
#ifdef VESLIDE_EMULATE
    return 1;
#else
    return 0;
#endif
}

// number of devices visible (0 when none, or when the driver cannot be reached)
int veslide_device_count(void) {
#ifdef VESLIDE_EMULATE
    return 1;
#else
    int n = 0;
    if (cudaGetDeviceCount(&n) != cudaSuccess) {
        cudaGetLastError();   // not sticky: "no device" is an answer, not a failure
        return 0;
    }
    return n;
#endif
}

int veslide_device_select(int ordinal) {
#ifdef VESLIDE_EMULATE
    (void)ordinal;
    return 0;
#else
    return vs::check(cudaSetDevice(ordinal), "cudaSetDevice") ? 0 : 1;
#endif
}

// name (NUL-terminated, at most len bytes), memory [bytes], driver and runtime versions
// (1000 major + 10 minor), compute capability
int veslide_device_properties(int ordinal, char *name, int len, double *total_bytes, int *driver, int *runtime,
                              int *cc_major, int *cc_minor) {
#ifdef VESLIDE_EMULATE
    (void)ordinal;
    snprintf(name, len, "emulated device (host memory, no GPU)");
    *total_bytes = 0;
    *driver = 0;
    *runtime = 0;
    *cc_major = 0;
    *cc_minor = 0;
    return 0;
#else
    cudaDeviceProp p;
    if (!vs::check(cudaGetDeviceProperties(&p, ordinal), "cudaGetDeviceProperties")) return 1;
    snprintf(name, len, "%s", p.name);
    *total_bytes = (double)p.totalGlobalMem;
    *cc_major = p.major;
    *cc_minor = p.minor;
    if (!vs::check(cudaDriverGetVersion(driver), "cudaDriverGetVersion")) return 1;
    if (!vs::check(cudaRuntimeGetVersion(runtime), "cudaRuntimeGetVersion")) return 1;
    return 0;
#endif
}

// free and total memory of the current device [bytes]
int veslide_device_memory(double *free_bytes, double *total_bytes) {
#ifdef VESLIDE_EMULATE
    *free_bytes = -1;
    *total_bytes = -1;
    return 0;
#else
    size_t f = 0, t = 0;
    if (!vs::check(cudaMemGetInfo(&f, &t), "cudaMemGetInfo")) return 1;
    *free_bytes = (double)f;
    *total_bytes = (double)t;
    return 0;
#endif
}

int veslide_device_alloc(void **p, size_t bytes) {
    *p = vs::alloc(bytes > 0 ? bytes : 1);
    return *p ? 0 : 1;
}

int veslide_device_free(void *p) {
    vs::release(p);
    return vs::failed();
}

// bytes moved to and from the device by upload and download (the arrays; not the row partials)
static double moved_up = 0, moved_down = 0;
double veslide_device_moved_bytes(int up) { return up ? moved_up : moved_down; }

int veslide_device_upload(void *dest, const void *src, size_t bytes) {
    if (bytes == 0) return 0;
    moved_up += (double)bytes;
#ifdef VESLIDE_EMULATE
    vs::host_copy(dest, src, bytes);
    return 0;
#else
    return vs::transfer(dest, src, bytes, true);
#endif
}

int veslide_device_download(void *dest, const void *src, size_t bytes) {
    if (bytes == 0) return 0;
    moved_down += (double)bytes;
#ifdef VESLIDE_EMULATE
    vs::host_copy(dest, src, bytes);
    return 0;
#else
    return vs::transfer(dest, src, bytes, false);
#endif
}

int veslide_device_copy(void *dest, const void *src, size_t bytes) {
    if (bytes == 0) return 0;
#ifdef VESLIDE_EMULATE
    memmove(dest, src, bytes);
    return 0;
#else
    return vs::check(cudaMemcpy(dest, src, bytes, cudaMemcpyDeviceToDevice), "cudaMemcpy (on the device)") ? 0 : 1;
#endif
}

int veslide_device_zero(void *dest, size_t bytes) {
    if (bytes == 0) return 0;
#ifdef VESLIDE_EMULATE
    memset(dest, 0, bytes);
    return 0;
#else
    return vs::check(cudaMemset(dest, 0, bytes), "cudaMemset") ? 0 : 1;
#endif
}

int veslide_device_sync(void) {
#ifdef VESLIDE_EMULATE
    return vs::failed();
#else
    return vs::check(cudaDeviceSynchronize(), "cudaDeviceSynchronize") ? 0 : 1;
#endif
}

// 1 when a device call failed since the last take_error
int veslide_device_failed(void) { return vs::failed(); }

// the first failure's message (NUL-terminated, at most len bytes), and the state cleared
void veslide_device_take_error(char *msg, int len) {
    snprintf(msg, len, "%s", vs::error_text);
    vs::error_text[0] = 0;
    vs::error_set = false;
}

// bytes veslide holds on the device now, the most it held since the last reset
double veslide_device_bytes_in_use(void) { return (double)vs::bytes_now; }
double veslide_device_peak_bytes(void) { return (double)vs::bytes_peak; }
void veslide_device_reset_peak(void) { vs::bytes_peak = vs::bytes_now; }

// seconds since an arbitrary origin, after the device has finished its work
double veslide_device_clock(void) { return vs::now(); }

// the profile (VESLIDE_DEVICE_PROFILE=1) printed on stdout, largest first, and cleared
void veslide_device_profile(void) {
    if (!vs::profiling()) return;
    std::vector<std::pair<std::string, vs::profile_entry>> rows(vs::profile_table.begin(), vs::profile_table.end());
    std::sort(rows.begin(), rows.end(),
              [](const std::pair<std::string, vs::profile_entry> &a, const std::pair<std::string, vs::profile_entry> &b) {
                  return a.second.seconds > b.second.seconds;
              });
    double total = 0;
    for (auto &r : rows) total += r.second.seconds;
    printf("| pass | calls | total [ms] | per call [ms] | share |\n|---|---|---|---|---|\n");
    for (auto &r : rows)
        printf("| %s | %ld | %.2f | %.4f | %.1f %% |\n", r.first.c_str(), r.second.calls, 1e3 * r.second.seconds,
               1e3 * r.second.seconds / r.second.calls, 100.0 * r.second.seconds / (total > 0 ? total : 1));
    fflush(stdout);
    vs::profile_table.clear();
}

}  // extern "C"
