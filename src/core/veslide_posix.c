/* The few POSIX facilities veslide needs from C: what kind of file a path is, an advisory
 * lock that dies with its process, SIGXFSZ turned into an ordinary write error, a termination
 * signal held off while a result file is being written, and the memory a process may use and
 * has used. Called from veslide_system (Fortran, bind(c)). */
#define _GNU_SOURCE
#include <errno.h>
#include <fcntl.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/file.h>
#include <sys/resource.h>
#include <sys/stat.h>
#include <unistd.h>

/* The errno of the last failure of veslide_path_kind or veslide_lock (0: none) */
static int last_errno = 0;

/* -1: no such path, 0: regular file, 1: directory, 2: anything else (FIFO, device, socket) */
int veslide_path_kind(const char *path)
{
    struct stat st;
    if (stat(path, &st) != 0) {
        last_errno = errno;
        return -1;
    }
    last_errno = 0;
    if (S_ISREG(st.st_mode)) return 0;
    if (S_ISDIR(st.st_mode)) return 1;
    return 2;
}

/* The system's words for the last failure of veslide_path_kind or veslide_lock ("File name
 * too long", "Permission denied"), into buf (n bytes, NUL-terminated); "" when none */
void veslide_last_error(char *buf, int n)
{
    if (n <= 0) return;
    buf[0] = '\0';
    if (last_errno != 0) snprintf(buf, (size_t)n, "%s", strerror(last_errno));
}

/* An exclusive advisory lock on `path` (created if missing), held until veslide_unlock or the
 * end of the process. Returns the descriptor, -2 when another process holds the lock, -1 on
 * another failure. */
int veslide_lock(const char *path)
{
    int fd = open(path, O_RDWR | O_CREAT | O_CLOEXEC, 0644);
    if (fd < 0) {
        last_errno = errno;
        return -1;
    }
    if (flock(fd, LOCK_EX | LOCK_NB) != 0) {
        int e = errno;
        close(fd);
        if (e == EWOULDBLOCK) return -2;
        last_errno = e;
        return -1;
    }
    return fd;
}

void veslide_unlock(int fd)
{
    if (fd >= 0) {
        flock(fd, LOCK_UN);
        close(fd);
    }
}

/* End the process now with `status`, without the exit handlers of libraries (HDF5 closes its
 * files in one, and crashes on a file whose last write failed) */
void veslide_exit(int status)
{
    fflush(NULL);
    _exit(status);
}

/* A write beyond the file-size limit (ulimit -f) fails with EFBIG instead of killing the process */
void veslide_ignore_sigxfsz(void)
{
    signal(SIGXFSZ, SIG_IGN);
}

/* Termination (SIGTERM, SIGINT, SIGHUP) held off while a file is written: a signal that comes
 * while `deferring` is noted and acted on (the default action: the process ends by it) when the
 * write is done, so that a study's part file is never left half-written by a stop. Outside a
 * deferred stretch the signal ends the process at once, as without the handler. The handler
 * only sets flags (async-signal-safe) in whichever thread it runs. */
static volatile sig_atomic_t deferring = 0, pending = 0;

static void on_termination(int sig)
{
    if (deferring) {
        pending = sig;
        return;
    }
    signal(sig, SIG_DFL);
    raise(sig);
}

void veslide_catch_termination(void)
{
    struct sigaction sa;
    int sigs[3] = {SIGTERM, SIGINT, SIGHUP};
    memset(&sa, 0, sizeof sa);
    sa.sa_handler = on_termination;
    sa.sa_flags = SA_RESTART;
    sigemptyset(&sa.sa_mask);
    for (int k = 0; k < 3; k++) sigaction(sigs[k], &sa, NULL);
}

void veslide_defer_termination(void)
{
    deferring = 1;
}

void veslide_allow_termination(void)
{
    deferring = 0;
    if (pending) {
        int sig = pending;
        pending = 0;
        signal(sig, SIG_DFL);
        raise(sig);
    }
}

static long long read_number(const char *path)
{
    FILE *f = fopen(path, "r");
    long long v = -1;
    char buf[64];
    if (!f) return -1;
    if (fgets(buf, sizeof buf, f)) {
        if (strncmp(buf, "max", 3) == 0) v = -1;       /* cgroup v2: no limit */
        else if (sscanf(buf, "%lld", &v) != 1) v = -1;
    }
    fclose(f);
    return v;
}

static long long min_limit(long long a, long long b)
{
    if (a < 0) return b;
    if (b < 0) return a;
    return a < b ? a : b;
}

/* Bytes this process may still allocate: the smallest of the available memory of the machine
 * (MemAvailable), the address-space and data-segment limits (less what is in use) and the
 * memory limit of the cgroup (less its usage); -1 when nothing is known */
long long veslide_available_bytes(void)
{
    long long avail = -1, kb, lim, use;
    char line[256];
    struct rlimit rl;
    FILE *f = fopen("/proc/meminfo", "r");
    if (f) {
        while (fgets(line, sizeof line, f)) {
            if (sscanf(line, "MemAvailable: %lld kB", &kb) == 1) {
                avail = kb * 1024;
                break;
            }
        }
        fclose(f);
    }
    use = 0;
    f = fopen("/proc/self/statm", "r");
    if (f) {
        long long pages_total, pages_res;
        if (fscanf(f, "%lld %lld", &pages_total, &pages_res) == 2) use = pages_total * sysconf(_SC_PAGESIZE);
        fclose(f);
    }
    if (getrlimit(RLIMIT_AS, &rl) == 0 && rl.rlim_cur != RLIM_INFINITY)
        avail = min_limit(avail, (long long)rl.rlim_cur - use);
    if (getrlimit(RLIMIT_DATA, &rl) == 0 && rl.rlim_cur != RLIM_INFINITY)
        avail = min_limit(avail, (long long)rl.rlim_cur - use);
    lim = read_number("/sys/fs/cgroup/memory.max");                      /* cgroup v2 */
    if (lim >= 0) avail = min_limit(avail, lim - read_number("/sys/fs/cgroup/memory.current"));
    lim = read_number("/sys/fs/cgroup/memory/memory.limit_in_bytes");    /* cgroup v1 */
    if (lim >= 0 && lim < (1LL << 60))
        avail = min_limit(avail, lim - read_number("/sys/fs/cgroup/memory/memory.usage_in_bytes"));
    return avail;
}

/* Peak resident set size of this process so far [bytes]: VmHWM of /proc/self/status, the
 * high-water mark of this program's own address space (getrusage's ru_maxrss also keeps the
 * peak of the process before exec, e.g. of a large Python parent that started this program) */
long long veslide_peak_rss_bytes(void)
{
    char line[256];
    long long kb = -1;
    FILE *f = fopen("/proc/self/status", "r");
    if (f) {
        while (fgets(line, sizeof line, f)) {
            if (sscanf(line, "VmHWM: %lld kB", &kb) == 1) break;
        }
        fclose(f);
    }
    if (kb < 0) {
        struct rusage ru;
        if (getrusage(RUSAGE_SELF, &ru) != 0) return -1;
        kb = ru.ru_maxrss;
    }
    return kb * 1024;
}

/* Resident set size now [bytes] */
long long veslide_rss_bytes(void)
{
    long long pages_total, pages_res;
    FILE *f = fopen("/proc/self/statm", "r");
    if (!f) return -1;
    if (fscanf(f, "%lld %lld", &pages_total, &pages_res) != 2) pages_res = -1;
    fclose(f);
    return pages_res < 0 ? -1 : pages_res * sysconf(_SC_PAGESIZE);
}

/* OpenMP's threads should sleep, not spin, while they wait at a barrier: on a machine where
 * another process holds a core, a spinning thread takes the core its partner needs (measured in
 * docs/solver-scaling.md). libgomp reads OMP_WAIT_POLICY once, when it is loaded, so a program
 * that wants the passive policy without asking its user re-executes itself once with the variable
 * set (the same arguments, read back from /proc/self/cmdline). Nothing happens when the variable
 * is already set (the user's choice stands) or when /proc is not available; returns only then. */
void veslide_prefer_passive_wait(void)
{
    static char buf[65536];
    char *argv[1024];
    ssize_t n = 0, r;
    int fd, argc = 0;
    if (getenv("OMP_WAIT_POLICY") != NULL) return;
    fd = open("/proc/self/cmdline", O_RDONLY | O_CLOEXEC);
    if (fd < 0) return;
    while ((r = read(fd, buf + n, sizeof(buf) - 1 - (size_t)n)) > 0) n += r;
    close(fd);
    if (r < 0 || n <= 0 || (size_t)n >= sizeof(buf) - 1) return;
    buf[n] = '\0';
    for (char *p = buf; p < buf + n && argc < 1023; p += strlen(p) + 1) argv[argc++] = p;
    if (argc == 0 || argc >= 1023) return;
    argv[argc] = NULL;
    if (setenv("OMP_WAIT_POLICY", "passive", 1) != 0) return;
    execv("/proc/self/exe", argv);
    unsetenv("OMP_WAIT_POLICY");     /* exec failed: go on with the library's default */
}

/* Involuntary context switches of the process so far (all its threads): how often the kernel
 * took a core from it for another runnable task; -1 when unknown */
long long veslide_involuntary_switches(void)
{
    struct rusage ru;
    if (getrusage(RUSAGE_SELF, &ru) != 0) return -1;
    return (long long)ru.ru_nivcsw;
}
