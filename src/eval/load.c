/* ob_load_scene: a scene's name resolved to a built-in scene, a named scene of the data
 * directory (scenes/NAME.obscura.json) or a model path, and built by the builder for it (builtin.c,
 * import.c with its sidecars, sidecar.c). The loader sits above the builders and the container
 * (scene.c), which call nothing up here. */
#if !defined(_POSIX_C_SOURCE) && !defined(_GNU_SOURCE)
#define _POSIX_C_SOURCE 200809L /* stat() */
#endif

#include "eval/import.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <dirent.h>
#include <sys/stat.h>

#include "base/error.h"
#include "base/suggest.h"
#include "eval/model_io.h"
#include "eval/sidecar.h"
#include "io/file.h"

/* Long enough for any path the loader builds (Linux PATH_MAX). */
#define OB_PATH_MAX 4096

/* ---- ob_load_scene --------------------------------------------------------------------------- */

static bool is_regular_file(const char *path)
{
    struct stat st = {0};
    return path && stat(path, &st) == 0 && S_ISREG(st.st_mode);
}

int ob_named_scenes(char names[][64], int max)
{
    char dir[OB_PATH_MAX];
    if (!names || max <= 0 || snprintf(dir, sizeof dir, "%s/scenes", ob_data_dir()) >= (int)sizeof dir) return 0;
    DIR *d = opendir(dir);
    if (!d) return 0;
    int n = 0;
    const char *suffix = ".obscura.json";
    const size_t sl = strlen(suffix);
    for (struct dirent *e; (e = readdir(d)) != NULL && n < max;) {
        size_t len = strlen(e->d_name);
        if (len <= sl || strcmp(e->d_name + len - sl, suffix) != 0 || len - sl >= 64) continue;
        snprintf(names[n], 64, "%.*s", (int)(len - sl), e->d_name);
        ++n;
    }
    closedir(d);
    qsort(names, (size_t)n, 64, (int (*)(const void *, const void *))strcmp);
    return n;
}

/* An unknown bare name: the built-in and named scenes it could have meant, the nearest first when
 * one is a slip of the keyboard (`--scene bunyn`). */
static void unknown_scene(const char *name)
{
    enum { MOST = 128 };
    char stems[MOST][64]; /* 8 KiB of stack, on the error path only */
    const char *names[2 * MOST]; /* the built-in ones, then the named */
    int n = 0;
    char builtin[512] = "", named[2048] = "";
    for (int i = 0; i < ob_builtin_scene_count() && n < MOST; ++i) {
        names[n++] = ob_builtin_scene_name(i);
        snprintf(builtin + strlen(builtin), sizeof builtin - strlen(builtin), "%s%s", i ? ", " : "",
                 ob_builtin_scene_name(i));
    }
    const int count = ob_named_scenes(stems, MOST);
    for (int i = 0; i < count; ++i) {
        names[n++] = stems[i];
        snprintf(named + strlen(named), sizeof named - strlen(named), "%s%s", i ? ", " : "", stems[i]);
    }
    char hint[96];
    ob_set_error(OB_ERR_UNKNOWN_SCENE, "unknown scene '%s'%s (built in: %s; named: %s; or a model file)", name,
                 ob_suggest_text(name, strlen(name), names, n, hint, sizeof hint), builtin, named[0] ? named : "none");
}

static bool is_builtin(const char *name)
{
    for (int i = 0; i < ob_builtin_scene_count(); ++i) {
        if (strcmp(ob_builtin_scene_name(i), name) == 0) return true;
    }
    return false;
}

/* Copy src to dst (of size n); false when it does not fit. */
static bool copy_path(char *dst, size_t n, const char *src)
{
    int len = snprintf(dst, n, "%s", src);
    return len >= 0 && (size_t)len < n;
}

/* The directory part of path ("." when none), without a trailing slash. */
static bool dir_of(char *dst, size_t n, const char *path)
{
    const char *slash = strrchr(path, '/');
    if (!slash) return copy_path(dst, n, ".");
    size_t len = (size_t)(slash - path);
    if (len == 0) return copy_path(dst, n, "/");
    if (len >= n) return false;
    memcpy(dst, path, len);
    dst[len] = '\0';
    return true;
}

/* The file name of path without its directory and without its last extension. */
static bool stem_of(char *dst, size_t n, const char *path)
{
    const char *slash = strrchr(path, '/');
    const char *base = slash ? slash + 1 : path;
    if (!copy_path(dst, n, base)) return false;
    char *dot = strrchr(dst, '.');
    if (dot && dot != dst) *dot = '\0';
    return true;
}

/* rel resolved against the directory holding file (rel unchanged when absolute). */
static bool resolve_beside(char *dst, size_t n, const char *file, const char *rel)
{
    if (rel[0] == '/') return copy_path(dst, n, rel);
    char dir[OB_PATH_MAX] = "";
    if (!dir_of(dir, sizeof dir, file)) return false;
    int len = snprintf(dst, n, "%s/%s", dir, rel);
    return len >= 0 && (size_t)len < n;
}

static ob_scene *path_too_long(const char *what)
{
    ob_set_error(OB_ERR_INVALID_ARGUMENT, "path too long while resolving scene '%s'", what);
    return NULL;
}

/* Import a model, then apply up to two sidecars in order (either may be NULL). */
static ob_scene *import_with_sidecars(const ob_scene_desc *desc, const char *model, ob_up_axis up,
                                      const char *sidecar_a, const char *sidecar_b, const char *scene_name)
{
    ob_scene *s = ob_scene_import_within(model, up, desc->allow_external_files, desc->max_memory,
                                         desc->reserved_memory, desc->reserved_what);
    if (!s) return NULL;
    const char *sidecars[2] = {sidecar_a, sidecar_b};
    for (int i = 0; i < 2; ++i) {
        if (sidecars[i] && ob_scene_apply_sidecar(s, sidecars[i]) != OB_OK) {
            ob_destroy_scene(s);
            return NULL;
        }
    }
    if (!sidecar_a && !sidecar_b && desc->automatic_ground && ob_scene_add_automatic_ground(s, model) != OB_OK) {
        ob_destroy_scene(s);
        return NULL;
    }
    if (scene_name) snprintf(s->name, sizeof s->name, "%s", scene_name);
    return s;
}

ob_scene *ob_load_scene(const ob_scene_desc *desc)
{
    if (!desc || !desc->name || !desc->name[0]) {
        ob_set_error(OB_ERR_INVALID_ARGUMENT, "ob_load_scene: %s",
                     !desc ? "desc is NULL" : "scene name is NULL or empty");
        return NULL;
    }
    if ((int)desc->up < (int)OB_UP_DEFAULT || (int)desc->up > (int)OB_UP_Z) {
        ob_set_error(OB_ERR_INVALID_ARGUMENT, "ob_load_scene: invalid up axis %d", (int)desc->up);
        return NULL;
    }
    const char *name = desc->name;
    const char *explicit_sidecar = desc->sidecar && desc->sidecar[0] ? desc->sidecar : NULL;

    /* The explicit sidecar is checked first (and its "up" read) whatever the scene kind. */
    ob_up_axis explicit_up = OB_UP_DEFAULT;
    if (explicit_sidecar && ob_sidecar_peek(explicit_sidecar, NULL, 0, &explicit_up) != OB_OK) {
        return NULL;
    }

    /* 1. Built in: Y-up by construction, so "up" does not apply. */
    if (is_builtin(name)) {
        ob_scene *s = ob_scene_builtin(name);
        if (s && explicit_sidecar && ob_scene_apply_sidecar(s, explicit_sidecar) != OB_OK) {
            ob_destroy_scene(s);
            return NULL;
        }
        return s;
    }

    /* 2. A named scene: <data>/scenes/NAME.obscura.json with a "model" key. Names with a slash
     * are paths, never names, so "models/x.obj" cannot reach outside scenes/. */
    char named[OB_PATH_MAX] = "";
    if (!strchr(name, '/')) {
        int len = snprintf(named, sizeof named, "%s/scenes/%s.obscura.json", ob_data_dir(), name);
        if (len < 0 || (size_t)len >= sizeof named) return path_too_long(name);
    }
    if (named[0] && is_regular_file(named)) {
        char model_rel[OB_PATH_MAX] = "";
        ob_up_axis named_up = OB_UP_DEFAULT;
        if (ob_sidecar_peek(named, model_rel, sizeof model_rel, &named_up) != OB_OK) return NULL;
        if (!model_rel[0]) {
            ob_set_error(OB_ERR_SIDECAR, "%s: a named scene needs a \"model\" key", named);
            return NULL;
        }
        char model[OB_PATH_MAX] = "";
        if (!resolve_beside(model, sizeof model, named, model_rel)) return path_too_long(name);
        if (!is_regular_file(model)) {
            ob_set_error(OB_ERR_IO, "%s: model '%s' does not exist", named, model);
            return NULL;
        }
        ob_up_axis up = desc->up != OB_UP_DEFAULT  ? desc->up
                        : explicit_up != OB_UP_DEFAULT ? explicit_up
                        : named_up != OB_UP_DEFAULT    ? named_up
                                                       : OB_UP_Y;
        return import_with_sidecars(desc, model, up, named, explicit_sidecar, name);
    }

    /* 3. A model path. */
    if (!is_regular_file(name)) {
        /* Something that exists but is no file (a directory, a FIFO, /dev/null) says what it is:
         * "no such file" would send the user looking for a typo. */
        struct stat st = {0};
        if (stat(name, &st) == 0) {
            ob_set_error(OB_ERR_IO, "cannot read model '%s': it is %s, not a model file", name, ob_file_kind(st.st_mode));
            return NULL;
        }
        /* Something that looks like a path is a missing model; a bare word is an unknown name. */
        if (strchr(name, '/') || strchr(name, '.'))
            ob_set_error(OB_ERR_IO, "cannot read model '%s': no such file", name);
        else
            unknown_scene(name);
        return NULL;
    }
    char stem[OB_PATH_MAX] = "";
    if (!stem_of(stem, sizeof stem, name)) return path_too_long(name);

    /* Sidecar: explicit, else MODEL.obscura.json beside the model, else scenes/STEM.obscura.json
     * in the data directory. */
    char found[OB_PATH_MAX] = "";
    const char *sidecar = explicit_sidecar;
    if (!sidecar) {
        char dir[OB_PATH_MAX] = "";
        if (!dir_of(dir, sizeof dir, name)) return path_too_long(name);
        int len = snprintf(found, sizeof found, "%s/%s.obscura.json", dir, stem);
        if (len < 0 || (size_t)len >= sizeof found) return path_too_long(name);
        /* Anything of that name is taken as the sidecar, so that a FIFO or a directory there
         * fails with a line saying what it is (the reader opens regular files only) instead of
         * being skipped without a word. */
        struct stat beside = {0};
        if (stat(found, &beside) == 0) {
            sidecar = found;
        } else {
            len = snprintf(found, sizeof found, "%s/scenes/%s.obscura.json", ob_data_dir(), stem);
            if (len < 0 || (size_t)len >= sizeof found) return path_too_long(name);
            if (is_regular_file(found)) sidecar = found;
        }
    }
    ob_up_axis sidecar_up = explicit_up;
    if (sidecar && sidecar != explicit_sidecar &&
        ob_sidecar_peek(sidecar, NULL, 0, &sidecar_up) != OB_OK) {
        return NULL;
    }
    ob_up_axis up = desc->up != OB_UP_DEFAULT      ? desc->up
                    : sidecar_up != OB_UP_DEFAULT ? sidecar_up
                                                  : OB_UP_Y;
    return import_with_sidecars(desc, name, up, sidecar, NULL, stem);
}

