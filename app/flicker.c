/* Flicker metrics (issue 17): see flicker.h for what each number is. The reference along the path
 * is ray traced once per path frame from that frame's own G-buffer points (and cached like every
 * compare reference); the reprojection between frames is done here on the CPU from the G-buffer's
 * depth and each frame's camera, independently of the temporal pass it grades. */
#include "flicker.h"

#include <cglm/cglm.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cli.h"
#include "reference_cache.h"

/* A path frame: its G-buffer, camera and reference AO_R. */
typedef struct path_frame {
    cli_view_frame f;
    mat4 view;
    float *ref;
    bool empty; /* covers no pixel (only with --allow-empty): left out of every mean */
} path_frame;

/* Pixel centre (x, y) of frame a with linear depth d, as a world point. */
static void world_point(const path_frame *a, int x, int y, float d, vec3 out)
{
    const cli_view_frame *f = &a->f;
    float nx = ((float)x + 0.5f) / (float)f->width * 2.0f - 1.0f;
    float ny = ((float)y + 0.5f) / (float)f->height * 2.0f - 1.0f;
    vec4 v = {(nx + f->proj_info[2]) * d * f->proj_info[0], (ny + f->proj_info[3]) * d * f->proj_info[1], -d, 1.0f};
    vec4 w;
    glm_mat4_mulv((vec4 *)f->inv_view, v, w);
    glm_vec3_copy(w, out);
}

/* Mean |cur - prev reprojected| over the pixels of frame a (now) whose point frame b (before) saw:
 * the four depths of b around the reprojected point all within 2 % of the point's depth in b (an
 * edge or an occluder there leaves the pixel out). prev is bilinear between those four. NaN when
 * no pixel was seen in both: such a pair has no change to measure, and a 0 would pull the path's
 * mean toward "no flicker". */
static double warped_change(const path_frame *a, const path_frame *b, const float *cur, const float *prev)
{
    const int w = a->f.width, h = a->f.height;
    const float *pi = b->f.proj_info;
    double sum = 0.0;
    long count = 0;
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            const size_t i = (size_t)y * (size_t)w + (size_t)x;
            float d = a->f.depth[i];
            if (d <= 0.0f) continue;
            vec3 p;
            world_point(a, x, y, d, p);
            vec4 pw = {p[0], p[1], p[2], 1.0f}, v;
            glm_mat4_mulv((vec4 *)b->view, pw, v);
            float db = -v[2];
            if (db <= 0.0f) continue;
            /* ndc = (P00 X + P20 Z) / -Z with P00 = 1 / proj_info[0]. */
            float nx = (v[0] / pi[0] + pi[2] * v[2]) / db, ny = (v[1] / pi[1] + pi[3] * v[2]) / db;
            float qx = (nx * 0.5f + 0.5f) * (float)w - 0.5f, qy = (ny * 0.5f + 0.5f) * (float)h - 0.5f;
            int x0 = (int)floorf(qx), y0 = (int)floorf(qy);
            if (x0 < 0 || y0 < 0 || x0 + 1 >= w || y0 + 1 >= h) continue;
            float tx = qx - (float)x0, ty = qy - (float)y0;
            bool seen = true;
            double value = 0.0;
            for (int k = 0; k < 4 && seen; ++k) {
                size_t j = (size_t)(y0 + (k >> 1)) * (size_t)w + (size_t)(x0 + (k & 1));
                seen = fabsf(b->f.depth[j] - db) < 0.02f * db;
                value += (double)((k & 1) ? tx : 1.0f - tx) * ((k >> 1) ? ty : 1.0f - ty) * prev[j];
            }
            if (!seen) continue;
            sum += fabs((double)cur[i] - value);
            ++count;
        }
    return count ? sum / (double)count : NAN;
}

/* The path's mean of warped_change over the pairs that share pixels; NaN for none. */
typedef struct warped_mean {
    double sum;
    int pairs;
} warped_mean;

static void warped_add(warped_mean *m, double change)
{
    if (!isfinite(change)) return;
    m->sum += change;
    ++m->pairs;
}

static double warped_result(const warped_mean *m) { return m->pairs ? m->sum / (double)m->pairs : NAN; }

static double rmse(const float *ao, const float *ref, const float *depth, size_t px)
{
    double sum = 0.0;
    size_t count = 0;
    for (size_t i = 0; i < px; ++i)
        if (depth[i] > 0.0f) {
            double e = (double)ao[i] - (double)ref[i];
            sum += e * e;
            ++count;
        }
    return count ? sqrt(sum / (double)count) : NAN;
}

static double pass_ms(ob_renderer *r, const char *name)
{
    ob_pass_timing t[24];
    int n = ob_query_timings(r, t, 24);
    for (int p = 0; p < n; ++p)
        if (!strcmp(t[p].name, name)) return t[p].ms;
    return 0.0;
}

/* Frame t's reference into ref: AO_R at the pixel centres of its G-buffer (frame), or with
 * jitter J > 0 the mean of AO_R over the J jittered G-buffers the methods see (ob_jitter_offset's
 * points), each traced with spp / J rays (rounded up, 2 at least): the same rays per pixel, spread over the
 * footprint the accumulation averages (docs/temporal.md, "Jitter"). Sky stays 1 in each, as in
 * the methods' images. Each position is cached as a view of its own. */
static int path_reference(const cli_flicker_desc *d, const ob_camera *cam, const cli_view_frame *frame, int jitter,
                          float *ref, float *scratch)
{
    const cli_common *c = d->common;
    const int w = c->width, h = c->height;
    const size_t px = (size_t)w * (size_t)h;
    char key[900] = "";
    cli_reference_info info;
    if (jitter <= 0) {
        cli_reference_key(c, d->scene_key, cam->name, key, sizeof key);
        return cli_reference_ao(d->scene, frame, key, d->radius, d->spp, d->no_cache, c->verbose, ref, &info);
    }
    const int spp = (d->spp + jitter - 1) / jitter > 2 ? (d->spp + jitter - 1) / jitter : 2; /* the tracer's least */
    memset(ref, 0, px * sizeof(float));
    for (int k = 0; k < jitter; ++k) {
        float o[2];
        ob_jitter_offset(k, jitter, o);
        /* The lens shift moves the frustum as ob_settings.jitter moves the projection: P20 +=
         * 2 jx / width (ob_camera.shift is in half-widths). */
        ob_camera jc = *cam;
        jc.shift[0] += 2.0f * o[0] / (float)w;
        jc.shift[1] += 2.0f * o[1] / (float)h;
        snprintf(jc.name, sizeof jc.name, "%.48s j%d/%d", cam->name, k & 63, jitter & 127);
        cli_view_frame jf;
        int code = cli_view_frame_make(d->renderer, &jc, w, h, &jf);
        if (code != EXIT_OK) return code;
        jf.seed = (uint64_t)k + 1u; /* independent rays per position: one seed would repeat them */
        cli_reference_key(c, d->scene_key, jc.name, key, sizeof key);
        code = cli_reference_ao(d->scene, &jf, key, d->radius, spp, d->no_cache, c->verbose, scratch, &info);
        cli_view_frame_free(&jf);
        if (code != EXIT_OK) return code;
        for (size_t i = 0; i < px; ++i) ref[i] += scratch[i] / (float)jitter;
    }
    return EXIT_OK;
}

/* One variant of one combination: the path, then the still camera. */
static int run_variant(const cli_flicker_desc *d, const path_frame *frames, int count, const ob_settings *s,
                       cli_flicker_variant *out, float *cur, float *prev, double *mean, double *m2, double *ms)
{
    const cli_common *c = d->common;
    ob_renderer *r = d->renderer;
    const int w = c->width, h = c->height;
    const size_t px = (size_t)w * (size_t)h;
    memset(out, 0, sizeof *out);
    out->worst_ao = malloc(px * sizeof(float));
    out->rmse_frames = malloc((size_t)count * sizeof(double));
    if (!out->worst_ao || !out->rmse_frames) return cli_fail(EXIT_RUNTIME, "out of memory");
    ob_renderer_reset_history(r);
    warped_mean warped = {0};
    int seen = 0, still_frame = -1;
    for (int t = 0; t < count; ++t) {
        ob_camera cam;
        int code = cli_common_path_camera(c, d->scene, &d->base, t, &cam);
        if (code != EXIT_OK) return code;
        /* Every frame is rendered, empty or not: the history runs along the whole path. */
        if (ob_render_frame(r, &cam, s) != OB_OK) return cli_fail_from_library();
        ob_read_image(r, OB_IMAGE_AO_F32, cur, px * sizeof(float));
        ms[t] = pass_ms(r, "temporal");
        /* A frame that sees nothing has no error (NaN: null in results.json), and is in no mean,
         * worst or last: a 0 there would count as a perfect frame. */
        double e = frames[t].empty ? NAN : rmse(cur, frames[t].ref, frames[t].f.depth, px);
        out->rmse_frames[t] = e;
        if (!frames[t].empty) {
            out->rmse_mean += e;
            if (seen == 0 || e > out->rmse_worst) {
                out->rmse_worst = e;
                out->worst_frame = t;
                memcpy(out->worst_ao, cur, px * sizeof(float));
            }
            out->rmse_last = e; /* the last frame that sees something */
            if (still_frame < 0) still_frame = t;
            ++seen;
        }
        if (t > 0) warped_add(&warped, warped_change(&frames[t], &frames[t - 1], cur, prev));
        memcpy(prev, cur, px * sizeof(float));
    }
    out->frames_seen = seen;
    out->rmse_mean = seen ? out->rmse_mean / (double)seen : NAN;
    if (!seen) out->rmse_last = out->rmse_worst = NAN;
    out->warped = warped_result(&warped);
    out->temporal_ms = cli_median(ms, count);
    if (still_frame < 0) {
        out->static_noise = NAN;
        return EXIT_OK;
    }
    /* Still: warm-up of a history length (the on variant's history fills), then the measured frames
     * (Welford's running mean and sum of squares per pixel), at the first frame that sees
     * something (the path's first unless --allow-empty let an empty one through). */
    ob_renderer_reset_history(r);
    ob_camera still;
    int code = cli_common_path_camera(c, d->scene, &d->base, still_frame, &still);
    if (code != EXIT_OK) return code;
    const int warmup = s->temporal_frames > 0 ? s->temporal_frames : OB_TEMPORAL_FRAMES_DEFAULT;
    memset(mean, 0, px * sizeof(double));
    memset(m2, 0, px * sizeof(double));
    for (int f = 0; f < warmup + FLICKER_STILL_FRAMES; ++f) {
        if (ob_render_frame(r, &still, s) != OB_OK) return cli_fail_from_library();
        if (f < warmup) continue;
        ob_read_image(r, OB_IMAGE_AO_F32, cur, px * sizeof(float));
        const double n = (double)(f - warmup + 1);
        for (size_t i = 0; i < px; ++i) {
            double delta = (double)cur[i] - mean[i];
            mean[i] += delta / n;
            m2[i] += delta * ((double)cur[i] - mean[i]);
        }
    }
    double sum = 0.0;
    size_t geometry = 0;
    for (size_t i = 0; i < px; ++i)
        if (frames[still_frame].f.depth[i] > 0.0f) {
            sum += sqrt(m2[i] / (double)FLICKER_STILL_FRAMES);
            ++geometry;
        }
    out->static_noise = geometry ? sum / (double)geometry : NAN;
    return EXIT_OK;
}

int cli_flicker_run(const cli_flicker_desc *d, const cli_config *configs, int count, cli_flicker_row *rows,
                    cli_flicker_reference *ref)
{
    const cli_common *c = d->common;
    const int w = c->width, h = c->height, n = c->path_frames;
    const size_t px = (size_t)w * (size_t)h;
    const int jitter = cli_common_path_jitter(c);
    memset(rows, 0, (size_t)count * sizeof *rows);
    memset(ref, 0, sizeof *ref);
    path_frame *frames = calloc((size_t)n, sizeof *frames);
    float *cur = malloc(px * sizeof(float)), *prev = malloc(px * sizeof(float));
    double *mean = malloc(px * sizeof(double)), *m2 = malloc(px * sizeof(double)), *ms = malloc((size_t)n * sizeof(double));
    int code = EXIT_OK;
    warped_mean ref_warped = {0};
    if (!frames || !cur || !prev || !mean || !m2 || !ms) code = cli_fail(EXIT_RUNTIME, "out of memory");
    /* The path's G-buffers and references, once for every combination. */
    for (int t = 0; t < n && code == EXIT_OK; ++t) {
        ob_camera cam;
        if ((code = cli_common_path_camera(c, d->scene, &d->base, t, &cam)) != EXIT_OK) break;
        /* A name per path frame: the reference cache's key. The frame numbers first, so a long
         * path or camera name cut to fit the 64 bytes can never make two frames share a key. */
        if (c->path) snprintf(cam.name, sizeof cam.name, "%d/%d path %.32s", t, n, c->path);
        else snprintf(cam.name, sizeof cam.name, "%d/%d orbit %.6g %.16s", t, n, (double)c->orbit_deg, d->base.name);
        if ((code = cli_view_frame_make(d->renderer, &cam, w, h, &frames[t].f)) != EXIT_OK) break;
        size_t covered = 0;
        for (size_t i = 0; i < px; ++i) covered += frames[t].f.depth[i] > 0.0f;
        frames[t].empty = covered == 0;
        if (frames[t].empty && !c->allow_empty) {
            /* A path comes from the scene's sidecar (input); an orbit from the options. */
            code = c->path ? cli_fail(EXIT_INPUT, "--path %s: frame %d of %d sees nothing (it covers no pixel); check "
                                      "the path's keys (or --allow-empty to leave such frames out of the means)",
                                      c->path, t, n)
                           : cli_fail(EXIT_USAGE, "--orbit %g: frame %d of %d sees nothing (it covers no pixel); check "
                                      "the camera (or --allow-empty to leave such frames out of the means)",
                                      (double)c->orbit_deg, t, n);
            break;
        }
        if (frames[t].empty) ++ref->frames_empty;
        glm_lookat(frames[t].f.cam.eye, frames[t].f.cam.target, frames[t].f.cam.up, frames[t].view);
        frames[t].ref = malloc(px * sizeof(float));
        if (!frames[t].ref) {
            code = cli_fail(EXIT_RUNTIME, "out of memory");
            break;
        }
        code = path_reference(d, &cam, &frames[t].f, jitter, frames[t].ref, cur);
        if (code == EXIT_OK && t > 0) warped_add(&ref_warped, warped_change(&frames[t], &frames[t - 1], frames[t].ref, frames[t - 1].ref));
    }
    if (code == EXIT_OK && ref->frames_empty == n)
        code = cli_fail(c->path ? EXIT_INPUT : EXIT_USAGE, "%s: no frame of %d sees anything: nothing to grade",
                        c->path ? "--path" : "--orbit", n);
    if (code == EXIT_OK) {
        ref->frames = n;
        ref->jitter = jitter;
        ref->warped = warped_result(&ref_warped);
    }
    for (int k = 0; k < count && code == EXIT_OK; ++k) {
        rows[k].config = &configs[k];
        ob_settings s = configs[k].settings;
        s.temporal = true;
        s.jitter = jitter; /* both variants: the same jittered inputs, only the accumulation differs */
        if (s.temporal_frames <= 0) s.temporal_frames = OB_TEMPORAL_FRAMES_DEFAULT;
        code = run_variant(d, frames, n, &s, &rows[k].on, cur, prev, mean, m2, ms);
        /* Off: the same moving noise, a history of one frame (alpha = 1: nothing kept). */
        s.temporal_frames = 1;
        if (code == EXIT_OK) code = run_variant(d, frames, n, &s, &rows[k].off, cur, prev, mean, m2, ms);
        rows[k].off.temporal_ms = 0.0;
        /* No pair of frames that share pixels: NaN (null in results.json) carries through. */
        rows[k].on.warped_excess = rows[k].on.warped - ref->warped;
        rows[k].off.warped_excess = rows[k].off.warped - ref->warped;
        if (code == EXIT_OK) {
            const cli_flicker_variant *a = &rows[k].off, *b = &rows[k].on;
            printf("flicker %s: static noise %.4f -> %.4f (%.1fx), warped error %.4f -> %.4f (%.1fx; reference %.4f), "
                   "RMSE last %.4f -> %.4f, worst %.4f (frame %d) -> %.4f (frame %d), mean %.4f -> %.4f\n",
                   configs[k].label, a->static_noise, b->static_noise,
                   b->static_noise > 0.0 ? a->static_noise / b->static_noise : 0.0, a->warped, b->warped,
                   b->warped > 0.0 ? a->warped / b->warped : 0.0, ref->warped, a->rmse_last,
                   b->rmse_last, a->rmse_worst, a->worst_frame, b->rmse_worst, b->worst_frame, a->rmse_mean,
                   b->rmse_mean);
        }
    }
    for (int t = 0; frames && t < n; ++t) {
        cli_view_frame_free(&frames[t].f);
        free(frames[t].ref);
    }
    free(frames);
    free(cur);
    free(prev);
    free(mean);
    free(m2);
    free(ms);
    return code;
}

void cli_flicker_free(cli_flicker_row *rows, int count)
{
    for (int k = 0; rows && k < count; ++k) {
        free(rows[k].off.worst_ao);
        free(rows[k].on.worst_ao);
        free(rows[k].off.rmse_frames);
        free(rows[k].on.rmse_frames);
        rows[k].off.worst_ao = rows[k].on.worst_ao = NULL;
        rows[k].off.rmse_frames = rows[k].on.rmse_frames = NULL;
    }
}
