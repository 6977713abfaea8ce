/* ob_data_dir: where scenes/ (named scene sidecars), data/ (files they name) and shaders/ (the
 * viewer's reload) are, found at run time so that no path of the machine that built the library
 * is compiled into it (the lookup order is documented at ob_data_dir in obscura.h).
 *
 * The anchors are the files the process actually runs: the loaded libobscura (dladdr on one of
 * its own objects; in a static link that is the executable) and the executable
 * (/proc/self/exe). Beside each we try the install layout, then the build tree's:
 *   - installed: OB_DATA_REL_LIBDIR / OB_DATA_REL_BINDIR, the relative path from the install's
 *     libdir / bindir to <datadir>/obscura, computed by CMake from the GNUInstallDirs layout
 *     ("../share/obscura" by default, "../../share/obscura" for lib/<multiarch>); relative, so a
 *     prefix moved as a whole (cmake --install --prefix, DESTDIR, a tarball) still finds it;
 *   - build tree: CMake makes <build>/share/obscura with links to the source tree's scenes/,
 *     data/ and shaders/; build/obscura and build/libobscura.so sit beside share/, the tests
 *     one level below (build/tests/), hence share/obscura and ../share/obscura.
 * A candidate counts only when it has a scenes/ directory, so a stray share/ elsewhere is passed
 * over. */
#include <dlfcn.h>
#include <limits.h>
#include <pthread.h>
#include <stdbool.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "obscura/scene.h"

#ifndef OB_DATA_REL_LIBDIR
#define OB_DATA_REL_LIBDIR "../share/obscura"
#endif
#ifndef OB_DATA_REL_BINDIR
#define OB_DATA_REL_BINDIR "../share/obscura"
#endif

/* Found once per process (the files do not move while it runs); "." when nothing was found. */
static char found_dir[PATH_MAX] = ".";
static pthread_once_t found_once = PTHREAD_ONCE_INIT;

static bool is_data_dir(const char *dir)
{
    char scenes[PATH_MAX + 16] = "";
    struct stat st;
    snprintf(scenes, sizeof scenes, "%s/scenes", dir);
    return stat(scenes, &st) == 0 && S_ISDIR(st.st_mode);
}

/* The directory of `file` with every link resolved, so that a link to the binary (e.g.
 * /usr/local/bin/obscura -> /opt/obscura/bin/obscura) leads to the real install. */
static bool real_dir_of(const char *file, char out[PATH_MAX])
{
    char *real = realpath(file, NULL);
    if (!real) return false;
    char *slash = strrchr(real, '/');
    bool ok = slash != NULL && (size_t)(slash - real) < PATH_MAX;
    if (ok) snprintf(out, PATH_MAX, "%.*s", slash == real ? 1 : (int)(slash - real), real);
    free(real);
    return ok;
}

static bool try_beside(const char *anchor, const char *installed_rel)
{
    const char *rels[3] = {installed_rel, "share/obscura", "../share/obscura"};
    for (int i = 0; i < 3; ++i) {
        char candidate[PATH_MAX + 64] = "";
        int len = snprintf(candidate, sizeof candidate, "%s/%s", anchor, rels[i]);
        if (len < 0 || (size_t)len >= sizeof candidate || !is_data_dir(candidate)) continue;
        /* realpath drops the "..": messages then name a plain path. */
        char *real = realpath(candidate, NULL);
        if (real && strlen(real) < sizeof found_dir) {
            snprintf(found_dir, sizeof found_dir, "%s", real);
            free(real);
            return true;
        }
        free(real);
    }
    return false;
}

static void find_data_dir(void)
{
    char anchor[PATH_MAX] = "";
    Dl_info info;
    memset(&info, 0, sizeof info);
    /* For the main program glibc reports argv[0], which may be a bare name looked up in PATH:
     * only a name with a slash is a path; /proc/self/exe below covers the rest. */
    if (dladdr(found_dir, &info) && info.dli_fname && strchr(info.dli_fname, '/') &&
        real_dir_of(info.dli_fname, anchor) && try_beside(anchor, OB_DATA_REL_LIBDIR))
        return;
    if (real_dir_of("/proc/self/exe", anchor) && try_beside(anchor, OB_DATA_REL_BINDIR)) return;
}

const char *ob_data_dir(void)
{
    /* Read on every call: a host or a test may set it after the first lookup. */
    const char *env = getenv("OBSCURA_DATA_DIR");
    if (env && *env) return env;
    pthread_once(&found_once, find_data_dir);
    return found_dir;
}
