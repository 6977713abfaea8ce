/* The ray-traced reference AO_R of a view, shared by compare and tune: the G-buffer it is traced
 * from (a `none` frame), the camera matrices the renderer uses, and the cache. The reference is
 * cached by (view key, camera, radius, spp, size) under $XDG_CACHE_HOME/obscura (or
 * ~/.cache/obscura): reports and tuning runs are re-run far more often than the geometry changes.
 * An entry records what it was traced from and a checksum of its values, and is checked before it
 * is used (reference_cache.c has the format): a corrupt, truncated, foreign or non-regular entry is
 * one warning line, removed and traced again. */
#ifndef OB_REFERENCE_CACHE_H
#define OB_REFERENCE_CACHE_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "cli_options.h"

/* A view's G-buffer and camera, as the reference and the methods see it. */
typedef struct cli_view_frame {
    int width, height;
    float *depth;          /* width x height, bottom row first, 0 = sky */
    float *normals;        /* 3 per pixel, view space */
    ob_camera cam;         /* the camera with the renderer's defaults filled in (fov, up) */
    float proj_info[4];    /* 1/P00, 1/P11, P20, P21 */
    float inv_view[16];
    /* The reference's ray seed (ob_reference_desc.seed; 0 from cli_view_frame_make): the views
     * whose references are averaged (a path frame's jitter positions) each take their own, so that
     * their rays are independent. */
    uint64_t seed;
} cli_view_frame;

/* Render a `none` frame of cam with r (its scene set) and read the G-buffer. 0 or an exit code
 * (f empty then). */
int cli_view_frame_make(ob_renderer *r, const ob_camera *cam, int width, int height, cli_view_frame *f);
void cli_view_frame_free(cli_view_frame *f);

/* The cache key's text for a view: the scene as the command line named it, the camera,
 * --sidecar/--up when given (they change the geometry the reference sees), and the size and
 * content hash of the files the scene is read from (none for a built-in scene). */
void cli_reference_key(const cli_common *c, const char *scene_name, const char *camera_name, char *key, size_t n);

/* The cache alone, for a host that traces the reference itself (the viewer, on a worker thread):
 * load fills ref (width x height) and the mean standard error over the geometry pixels and returns
 * true when the cache has a valid entry for this (view key, camera, radius, spp, size, scene
 * geometry); an entry that fails the check is a warning on stderr ("obscura: warning: reference
 * cache entry PATH: WHY; recomputing") and is removed. store writes ref and its standard error se
 * through a uniquely named temporary file renamed over the entry; a cache that cannot be written
 * (read-only, full) is one warning per process (one per failure with verbose), not an error. Both
 * are safe on any thread: no GL. */
bool cli_reference_cache_load(const ob_scene *scene, const cli_view_frame *f, const char *key, float radius, int spp,
                              float *ref, double *stderr_mean);
void cli_reference_cache_store(const ob_scene *scene, const cli_view_frame *f, const char *key, float radius,
                               int spp, const float *ref, const float *se, bool verbose);

typedef struct cli_reference_info {
    bool cached;
    double seconds;        /* ray tracing time (0 from the cache) */
    double stderr_mean;    /* mean standard error over the geometry pixels */
} cli_reference_info;

/* AO_R at every pixel of f into ref (width x height): from the cache unless no_cache, else ray
 * traced with spp rays at radius R (a progress bar on stderr) and cached (a failure to cache is
 * a warning, not an error). 0 or an exit code. */
int cli_reference_ao(const ob_scene *scene, const cli_view_frame *f, const char *key, float radius, int spp,
                     bool no_cache, bool verbose, float *ref, cli_reference_info *info);

#endif
