/* The ray-traced reference of a view and its cache (reference_cache.h). */
#include "reference_cache.h"

#include <cglm/cglm.h>
#include <errno.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <time.h>
#include <unistd.h>

int cli_view_frame_make(ob_renderer *r, const ob_camera *cam, int width, int height, cli_view_frame *f)
{
    memset(f, 0, sizeof *f);
    size_t px = (size_t)width * (size_t)height;
    f->width = width;
    f->height = height;
    f->depth = malloc(px * sizeof(float));
    f->normals = malloc(px * 3 * sizeof(float));
    if (!f->depth || !f->normals) {
        cli_view_frame_free(f);
        return cli_fail(EXIT_RUNTIME, "out of memory");
    }
    /* The G-buffer is the same for every method: take it from a `none` frame. */
    ob_settings s;
    ob_settings_init(&s, "none");
    if (ob_render_frame(r, cam, &s) != OB_OK) {
        cli_view_frame_free(f);
        return cli_fail_from_library();
    }
    ob_read_image(r, OB_IMAGE_DEPTH_F32, f->depth, px * sizeof(float));
    ob_read_image(r, OB_IMAGE_NORMAL_F32, f->normals, px * 3 * sizeof(float));
    /* The same camera matrices as the renderer (renderer.c): for the world points. */
    f->cam = *cam;
    if (f->cam.fov_y_deg <= 0.0f) f->cam.fov_y_deg = 60.0f;
    if (f->cam.up[0] == 0.0f && f->cam.up[1] == 0.0f && f->cam.up[2] == 0.0f) f->cam.up[1] = 1.0f;
    mat4 view, inv_view, proj;
    glm_lookat(f->cam.eye, f->cam.target, f->cam.up, view);
    glm_mat4_inv(view, inv_view);
    glm_perspective(glm_rad(f->cam.fov_y_deg), (float)width / (float)height, 1.0f, 2.0f, proj);
    proj[2][0] = f->cam.shift[0]; /* the lens shift, as ob_render_frame */
    proj[2][1] = f->cam.shift[1];
    f->proj_info[0] = 1.0f / proj[0][0];
    f->proj_info[1] = 1.0f / proj[1][1];
    f->proj_info[2] = proj[2][0];
    f->proj_info[3] = proj[2][1];
    memcpy(f->inv_view, inv_view, sizeof f->inv_view);
    return EXIT_OK;
}

void cli_view_frame_free(cli_view_frame *f)
{
    free(f->depth);
    free(f->normals);
    f->depth = f->normals = NULL;
}

void cli_reference_key(const cli_common *c, const char *scene_name, const char *camera_name, char *key, size_t n)
{
    /* --sidecar and --up are part of the key only when given, so that existing caches still hit. */
    int len = snprintf(key, n, "%s|%s|v1", scene_name, camera_name);
    if ((c->sidecar || c->up != OB_UP_DEFAULT) && len > 0 && (size_t)len < n)
        snprintf(key + len, n - (size_t)len, "|sidecar=%s|up=%d", c->sidecar ? c->sidecar : "", (int)c->up);
}

static uint64_t fnv1a(const void *data, size_t n, uint64_t h)
{
    const unsigned char *p = data;
    for (size_t i = 0; i < n; ++i) h = (h ^ p[i]) * 1099511628211ull;
    return h;
}

static const char *cache_dir(char *buf, size_t n)
{
    const char *xdg = getenv("XDG_CACHE_HOME");
    const char *home = getenv("HOME");
    if (xdg && *xdg) snprintf(buf, n, "%s/obscura", xdg);
    else if (home && *home) snprintf(buf, n, "%s/.cache/obscura", home);
    else return NULL;
    return buf;
}

static bool make_dir(const char *path) { return mkdir(path, 0777) == 0 || errno == EEXIST; }

/* The cache file of a view's reference: its name hashes (view key, camera, radius, spp, size).
 * False when there is no cache directory ($XDG_CACHE_HOME and $HOME unset). */
static bool cache_path(const ob_scene *scene, const cli_view_frame *f, const char *view_key, float radius, int spp,
                       char *dir, size_t dn, char *path, size_t pn)
{
    int w = f->width, h = f->height;
    uint64_t key = fnv1a(view_key, strlen(view_key), 1469598103934665603ull);
    key = fnv1a(&f->cam, sizeof f->cam, key);
    key = fnv1a(&radius, sizeof radius, key);
    key = fnv1a(&spp, sizeof spp, key);
    key = fnv1a(&w, sizeof w, key);
    key = fnv1a(&h, sizeof h, key);
    /* The geometry too: a named scene's sidecar (a ground added under a model) changes what the
     * rays hit without changing the view key, and a stale reference would grade every method
     * against the old scene. */
    ob_scene_stats stats = ob_query_scene_stats(scene);
    key = fnv1a(&stats, sizeof stats, key);
    if (!cache_dir(dir, dn)) return false;
    snprintf(path, pn, "%s/reference-%016llx.pfm", dir, (unsigned long long)key);
    return true;
}

bool cli_reference_cache_load(const ob_scene *scene, const cli_view_frame *f, const char *view_key, float radius,
                              int spp, float *ref, double *stderr_mean)
{
    char dir[512], path[700];
    if (!cache_path(scene, f, view_key, radius, spp, dir, sizeof dir, path, sizeof path)) return false;
    size_t px = (size_t)f->width * (size_t)f->height;
    int cw = 0, ch = 0, cc = 0;
    float *cached = NULL;
    if (access(path, R_OK) == 0 && ob_read_pfm(path, &cw, &ch, &cc, &cached) == OB_OK && cw == f->width &&
        ch == f->height && cc == 3) {
        /* Channels: AO, standard error, unused. */
        double se = 0.0;
        size_t n = 0;
        for (size_t i = 0; i < px; ++i) {
            ref[i] = cached[3 * i];
            if (f->depth[i] > 0.0f) se += cached[3 * i + 1], ++n;
        }
        free(cached);
        *stderr_mean = n ? se / (double)n : 0.0;
        return true;
    }
    free(cached);
    ob_clear_error(); /* a missing or stale cache entry is not an error */
    return false;
}

void cli_reference_cache_store(const ob_scene *scene, const cli_view_frame *f, const char *view_key, float radius,
                               int spp, const float *ref, const float *se, bool verbose)
{
    char dir[512], path[700];
    if (!cache_path(scene, f, view_key, radius, spp, dir, sizeof dir, path, sizeof path)) return;
    size_t px = (size_t)f->width * (size_t)f->height;
    float *rgb = malloc(px * 3 * sizeof(float));
    if (!rgb) return; /* a failure to cache is not a failure of the command */
    char parent[520];
    snprintf(parent, sizeof parent, "%s", dir);
    char *slash = strrchr(parent, '/');
    if (slash) {
        *slash = '\0';
        make_dir(parent);
    }
    make_dir(dir);
    for (size_t i = 0; i < px; ++i) {
        rgb[3 * i] = ref[i];
        rgb[3 * i + 1] = se[i];
        rgb[3 * i + 2] = 0.0f;
    }
    if (ob_write_pfm(path, f->width, f->height, 3, rgb) != OB_OK) {
        ob_clear_error();
        if (verbose) fprintf(stderr, "obscura: note: could not cache the reference in %s\n", path);
    }
    free(rgb);
}

int cli_reference_ao(const ob_scene *scene, const cli_view_frame *f, const char *view_key, float radius, int spp,
                     bool no_cache, bool verbose, float *ref, cli_reference_info *info)
{
    memset(info, 0, sizeof *info);
    int w = f->width, h = f->height;
    size_t px = (size_t)w * (size_t)h;
    if (!no_cache && cli_reference_cache_load(scene, f, view_key, radius, spp, ref, &info->stderr_mean)) {
        info->cached = true;
        return EXIT_OK;
    }
    float *pos = malloc(px * 3 * sizeof(float)), *nrm = malloc(px * 3 * sizeof(float));
    float *se = malloc(px * sizeof(float));
    if (!pos || !nrm || !se) {
        free(pos);
        free(nrm);
        free(se);
        return cli_fail(EXIT_RUNTIME, "out of memory for the reference");
    }
    int code = EXIT_OK;
    struct timespec t0, t1;
    clock_gettime(CLOCK_MONOTONIC, &t0);
    if (ob_reference_points(f->depth, f->normals, w, h, f->proj_info, f->inv_view, pos, nrm) != OB_OK ||
        ob_reference_ao(scene, pos, nrm, px, &(ob_reference_desc){.spp = spp, .radius = radius, .progress = true}, ref,
                        se) != OB_OK) {
        code = cli_fail_from_library();
    }
    clock_gettime(CLOCK_MONOTONIC, &t1);
    info->seconds = (double)(t1.tv_sec - t0.tv_sec) + 1e-9 * (double)(t1.tv_nsec - t0.tv_nsec);
    if (code == EXIT_OK) {
        double sum = 0.0;
        size_t n = 0;
        for (size_t i = 0; i < px; ++i)
            if (f->depth[i] > 0.0f) sum += se[i], ++n;
        info->stderr_mean = n ? sum / (double)n : 0.0;
        /* Cache: a failure to cache is not a failure of the command. */
        cli_reference_cache_store(scene, f, view_key, radius, spp, ref, se, verbose);
    }
    free(pos);
    free(nrm);
    free(se);
    return code;
}
