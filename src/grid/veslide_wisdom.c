/* FFTW wisdom kept per machine, so that a grid planned once (FFTW_MEASURE or _PATIENT) is planned
 * the same way by every later run and the results repeat bit for bit. The file is
 * $VESLIDE_FFTW_WISDOM, else ${XDG_CACHE_HOME:-$HOME/.cache}/veslide/fftw-wisdom-HOSTNAME;
 * VESLIDE_FFTW_WISDOM=none keeps no file. A process whose FFTW has its MPI planners (`mpi` 1: a
 * distributed grid) keeps its own file, the same name with "-mpi": a process without them cannot
 * import wisdom that holds MPI plans (FFTW refuses the whole file), and would plan anew. Written
 * atomically (a temporary file renamed), so concurrent runs never read a half-written file.
 * Called from veslide_fftw (bind(c)). */
#define _GNU_SOURCE
#include <errno.h>
#include <fftw3.h>
#include <limits.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

static char wisdom_file[PATH_MAX];

/* The wisdom file's path, of a process with FFTW's MPI planners when `mpi`; 0 when none is kept */
static const char *wisdom_path(int mpi)
{
    const char *env = getenv("VESLIDE_FFTW_WISDOM");
    const char *tail = mpi ? "-mpi" : "";
    char host[256] = "localhost";
    if (env && *env) {
        if (strcmp(env, "none") == 0) return 0;
        snprintf(wisdom_file, sizeof wisdom_file, "%s%s", env, tail);
        return wisdom_file;
    }
    gethostname(host, sizeof host - 1);
    const char *cache = getenv("XDG_CACHE_HOME");
    const char *home = getenv("HOME");
    if (cache && *cache)
        snprintf(wisdom_file, sizeof wisdom_file, "%s/veslide/fftw-wisdom-%s%s", cache, host, tail);
    else if (home && *home)
        snprintf(wisdom_file, sizeof wisdom_file, "%s/.cache/veslide/fftw-wisdom-%s%s", home, host, tail);
    else
        return 0;
    return wisdom_file;
}

/* mkdir -p of the directory part of path */
static void make_parents(const char *path)
{
    char dir[PATH_MAX];
    snprintf(dir, sizeof dir, "%s", path);
    for (char *p = dir + 1; *p; ++p) {
        if (*p != '/') continue;
        *p = 0;
        if (mkdir(dir, 0755) != 0 && errno != EEXIST) return;
        *p = '/';
    }
}

/* Import the machine's wisdom: 1 imported, 0 none (no file, none kept, or unreadable) */
int veslide_wisdom_load(int mpi)
{
    const char *path = wisdom_path(mpi);
    if (!path || access(path, R_OK) != 0) return 0;
    return fftw_import_wisdom_from_filename(path) ? 1 : 0;
}

/* Export the process's wisdom (what it imported and what it planned since): 0 written or none
 * kept, -1 not written (a read-only home is not an error for the run) */
int veslide_wisdom_save(int mpi)
{
    const char *path = wisdom_path(mpi);
    char tmp[PATH_MAX + 32];
    if (!path) return 0;
    make_parents(path);
    snprintf(tmp, sizeof tmp, "%s.%ld.tmp", path, (long)getpid());
    if (!fftw_export_wisdom_to_filename(tmp)) {
        unlink(tmp);
        return -1;
    }
    if (rename(tmp, path) != 0) {
        unlink(tmp);
        return -1;
    }
    return 0;
}
