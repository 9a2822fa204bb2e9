/* The few POSIX facilities veslide needs from C: what kind of file a path is, an advisory
 * lock that dies with its process, SIGXFSZ turned into an ordinary write error, and the memory
 * a process may use and has used. Called from veslide_system (Fortran, bind(c)). */
#define _GNU_SOURCE
#include <errno.h>
#include <fcntl.h>
#include <signal.h>
#include <stdio.h>
#include <string.h>
#include <sys/file.h>
#include <sys/resource.h>
#include <sys/stat.h>
#include <unistd.h>

/* -1: no such path, 0: regular file, 1: directory, 2: anything else (FIFO, device, socket) */
int veslide_path_kind(const char *path)
{
    struct stat st;
    if (stat(path, &st) != 0) return -1;
    if (S_ISREG(st.st_mode)) return 0;
    if (S_ISDIR(st.st_mode)) return 1;
    return 2;
}

/* An exclusive advisory lock on `path` (created if missing), held until veslide_unlock or the
 * end of the process. Returns the descriptor, -2 when another process holds the lock, -1 on
 * another failure. */
int veslide_lock(const char *path)
{
    int fd = open(path, O_RDWR | O_CREAT | O_CLOEXEC, 0644);
    if (fd < 0) return -1;
    if (flock(fd, LOCK_EX | LOCK_NB) != 0) {
        int busy = (errno == EWOULDBLOCK);
        close(fd);
        return busy ? -2 : -1;
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
