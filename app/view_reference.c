/* obscura view's reference view (G, issue 20): the ground truth beside the method. The Embree
 * AO_R (docs/architecture.md: cosine-weighted rays from the very G-buffer points the method sees, ending at
 * R) of the current camera, the method's AO, their signed error and the current view, in four
 * panes of half the picture each way (beside the panel), with the RMSE over the geometry pixels.
 *
 * Why at the pane's size: the panes are what is shown, so tracing more pixels than that would be
 * time spent on pixels no one sees (450x300 on a 900x600 window: compare traced Cornell's in 4.8 s
 * on 2 cores at 512 rays per pixel). The method is rendered by a renderer of its own at that size, so both
 * images describe the same points.
 *
 * Why a worker thread: a trace takes seconds; the window keeps drawing (the method's pane stays
 * live: change a parameter and watch the RMSE) while it runs. The worker traces the geometry
 * points in bands, one ob_reference_ao call each, which gives the progress line and a stop
 * between bands (a new trace, the view turned off, quit) without a change to the library; each
 * band rebuilds Embree's BVH (about 30 ms for FZK-Haus or the bunny), so there are at most 20.
 * Results are cached on disk (reference_cache.h) by scene, camera, radius, rays and size, so
 * turning the view on again for a camera already traced is instant.
 *
 * A script's clock waits while a trace runs (view.c), so `key G press` followed by a screenshot
 * shows the finished reference on any machine. */
#include <epoxy/gl.h>
#include <math.h>
#include <pthread.h>
#include <stdatomic.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "reference_cache.h"
#include "view.h"
#include "view_gui.h"

enum {
    REF_MIN_BAND = 4096, /* points per band at least: below that the BVH build dominates */
    REF_MAX_BANDS = 20,  /* progress in 5 % steps at best */
};
/* The error pane saturates at +-0.5, as compare's error maps do. */
#define REF_ERROR_RANGE 0.5f
/* Rays per pixel to choose from; 512 is compare's default (mean standard error < 0.01). */
static const int ref_spp_choices[] = {64, 128, 256, 512};
static const char *const ref_spp_names[] = {"64", "128", "256", "512"};
enum { REF_SPP_COUNT = 4, REF_SPP_DEFAULT = 3 };

/* One trace. The worker owns everything but the atomics until it sets `finished`. */
typedef struct ref_job {
    const ob_scene *scene;
    cli_view_frame frame; /* the pane-sized G-buffer and its camera */
    ob_camera cam;        /* as the viewer gave it (frame.cam has the renderer's defaults filled in) */
    char key[600];
    float radius;
    int spp;
    bool verbose;
    float *ao, *se;       /* frame size, bottom row first */
    bool cached;
    double seconds, stderr_mean;
    char error[512];      /* empty: it worked */
    atomic_int permille;  /* progress, 0..1000 */
    atomic_bool cancel, finished;
} ref_job;

struct view_reference {
    bool on;
    int spp_choice;
    ob_renderer *r;  /* pane-sized: the method's AO and the G-buffer points */
    int w, h;
    pthread_t thread;
    ref_job *job;    /* the trace under way, NULL when none */
    double job_start;
    /* The reference shown: its camera, radius, rays and size say whether it is still the truth
     * of what the method pane shows. */
    float *ref;
    uint8_t *mask;   /* its geometry pixels (depth > 0): the error is measured there */
    ob_camera cam;
    float radius;
    int spp, ref_w, ref_h;
    bool have, cached, ref_uploaded;
    double seconds, stderr_mean;
    /* The method's AO now, its geometry pixels, and its error against the reference. */
    float *ao, *depth;
    uint8_t *live_mask;
    size_t ao_cap;
    ob_metrics m;
    bool fresh, measured;
    /* Display: the method's AO, the reference and the error as textures blitted into the panes. */
    GLuint tex[3], fbo;
    int tex_w[3], tex_h[3];
    uint8_t *bytes;
    size_t bytes_cap;
};

static double wall_seconds(void)
{
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return (double)t.tv_sec + 1e-9 * (double)t.tv_nsec;
}

/* ---- the worker ---------------------------------------------------------------------------- */
static void job_fail(ref_job *j, const char *what)
{
    const char *msg = "";
    ob_get_error(&msg);
    snprintf(j->error, sizeof j->error, "%s%s%s", what, *msg ? ": " : "", msg);
}

static void *trace(void *arg)
{
    ref_job *j = arg;
    double t0 = wall_seconds();
    const cli_view_frame *f = &j->frame;
    size_t px = (size_t)f->width * (size_t)f->height;
    if (cli_reference_cache_load(j->scene, f, j->key, j->radius, j->spp, j->ao, &j->stderr_mean)) {
        j->cached = true;
        atomic_store(&j->permille, 1000);
        atomic_store(&j->finished, true);
        return NULL;
    }
    float *pos = malloc(px * 3 * sizeof(float)), *nrm = malloc(px * 3 * sizeof(float));
    float *cao = malloc(px * sizeof(float)), *cse = malloc(px * sizeof(float));
    size_t *index = malloc(px * sizeof(size_t));
    if (!pos || !nrm || !cao || !cse || !index) {
        snprintf(j->error, sizeof j->error, "out of memory for a %dx%d reference", f->width, f->height);
    } else if (ob_reference_points(f->depth, f->normals, f->width, f->height, f->proj_info, f->inv_view, pos, nrm) !=
               OB_OK) {
        job_fail(j, "reference points");
    } else {
        /* The geometry points packed together (in place: the packed index never passes the
         * source), so every band holds the same work and the progress moves evenly. */
        size_t n = 0;
        for (size_t i = 0; i < px; ++i) {
            if (!(f->depth[i] > 0.0f)) continue;
            memmove(pos + 3 * n, pos + 3 * i, 3 * sizeof(float));
            memmove(nrm + 3 * n, nrm + 3 * i, 3 * sizeof(float));
            index[n++] = i;
        }
        size_t bands = n / REF_MIN_BAND;
        bands = bands < 1 ? 1 : bands > REF_MAX_BANDS ? REF_MAX_BANDS : bands;
        for (size_t b = 0; b < bands && !j->error[0]; ++b) {
            if (atomic_load(&j->cancel)) break;
            size_t lo = n * b / bands, hi = n * (b + 1) / bands;
            /* A seed per band: each call numbers its points from 0, and one seed for all would
             * give every band the same ray directions pixel by pixel (a visible repeat). */
            ob_reference_desc desc = {.spp = j->spp, .radius = j->radius, .seed = 0x9e3779b97f4a7c15ull * (b + 1)};
            if (ob_reference_ao(j->scene, pos + 3 * lo, nrm + 3 * lo, hi - lo, &desc, cao + lo, cse + lo) != OB_OK)
                job_fail(j, "reference");
            atomic_store(&j->permille, (int)(1000 * (b + 1) / bands));
        }
        if (!j->error[0] && !atomic_load(&j->cancel)) {
            double sum = 0.0;
            for (size_t i = 0; i < px; ++i) {
                j->ao[i] = 1.0f; /* sky: open, and outside the mask anyway */
                j->se[i] = 0.0f;
            }
            for (size_t k = 0; k < n; ++k) {
                j->ao[index[k]] = cao[k];
                j->se[index[k]] = cse[k];
                sum += cse[k];
            }
            j->stderr_mean = n ? sum / (double)n : 0.0;
            cli_reference_cache_store(j->scene, f, j->key, j->radius, j->spp, j->ao, j->se, j->verbose);
        }
    }
    free(pos);
    free(nrm);
    free(cao);
    free(cse);
    free(index);
    j->seconds = wall_seconds() - t0;
    atomic_store(&j->finished, true);
    return NULL;
}

static void job_free(ref_job *j)
{
    if (!j) return;
    cli_view_frame_free(&j->frame);
    free(j->ao);
    free(j->se);
    free(j);
}

/* Stop the trace under way (it ends after its current band) and forget it. */
static void stop_job(view_reference *R)
{
    if (!R->job) return;
    atomic_store(&R->job->cancel, true);
    pthread_join(R->thread, NULL);
    job_free(R->job);
    R->job = NULL;
}

/* ---- the state ----------------------------------------------------------------------------- */
float view_ao_radius(const viewer *v)
{
    const ob_method_info *m = ob_method_at(v->s.method);
    for (int i = 0; i < m->param_count; ++i) {
        if (strcmp(m->params[i].name, "radius") != 0) continue;
        bool follows = m->params[i].follows_scene_radius && !(v->s.params_set & (1u << i));
        return follows ? ob_query_scene_ao_radius(v->scene) : v->s.params[i];
    }
    return ob_query_scene_ao_radius(v->scene); /* none: graded at the scene's radius */
}

static view_reference *state(viewer *v)
{
    if (!v->ref) {
        v->ref = calloc(1, sizeof *v->ref);
        if (v->ref) v->ref->spp_choice = REF_SPP_DEFAULT;
    }
    return v->ref;
}

bool view_reference_on(const viewer *v) { return v->ref && v->ref->on; }
bool view_reference_busy(const viewer *v) { return v->ref && v->ref->job; }

static bool same_camera(const ob_camera *a, const ob_camera *b) { return memcmp(a, b, sizeof *a) == 0; }

/* The pane renderer at w x h (made on first use). */
static bool fit_renderer(viewer *v, view_reference *R, int w, int h)
{
    if (R->r && R->w == w && R->h == h) return true;
    if (!R->r) {
        R->r = ob_make_renderer(v->ctx, &(ob_renderer_desc){.width = w, .height = h});
        if (!R->r || ob_renderer_set_scene(R->r, v->scene) != OB_OK ||
            (v->o.common.env && ob_renderer_set_environment(R->r, v->o.common.env) != OB_OK)) {
            ob_destroy_renderer(R->r);
            R->r = NULL;
            return false;
        }
    } else if (ob_renderer_resize(R->r, w, h) != OB_OK) {
        return false;
    }
    R->w = w;
    R->h = h;
    return true;
}

static void pane_size(int w, int h, int *pw, int *ph)
{
    *pw = w / 2 > 16 ? w / 2 : 16;
    *ph = h / 2 > 16 ? h / 2 : 16;
}

/* The reference of the current camera at the pane size: shown already, or a trace started. */
static void start(viewer *v, view_reference *R)
{
    int pw = 0, ph = 0;
    pane_size(v->pic_w, v->pic_h, &pw, &ph);
    ob_camera cam = current_camera(v);
    float radius = view_ao_radius(v);
    int spp = ref_spp_choices[R->spp_choice];
    if (R->have && same_camera(&cam, &R->cam) && R->radius == radius && R->spp == spp && R->ref_w == pw &&
        R->ref_h == ph)
        return;
    stop_job(R);
    const char *msg = "";
    if (!fit_renderer(v, R, pw, ph)) {
        ob_get_error(&msg);
        say(v, true, "reference view: no %dx%d renderer: %s", pw, ph, msg);
        return;
    }
    ref_job *j = calloc(1, sizeof *j);
    if (!j) {
        say(v, true, "reference view: out of memory");
        return;
    }
    /* The G-buffer of a `none` frame of this camera: the points the method's pane shows. */
    if (cli_view_frame_make(R->r, &cam, pw, ph, &j->frame) != 0) {
        ob_get_error(&msg); /* the message outlives the read in cli_view_frame_make */
        say(v, true, "reference view: no G-buffer for the reference: %s", msg);
        free(j);
        return;
    }
    size_t px = (size_t)pw * (size_t)ph;
    j->ao = malloc(px * sizeof(float));
    j->se = malloc(px * sizeof(float));
    if (!j->ao || !j->se) {
        job_free(j);
        say(v, true, "reference view: out of memory for %dx%d", pw, ph);
        return;
    }
    j->scene = v->scene;
    j->cam = cam;
    j->radius = radius;
    j->spp = spp;
    j->verbose = v->o.common.verbose;
    /* The camera's name "viewer": never the key of a compare run's named camera, whose reference
     * is traced in one call with other seeds. */
    cli_reference_key(&v->o.common, v->o.common.scene ? v->o.common.scene : ob_query_scene_name(v->scene), "viewer",
                      j->key, sizeof j->key);
    atomic_init(&j->permille, 0);
    atomic_init(&j->cancel, false);
    atomic_init(&j->finished, false);
    if (pthread_create(&R->thread, NULL, trace, j) != 0) {
        job_free(j);
        say(v, true, "reference view: no worker thread");
        return;
    }
    R->job = j;
    R->job_start = wall_seconds();
    say(v, false, "reference: AO_R of this camera at %dx%d, %d rays per pixel, R = %.4g (the cache or a trace)", pw, ph,
        spp, (double)radius);
}

/* A finished trace becomes the reference shown. */
static void poll_job(viewer *v, view_reference *R)
{
    ref_job *j = R->job;
    if (!j || !atomic_load(&j->finished)) return;
    pthread_join(R->thread, NULL);
    R->job = NULL;
    if (j->error[0]) {
        say(v, true, "reference view: %s", j->error);
        job_free(j);
        return;
    }
    size_t px = (size_t)j->frame.width * (size_t)j->frame.height;
    uint8_t *mask = malloc(px);
    if (!mask) {
        say(v, true, "reference view: out of memory");
        job_free(j);
        return;
    }
    for (size_t i = 0; i < px; ++i) mask[i] = j->frame.depth[i] > 0.0f;
    free(R->ref);
    free(R->mask);
    R->ref = j->ao;
    j->ao = NULL;
    R->mask = mask;
    R->cam = j->cam;
    R->radius = j->radius;
    R->spp = j->spp;
    R->ref_w = j->frame.width;
    R->ref_h = j->frame.height;
    R->have = true;
    R->cached = j->cached;
    R->seconds = j->seconds;
    R->stderr_mean = j->stderr_mean;
    R->measured = false;
    R->ref_uploaded = false;
    if (j->cached) say(v, false, "reference: from the cache (%dx%d, %d rays per pixel)", R->ref_w, R->ref_h, R->spp);
    else
        say(v, false, "reference: traced in %.1f s (%dx%d, %d rays per pixel, mean standard error %.4f)", j->seconds,
            R->ref_w, R->ref_h, R->spp, j->stderr_mean);
    job_free(j);
}

void view_reference_toggle(viewer *v)
{
    view_reference *R = state(v);
    if (!R) {
        say(v, true, "reference view: out of memory");
        return;
    }
    R->on = !R->on;
    if (R->on) {
        say(v, false, "reference view on");
        start(v, R);
    } else {
        stop_job(R);
        say(v, false, "reference view off");
    }
}

void view_reference_free(viewer *v)
{
    view_reference *R = v->ref;
    if (!R) return;
    stop_job(R);
    ob_destroy_renderer(R->r);
    if (R->fbo) glDeleteFramebuffers(1, &R->fbo);
    glDeleteTextures(3, R->tex);
    free(R->ref);
    free(R->mask);
    free(R->ao);
    free(R->depth);
    free(R->live_mask);
    free(R->bytes);
    free(R);
    v->ref = NULL;
}

/* ---- drawing ------------------------------------------------------------------------------- */
static uint8_t *scratch_bytes(view_reference *R, size_t n)
{
    if (n > R->bytes_cap) {
        uint8_t *b = realloc(R->bytes, n);
        if (!b) return NULL;
        R->bytes = b;
        R->bytes_cap = n;
    }
    return R->bytes;
}

/* Visibility as grey bytes, linear (as compare writes its AO images), rows as given; sky dark blue
 * (as compare's mask images), since open sky and open ground are both white otherwise and the
 * geometry's outline would be lost. */
static void grey(const float *ao, const uint8_t *geometry, size_t px, uint8_t *rgb)
{
    for (size_t i = 0; i < px; ++i) {
        uint8_t *p = rgb + 3 * i;
        if (!geometry[i]) {
            p[0] = 20;
            p[1] = 28;
            p[2] = 64;
            continue;
        }
        float a = ao[i] < 0.0f ? 0.0f : ao[i] > 1.0f ? 1.0f : ao[i];
        p[0] = p[1] = p[2] = (uint8_t)lrintf(a * 255.0f);
    }
}

static void upload(view_reference *R, int k, const uint8_t *rgb, int w, int h)
{
    if (!R->tex[k]) glGenTextures(1, &R->tex[k]);
    glBindTexture(GL_TEXTURE_2D, R->tex[k]);
    glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
    glTexImage2D(GL_TEXTURE_2D, 0, GL_RGB8, w, h, 0, GL_RGB, GL_UNSIGNED_BYTE, rgb);
    glPixelStorei(GL_UNPACK_ALIGNMENT, 4);
    glBindTexture(GL_TEXTURE_2D, 0);
    R->tex_w[k] = w;
    R->tex_h[k] = h;
}

/* Texture k (bottom row first) stretched over the window's rectangle x, y, w, h (GL's origin). */
static void blit(view_reference *R, int k, int x, int y, int w, int h)
{
    if (!R->tex[k]) return;
    if (!R->fbo) glGenFramebuffers(1, &R->fbo);
    glBindFramebuffer(GL_READ_FRAMEBUFFER, R->fbo);
    glFramebufferTexture2D(GL_READ_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, R->tex[k], 0);
    glBindFramebuffer(GL_DRAW_FRAMEBUFFER, 0);
    glBlitFramebuffer(0, 0, R->tex_w[k], R->tex_h[k], x, y, x + w, y + h, GL_COLOR_BUFFER_BIT, GL_LINEAR);
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
}

/* After a failure of the view's own (not a setting the renderer refuses): the view goes off and
 * this frame shows the background (view.c cleared the window); the next one is the normal view. */
static bool turn_off(view_reference *R)
{
    stop_job(R);
    R->on = false;
    return true;
}

bool view_reference_frame(viewer *v)
{
    view_reference *R = v->ref;
    poll_job(v, R);
    /* The picture's rectangle, GL's origin bottom left. */
    const int x = v->pic_x, y = v->fb_height - v->pic_y - v->pic_h, w = v->pic_w, h = v->pic_h;
    int pw = 0, ph = 0;
    pane_size(w, h, &pw, &ph);
    const char *msg = "";
    if (!fit_renderer(v, R, pw, ph)) {
        ob_get_error(&msg);
        say(v, true, "reference view: no %dx%d renderer, turned off: %s", pw, ph, msg);
        return turn_off(R);
    }
    ob_camera cam = current_camera(v);
    if (ob_render_frame(R->r, &cam, &v->s) != OB_OK) return false;
    size_t px = (size_t)pw * (size_t)ph;
    if (px > R->ao_cap) {
        float *a = realloc(R->ao, px * sizeof(float)), *d = a ? realloc(R->depth, px * sizeof(float)) : NULL;
        uint8_t *m = d ? realloc(R->live_mask, px) : NULL;
        if (a) R->ao = a;
        if (d) R->depth = d;
        if (m) R->live_mask = m;
        if (!m) {
            say(v, true, "reference view: out of memory, turned off");
            return turn_off(R);
        }
        R->ao_cap = px;
    }
    ob_read_image(R->r, OB_IMAGE_AO_F32, R->ao, px * sizeof(float));
    ob_read_image(R->r, OB_IMAGE_DEPTH_F32, R->depth, px * sizeof(float));
    for (size_t i = 0; i < px; ++i) R->live_mask[i] = R->depth[i] > 0.0f;
    bool was_fresh = R->fresh;
    R->fresh = R->have && same_camera(&cam, &R->cam) && R->radius == view_ao_radius(v) && R->ref_w == pw &&
               R->ref_h == ph;
    if (was_fresh && !R->fresh && !R->job)
        say(v, false, "reference: stale, the camera, R or the size changed (G twice: trace this camera)");
    uint8_t *rgb = scratch_bytes(R, px * 3);
    if (!rgb) {
        say(v, true, "reference view: out of memory, turned off");
        return turn_off(R);
    }
    grey(R->ao, R->live_mask, px, rgb);
    upload(R, 0, rgb, pw, ph);
    if (R->have && !R->ref_uploaded) {
        R->ref_uploaded = true;
        size_t rpx = (size_t)R->ref_w * (size_t)R->ref_h;
        uint8_t *rrgb = scratch_bytes(R, rpx * 3 > px * 3 ? rpx * 3 : px * 3);
        if (rrgb) {
            rgb = rrgb;
            grey(R->ref, R->mask, rpx, rgb);
            upload(R, 1, rgb, R->ref_w, R->ref_h);
        }
    }
    if (R->fresh) {
        /* Every frame: the method's pane is live, so a parameter changed in the panel moves the
         * RMSE at once. A stale reference keeps its last error pane and numbers, marked stale. */
        ob_metrics m;
        if (ob_compare_images(R->ao, R->ref, R->mask, pw, ph, 1, &m) == OB_OK) {
            R->m = m;
            R->measured = true;
        } else {
            ob_clear_error(); /* no geometry in view: nothing to measure */
            R->measured = false;
        }
        if (ob_error_heatmap(R->ao, R->ref, R->mask, pw, ph, false, REF_ERROR_RANGE, rgb) == OB_OK)
            upload(R, 2, rgb, pw, ph);
    }
    /* Panes in the picture's rectangle, GL's origin bottom left: method | reference over error |
     * view. Its background first: a pane not there yet (no reference) shows it. */
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    glViewport(0, 0, v->fb_width, v->fb_height);
    glEnable(GL_SCISSOR_TEST);
    glClearColor(0.08f, 0.08f, 0.09f, 1.0f);
    glScissor(x, y, w, h);
    glClear(GL_COLOR_BUFFER_BIT);
    glDisable(GL_SCISSOR_TEST);
    blit(R, 0, x, y + h - ph, pw, ph);
    if (R->have) blit(R, 1, x + pw, y + h - ph, pw, ph);
    if (R->have && R->tex[2]) blit(R, 2, x, y + h - 2 * ph, pw, ph);
    bool ok = ob_present(R->r, v->view, 0, x + pw, y + h - 2 * ph, pw, ph) == OB_OK;
    /* A 2 px seam between the panes: white open surfaces would otherwise run into each other. */
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    glEnable(GL_SCISSOR_TEST);
    glScissor(x + pw - 1, y, 2, h);
    glClear(GL_COLOR_BUFFER_BIT);
    glScissor(x, y + h - ph - 1, w, 2);
    glClear(GL_COLOR_BUFFER_BIT);
    glDisable(GL_SCISSOR_TEST);
    return ok;
}

/* ---- labels, overlay and panel ------------------------------------------------------------- */
static void progress_text(const view_reference *R, char *out, size_t n)
{
    int pm = atomic_load(&R->job->permille);
    snprintf(out, n, "tracing AO_R: %d %% (%.1f s)", pm / 10, wall_seconds() - R->job_start);
}

void view_reference_labels(viewer *v)
{
    view_reference *R = v->ref;
    if (!R || !R->on) return;
    int pw = 0, ph = 0;
    pane_size(v->pic_w, v->pic_h, &pw, &ph);
    /* At each pane's bottom left (window pixels from the top left): the overlay sits at the top. */
    const float gap = 4.0f, top = (float)(v->pic_y + ph) - gap, bottom = (float)(v->pic_y + 2 * ph) - gap,
                left = (float)v->pic_x + gap, right = (float)(v->pic_x + pw) + gap;
    gui_label(left, top, 1.0f, 1.0f, 1.0f, "method: %s, AO after the filter\ngraded at R = %.4g",
              ob_method_at(v->s.method)->name, (double)view_ao_radius(v));
    char text[160];
    if (R->job) {
        progress_text(R, text, sizeof text);
        gui_label(right, top, 1.0f, 0.85f, 0.4f, "%s", text);
    } else if (R->have && !R->fresh) {
        gui_label(right, top, 1.0f, 0.7f, 0.3f, "reference AO_R: stale (the camera, R or size changed)\nG twice or "
                  "the panel's button: trace this camera");
    } else if (R->have) {
        gui_label(right, top, 1.0f, 1.0f, 1.0f, "reference AO_R (Embree), %d rays per pixel%s\nR = %.4g, mean "
                  "standard error %.4f", R->spp, R->cached ? ", cached" : "", (double)R->radius, R->stderr_mean);
    } else {
        gui_label(right, top, 1.0f, 1.0f, 1.0f, "no reference");
    }
    if (R->measured && R->fresh)
        gui_label(left, bottom, 1.0f, 1.0f, 1.0f, "signed error: red = method brighter, blue = darker (+-%.1f)\n"
                  "RMSE %.4f  bias %+.4f  SSIM %.3f", (double)REF_ERROR_RANGE, R->m.rmse, R->m.bias, R->m.ssim);
    else if (R->measured)
        gui_label(left, bottom, 1.0f, 0.7f, 0.3f, "signed error (stale)\nRMSE %.4f", R->m.rmse);
    gui_label(right, bottom, 1.0f, 1.0f, 1.0f, "view: %s", ob_view_name(v->view));
}

bool view_reference_has_status(const viewer *v)
{
    const view_reference *R = v->ref;
    return R && (R->job || (R->on && R->measured));
}

void view_reference_overlay(const viewer *v)
{
    const view_reference *R = v->ref;
    if (!R) return;
    if (R->job) {
        char text[160];
        progress_text(R, text, sizeof text);
        gui_text_colored(1.0f, 0.85f, 0.4f, "reference: %s", text);
    } else if (R->on && R->measured) {
        gui_text("reference: RMSE %.4f%s", R->m.rmse, R->fresh ? "" : " (stale)");
    }
}

void panel_reference(viewer *v)
{
    view_reference *R = state(v);
    if (!R) return;
    bool on = R->on;
    if (gui_checkbox("reference view (G)", &on)) view_reference_toggle(v);
    gui_tooltip("the Embree ground truth AO_R of this camera beside the method's AO, their signed error and the "
                "current view, at half the picture each way; cached, so a camera traced before is instant");
    if (gui_combo("rays per pixel", &R->spp_choice, ref_spp_names, REF_SPP_COUNT) && R->on) start(v, R);
    gui_tooltip("512: compare's default, mean standard error under 0.01; fewer trace faster and noisier");
    if (R->on && !R->job && (!R->have || !R->fresh) && gui_button("trace this camera")) start(v, R);
    if (R->job) {
        char text[160];
        progress_text(R, text, sizeof text);
        gui_progress((float)atomic_load(&R->job->permille) / 1000.0f, text);
    }
    if (R->have) {
        gui_text("%dx%d, %d rays, R = %.4g: %s", R->ref_w, R->ref_h, R->spp, (double)R->radius,
                 R->cached ? "from the cache" : "traced");
        if (!R->cached) gui_text("%.1f s, mean standard error %.4f", R->seconds, R->stderr_mean);
    }
    if (R->measured) {
        if (!R->fresh) gui_text_colored(1.0f, 0.7f, 0.3f, "stale: the camera, R or size changed");
        static const char *const headers[] = {"RMSE", "MAE", "bias", "PSNR", "SSIM"};
        if (gui_begin_table("reference_metrics", 5, headers)) {
            gui_table_row();
            gui_table_cell("%.4f", R->m.rmse);
            gui_table_cell("%.4f", R->m.mae);
            gui_table_cell("%+.4f", R->m.bias);
            gui_table_cell("%.1f", R->m.psnr);
            gui_table_cell("%.3f", R->m.ssim);
            gui_end_table();
        }
        gui_tooltip("over the geometry pixels of the pane, method AO against AO_R (as compare measures)");
    }
}
