/* obscura bench --host: the host path beside the frame's AO chain (issue 45, item 7).
 * For each configuration, four paths measured in one run, alternated frame by frame (the frame,
 * then each host call on that frame's G-buffer), so that a machine that slows down or speeds up
 * (a core taken on the shared 2-core machine) slows all four alike:
 *   (a) frame            ob_render_frame; the sum of its AO chain passes (CHAIN_PASSES)
 *   (b) host_linear      ob_host_ao on the frame's G-buffer read back (ob_read_image) and uploaded as
 *                        R32F linear depth and RGBA16F view normals, into an R32F output: the chain
 *                        alone, no input or output pass (a directional method's output still
 *                        needs the output pass: the chain writes its M as RGB)
 *   (c) host_packed      the same depth as a GL_DEPTH_COMPONENT32F reversed-Z [0,1] depth buffer
 *                        (window depth computed here from the linear depth with the frame's near
 *                        and far planes) and octahedral RG16F world-space normals, into an R8
 *                        output: input pass + chain + output pass
 *   (d) host_no_normals  (c) without normals: the input pass rebuilds them from the depth
 * Each host path has its own renderer (its own temporal history and targets). --host-rmse adds the
 * accuracy of those inputs against the ray-traced reference, on views of other scenes.
 * bench_report.c prints and writes what this file measures. */
#include <epoxy/gl.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "bench.h"
#include "reference_cache.h"

const char *const host_path_names[HOST_PATHS] = {"frame", "host_linear", "host_packed", "host_no_normals"};
const char *const host_path_depth[HOST_PATHS] = {"G-buffer", "R32F linear", "D32F reversed-Z 0-to-1",
                                                 "D32F reversed-Z 0-to-1"};
const char *const host_path_normals[HOST_PATHS] = {"G-buffer", "RGBA16F view", "RG16F octahedral world",
                                                   "none (rebuilt from depth)"};
const char *const host_path_output[HOST_PATHS] = {"renderer's own", "R32F", "R8", "R8"};

/* The passes of the AO chain (src/core/chain.c) that (a) sums; a host call's other passes are its
 * input and output passes. */
static const char *const CHAIN_PASSES[] = {"downsample", "edges",    "depth_mips", "second_back",
                                           "ao",         "temporal", "filter",     "upsample"};

static bool is_chain_pass(const char *name)
{
    for (size_t i = 0; i < sizeof CHAIN_PASSES / sizeof CHAIN_PASSES[0]; ++i)
        if (!strcmp(name, CHAIN_PASSES[i])) return true;
    return false;
}

/* The GL calls bench makes itself to hand the frame's G-buffer over as an engine would (epoxy, as
 * the viewer's; the library's context is current on this thread). */
static unsigned host_texture(unsigned format, int width, int height)
{
    unsigned t = 0;
    glCreateTextures(GL_TEXTURE_2D, 1, &t);
    glTextureStorage2D(t, 1, format, width, height);
    return t;
}

/* A host's textures for one size: the inputs of (b), (c), (d), each path's output, and the CPU
 * copies they are filled from (bottom row first, as ob_read_image and GL both have them). */
typedef struct host_inputs {
    int w, h;
    unsigned depth, normal, window, oct, radiance, albedo, out[HOST_PATHS];
    float *lin, *nrm, *win, *oct_px, *rad, *alb;
    float view[16], proj[16], reversed[16];
} host_inputs;

static void host_inputs_free(host_inputs *in)
{
    if (in->depth) {
        const unsigned t[] = {in->depth, in->normal, in->window, in->oct, in->radiance, in->albedo,
                              in->out[HOST_LINEAR], in->out[HOST_PACKED], in->out[HOST_NO_NORMALS]};
        glDeleteTextures((int)(sizeof t / sizeof t[0]), t);
    }
    free(in->lin);
    free(in->nrm);
    free(in->win);
    free(in->oct_px);
    free(in->rad);
    free(in->alb);
    memset(in, 0, sizeof *in);
}

static int host_inputs_make(host_inputs *in, int w, int h)
{
    memset(in, 0, sizeof *in);
    const size_t px = (size_t)w * (size_t)h;
    in->w = w;
    in->h = h;
    in->lin = malloc(px * sizeof(float));
    in->nrm = malloc(3 * px * sizeof(float));
    in->win = malloc(px * sizeof(float));
    in->oct_px = malloc(2 * px * sizeof(float));
    in->rad = malloc(3 * px * sizeof(float));
    in->alb = malloc(3 * px * sizeof(float));
    if (!in->lin || !in->nrm || !in->win || !in->oct_px || !in->rad || !in->alb) {
        host_inputs_free(in);
        return cli_fail(EXIT_RUNTIME, "out of memory");
    }
    in->depth = host_texture(GL_R32F, w, h);
    in->normal = host_texture(GL_RGBA16F, w, h);
    in->window = host_texture(GL_DEPTH_COMPONENT32F, w, h);
    in->oct = host_texture(GL_RG16F, w, h);
    in->radiance = host_texture(GL_RGBA16F, w, h);
    in->albedo = host_texture(GL_RGBA16F, w, h);
    in->out[HOST_LINEAR] = host_texture(GL_R32F, w, h);
    in->out[HOST_PACKED] = host_texture(GL_R8, w, h);
    in->out[HOST_NO_NORMALS] = host_texture(GL_R8, w, h);
    unsigned e = glGetError();
    if (e != 0) {
        host_inputs_free(in);
        return cli_fail(EXIT_RUNTIME, "--host: OpenGL error 0x%x making the host's %dx%d textures", e, w, h);
    }
    return EXIT_OK;
}

/* The camera's matrices as ob_render_frame makes them (src/core/frame.c): the renderer's defaults
 * filled in, near and far fitted to the scene's bounds as ob_camera_fit_planes does (and left in
 * *cam, so the frame uses the very planes the window depth is computed with), glm_lookat,
 * glm_perspective, the lens shift in P20 and P21; and the same projection reversed-Z with
 * glClipControl's [0, 1] range: window depth = n (f - d) / (d (f - n)), 1 at the near plane. */
static int host_matrices(const ob_scene *scene, ob_camera *cam, int w, int h, host_inputs *in)
{
    const ob_scene_stats st = ob_query_scene_stats(scene);
    if (ob_camera_matrices(cam, st.bounds_min, st.bounds_max, w, h, in->view, in->proj) != OB_OK)
        return cli_fail_from_library_in("--host: the camera");
    memcpy(in->reversed, in->proj, sizeof in->reversed);
    const double n = cam->near_z, f = cam->far_z;
    in->reversed[10] = (float)(n / (f - n));
    in->reversed[14] = (float)(f * n / (f - n));
    return EXIT_OK;
}

/* in->lin and in->nrm (and in->rad, in->alb with rgb) hold a G-buffer: the packed copies made
 * from them and everything uploaded. */
static void host_upload(host_inputs *in, bool rgb)
{
    const size_t px = (size_t)in->w * (size_t)in->h;
    const float *v = in->view, *p = in->reversed;
    for (size_t i = 0; i < px; ++i) {
        const double d = in->lin[i];
        /* ndc = -P22 + P32 / d; the far plane's 0 is sky. */
        in->win[i] = d > 0.0 ? (float)(-(double)p[10] + (double)p[14] / d) : 0.0f;
        /* World normal = the view's rotation transposed times the view normal (a rigid view). */
        const float *nv = in->nrm + 3 * i;
        float w[3];
        for (int r = 0; r < 3; ++r) w[r] = v[4 * r + 0] * nv[0] + v[4 * r + 1] * nv[1] + v[4 * r + 2] * nv[2];
        float l1 = fabsf(w[0]) + fabsf(w[1]) + fabsf(w[2]);
        float ex = l1 > 0.0f ? w[0] / l1 : 0.0f, ey = l1 > 0.0f ? w[1] / l1 : 0.0f;
        if (w[2] < 0.0f) { /* octahedral (Cigolle et al. 2014): the lower half folded over */
            float tx = (1.0f - fabsf(ey)) * (ex >= 0.0f ? 1.0f : -1.0f);
            float ty = (1.0f - fabsf(ex)) * (ey >= 0.0f ? 1.0f : -1.0f);
            ex = tx;
            ey = ty;
        }
        in->oct_px[2 * i] = ex;
        in->oct_px[2 * i + 1] = ey;
    }
    glTextureSubImage2D(in->depth, 0, 0, 0, in->w, in->h, GL_RED, GL_FLOAT, in->lin);
    glTextureSubImage2D(in->normal, 0, 0, 0, in->w, in->h, GL_RGB, GL_FLOAT, in->nrm);
    glTextureSubImage2D(in->window, 0, 0, 0, in->w, in->h, GL_DEPTH_COMPONENT, GL_FLOAT, in->win);
    glTextureSubImage2D(in->oct, 0, 0, 0, in->w, in->h, GL_RG, GL_FLOAT, in->oct_px);
    if (rgb) {
        glTextureSubImage2D(in->radiance, 0, 0, 0, in->w, in->h, GL_RGB, GL_FLOAT, in->rad);
        glTextureSubImage2D(in->albedo, 0, 0, 0, in->w, in->h, GL_RGB, GL_FLOAT, in->alb);
    }
}

/* The frame r just rendered, read back and uploaded. */
static int host_grab(ob_renderer *r, host_inputs *in, bool rgb)
{
    const size_t px = (size_t)in->w * (size_t)in->h;
    if (ob_read_image(r, OB_IMAGE_DEPTH_F32, in->lin, px * sizeof(float)) != OB_OK ||
        ob_read_image(r, OB_IMAGE_NORMAL_F32, in->nrm, 3 * px * sizeof(float)) != OB_OK ||
        (rgb && (ob_read_image(r, OB_IMAGE_RADIANCE_F32, in->rad, 3 * px * sizeof(float)) != OB_OK ||
                 ob_read_image(r, OB_IMAGE_ALBEDO_F32, in->alb, 3 * px * sizeof(float)) != OB_OK)))
        return cli_fail_from_library();
    host_upload(in, rgb);
    return EXIT_OK;
}

/* The host path calls no glGetError (obscura.h: a host's pending error stays the host's): bench,
 * the host here, reads it after each call, so that a call that went wrong in GL is not timed. */
static int host_gl_check(int p)
{
    unsigned e = glGetError();
    if (e == 0) return EXIT_OK;
    return cli_fail(EXIT_RUNTIME, "--host: OpenGL error 0x%x after ob_host_ao (%s)", e, host_path_names[p]);
}

/* Path p's frame and outputs over in's textures. */
static void host_call_args(const host_inputs *in, int p, bool rgb, ob_host_frame *f, ob_host_outputs *out)
{
    memset(f, 0, sizeof *f);
    memset(out, 0, sizeof *out);
    f->depth = p == HOST_LINEAR ? in->depth : in->window;
    f->normal = p == HOST_LINEAR ? in->normal : p == HOST_PACKED ? in->oct : 0;
    f->normal_space = p == HOST_PACKED ? OB_NORMALS_WORLD : OB_NORMALS_VIEW;
    f->depth_zero_to_one = p != HOST_LINEAR;
    memcpy(f->projection, p == HOST_LINEAR ? in->proj : in->reversed, sizeof f->projection);
    memcpy(f->view, in->view, sizeof f->view);
    if (rgb) {
        f->radiance = in->radiance;
        f->albedo = in->albedo;
    }
    out->ao = in->out[p];
}

/* The settings a host passes for the frame's: the same, with the scene's lights named (a host has
 * no scene; the indirect-light methods read them) and the radius the frame took from the scene
 * when the configuration left it to the scene. */
static int host_settings_of(const ob_settings *s, const ob_scene *scene, float scene_radius, ob_settings *hs)
{
    *hs = *s;
    if (hs->light_count == 0) {
        int n = ob_query_scene_light_count(scene);
        hs->light_count = n < OB_MAX_LIGHTS ? n : OB_MAX_LIGHTS;
        for (int i = 0; i < hs->light_count; ++i) hs->lights[i] = ob_query_scene_light(scene, i);
    }
    const ob_method_info *m = ob_method_at(hs->method);
    for (int i = 0; i < m->param_count; ++i)
        if (!strcmp(m->params[i].name, "radius") && !((hs->params_set >> i) & 1u)) {
            char set[64];
            snprintf(set, sizeof set, "radius=%.9g", (double)scene_radius);
            if (ob_settings_set(hs, set) != OB_OK) return cli_fail_from_library();
        }
    return EXIT_OK;
}

/* Per path: MAX_PASSES pass columns of `frames`, then chain, input, output, total, ratio. */
enum { HOST_COL_CHAIN = MAX_PASSES, HOST_COL_INPUT, HOST_COL_OUTPUT, HOST_COL_TOTAL, HOST_COL_RATIO, HOST_COL_CALL, HOST_COLS };

/* Path p's timings of frame m (its renderer's last frame, waited for). (a) keeps its chain passes. */
static int host_record(ob_renderer *r, int p, host_path_row *row, double *v, int frames, int m)
{
    if (ob_wait_timings(r) != OB_OK) return cli_fail_from_library();
    ob_pass_timing t[MAX_PASSES];
    int n = ob_query_timings(r, t, MAX_PASSES);
    for (int c = 0; c < HOST_COLS; ++c) v[(size_t)c * (size_t)frames + (size_t)m] = 0.0;
    for (int q = 0; q < n; ++q) {
        const bool chain = is_chain_pass(t[q].name), input = !strcmp(t[q].name, "input"),
                   output = !strcmp(t[q].name, "output");
        if (p == HOST_FRAME && !chain) continue;
        int k = 0;
        while (k < row->pass_count && strcmp(row->pass[k], t[q].name)) ++k;
        if (k == row->pass_count) {
            if (k == MAX_PASSES) continue;
            snprintf(row->pass[row->pass_count++], sizeof row->pass[0], "%s", t[q].name);
        }
        v[(size_t)k * (size_t)frames + (size_t)m] += t[q].ms;
        int col = chain ? HOST_COL_CHAIN : input ? HOST_COL_INPUT : output ? HOST_COL_OUTPUT : -1;
        if (col >= 0) v[(size_t)col * (size_t)frames + (size_t)m] += t[q].ms;
        v[(size_t)HOST_COL_TOTAL * (size_t)frames + (size_t)m] += t[q].ms;
        row->has_input = row->has_input || input;
        row->has_output = row->has_output || output;
    }
    return EXIT_OK;
}

/* Warm-up, then o->frames measured frames, each: the frame on eyes[0], its G-buffer handed to each
 * host path's renderer. scratch: HOST_PATHS x HOST_COLS x frames. */
static int host_measure(ob_renderer **rs, const ob_camera *base, const ob_scene *scene, const ob_settings *s,
                        const ob_settings *hs, const bench_opts *o, host_inputs *in, double *scratch, host_row *row)
{
    const int frames = o->frames;
    const bool rgb = ob_method_at(s->method)->directional;
    for (int p = 0; p < HOST_PATHS; ++p) ob_renderer_reset_history(rs[p]);
    for (int f = 0; f < o->warmup + frames; ++f) {
        const bool measured = f >= o->warmup;
        const int m = f - o->warmup;
        ob_camera cam = *base;
        if (o->moving_scene) {
            int code = cli_common_path_camera(&o->common, o->moving_scene, base, f % o->common.path_frames, &cam);
            if (code != EXIT_OK) return code;
        }
        int code = host_matrices(scene, &cam, in->w, in->h, in);
        if (code != EXIT_OK) return code;
        double t0 = bench_now_s();
        if (ob_render_frame(rs[HOST_FRAME], &cam, s) != OB_OK) return cli_fail_from_library();
        double call_ms = 1e3 * (bench_now_s() - t0);
        if (measured) code = host_record(rs[HOST_FRAME], HOST_FRAME, &row->path[HOST_FRAME], scratch, frames, m);
        if (measured) scratch[(size_t)HOST_COL_CALL * (size_t)frames + (size_t)m] = call_ms;
        if (code == EXIT_OK) code = host_grab(rs[HOST_FRAME], in, rgb);
        for (int p = HOST_LINEAR; p < HOST_PATHS && code == EXIT_OK; ++p) {
            ob_host_frame hf;
            ob_host_outputs ho;
            host_call_args(in, p, rgb, &hf, &ho);
            t0 = bench_now_s();
            if (ob_host_ao(rs[p], &hf, hs, &ho) != OB_OK) return cli_fail_from_library();
            call_ms = 1e3 * (bench_now_s() - t0);
            if ((code = host_gl_check(p)) != EXIT_OK) return code;
            double *v = scratch + (size_t)p * HOST_COLS * (size_t)frames;
            if (measured) code = host_record(rs[p], p, &row->path[p], v, frames, m);
            if (measured) v[(size_t)HOST_COL_CALL * (size_t)frames + (size_t)m] = call_ms;
        }
        if (code != EXIT_OK) return code;
        if (!measured) continue;
        const double base_ms = scratch[(size_t)HOST_COL_TOTAL * (size_t)frames + (size_t)m];
        for (int p = 0; p < HOST_PATHS; ++p) {
            double *v = scratch + (size_t)p * HOST_COLS * (size_t)frames;
            v[(size_t)HOST_COL_RATIO * (size_t)frames + (size_t)m] =
                base_ms > 0.0 ? v[(size_t)HOST_COL_TOTAL * (size_t)frames + (size_t)m] / base_ms : 0.0;
        }
    }
    for (int p = 0; p < HOST_PATHS; ++p) {
        host_path_row *pr = &row->path[p];
        double *v = scratch + (size_t)p * HOST_COLS * (size_t)frames;
        for (int k = 0; k < pr->pass_count; ++k) bench_stats(v + (size_t)k * (size_t)frames, frames, &pr->med[k], &pr->min[k], &pr->max[k]);
        double *cols[6] = {pr->chain, pr->input, pr->output, pr->total, pr->ratio, pr->call};
        for (int c = 0; c < 6; ++c)
            bench_stats(v + (size_t)(HOST_COL_CHAIN + c) * (size_t)frames, frames, &cols[c][0], &cols[c][1], &cols[c][2]);
    }
    return EXIT_OK;
}

/* --host-rmse's list: SCENE[:CAMERA] elements, checked for shape while parsing (the scenes and
 * cameras themselves when they are loaded, before anything is timed). */
int bench_host_views_check(const char *v)
{
    if (!*v) return cli_fail(EXIT_USAGE, "--host-rmse: expected a comma list of SCENE[:CAMERA], got ''");
    if (strlen(v) >= 1024) return cli_fail(EXIT_USAGE, "--host-rmse: %zu bytes; at most 1023", strlen(v));
    int n = 1;
    for (const char *p = v; *p; ++p) n += *p == ',';
    if (n > HOST_MAX_VIEWS) return cli_fail(EXIT_USAGE, "--host-rmse: %d views; at most %d", n, HOST_MAX_VIEWS);
    for (const char *p = v;;) {
        const char *end = strchr(p, ',');
        size_t len = end ? (size_t)(end - p) : strlen(p);
        if (len == 0 || (len == 1 && *p == ':') || p[0] == ':' || p[len - 1] == ':')
            return cli_fail(EXIT_USAGE, "--host-rmse: empty scene or camera in '%s'", v);
        if (!end) break;
        p = end + 1;
    }
    return EXIT_OK;
}

static host_acc_row *new_acc_row(host_state *hst)
{
    void *acc = hst->acc;
    host_acc_row *a = bench_grow(&acc, &hst->acc_count, &hst->acc_cap, sizeof *a);
    hst->acc = acc;
    return a;
}

/* One --host-rmse view as the grading sees it: its G-buffer (also uploaded as each host path's
 * inputs) and AO_R. */
typedef struct host_rmse_frame {
    char name[256];        /* the scene as the list names it */
    ob_scene *scene;
    ob_camera cam;
    cli_view_frame vf;
    float *ref, *ao;
    uint8_t *mask;
    float radius;
    cli_reference_info info;
} host_rmse_frame;

static void host_rmse_frame_free(host_rmse_frame *v)
{
    cli_view_frame_free(&v->vf);
    free(v->ref);
    free(v->ao);
    free(v->mask);
    ob_destroy_scene(v->scene);
}

/* The view's scene and camera, its G-buffer from fr and its AO_R (the reference cache compare and
 * tune use, at compare's size and rays), and the G-buffer uploaded for the host paths (with the
 * direct light and albedo when a method reads them). */
static int host_rmse_frame_make(const bench_opts *o, const char *spec, ob_renderer *fr, host_inputs *in, bool rgb,
                                host_rmse_frame *v)
{
    const cli_common *c = &o->common;
    const int w = HOST_RMSE_W, h = HOST_RMSE_H;
    const size_t px = (size_t)w * (size_t)h;
    snprintf(v->name, sizeof v->name, "%s", spec);
    const char *camera = NULL;
    char *colon = strrchr(v->name, ':');
    if (colon && !strchr(colon, '/')) {
        *colon = '\0';
        camera = colon + 1;
    }
    int code = cli_common_load_scene(c, v->name, &v->scene);
    if (code == EXIT_OK) code = cli_common_camera(c, v->scene, camera, &v->cam);
    if (code == EXIT_OK && ob_renderer_set_scene(fr, v->scene) != OB_OK) code = cli_fail_from_library();
    if (code == EXIT_OK) code = cli_common_prepare(c, fr);
    if (code == EXIT_OK) code = cli_view_frame_make(fr, &v->cam, w, h, &v->vf);
    if (code == EXIT_OK)
        code = cli_check_visible(fr, w, h, ob_query_scene_name(v->scene), v->cam.name, c->allow_empty, EXIT_USAGE);
    v->ref = malloc(px * sizeof(float));
    v->ao = malloc(px * sizeof(float));
    v->mask = malloc(px);
    if (code == EXIT_OK && (!v->ref || !v->ao || !v->mask)) code = cli_fail(EXIT_RUNTIME, "out of memory");
    v->radius = v->scene ? ob_query_scene_ao_radius(v->scene) : 0.0f;
    if (code == EXIT_OK) {
        char key[900] = "";
        cli_reference_key(c, v->name, v->cam.name, key, sizeof key);
        code = cli_reference_ao(v->scene, &v->vf, key, v->radius, HOST_RMSE_SPP, false, c->verbose, v->ref, &v->info);
    }
    if (code != EXIT_OK) return code;
    for (size_t i = 0; i < px; ++i) v->mask[i] = v->vf.depth[i] > 0.0f;
    memcpy(in->lin, v->vf.depth, px * sizeof(float));
    memcpy(in->nrm, v->vf.normals, 3 * px * sizeof(float));
    /* The direct light and albedo of the same (none) frame, for the indirect-light methods. */
    if (rgb && (ob_read_image(fr, OB_IMAGE_RADIANCE_F32, in->rad, 3 * px * sizeof(float)) != OB_OK ||
                ob_read_image(fr, OB_IMAGE_ALBEDO_F32, in->alb, 3 * px * sizeof(float)) != OB_OK))
        return cli_fail_from_library();
    v->cam = v->vf.cam;
    code = host_matrices(v->scene, &v->cam, w, h, in);
    if (code == EXIT_OK) host_upload(in, rgb);
    return code;
}

/* Configuration k on the view: the frame's AO and each host path's after HOST_RMSE_FRAMES calls
 * (compare's frames per row), against AO_R over the geometry pixels, into a new accuracy row. */
static int host_rmse_grade(const bench_opts *o, const host_rmse_frame *v, ob_renderer *fr, ob_renderer *hr,
                           const host_inputs *in, const bench_plan *p, int k, host_state *hst)
{
    const int w = HOST_RMSE_W, h = HOST_RMSE_H;
    const size_t px = (size_t)w * (size_t)h;
    ob_settings s, hs;
    const int n = o->samples_given && p->has_samples[k] ? o->samples[0] : 0;
    int code = bench_configure(&p->configs[k], n, p->has_radius[k] ? v->radius : 0.0f, &s);
    if (code == EXIT_OK) code = host_settings_of(&s, v->scene, v->radius, &hs);
    if (code != EXIT_OK) return code;
    const bool directional = ob_method_at(s.method)->directional;
    host_acc_row *a = new_acc_row(hst);
    if (!a) return cli_fail(EXIT_RUNTIME, "out of memory");
    snprintf(a->scene, sizeof a->scene, "%s", v->name);
    snprintf(a->camera, sizeof a->camera, "%s", v->cam.name);
    a->cfg = &p->configs[k];
    a->samples = n;
    a->radius = v->radius;
    a->ref_cached = v->info.cached;
    a->ref_stderr = v->info.stderr_mean;
    for (int q = 0; q < HOST_PATHS && code == EXIT_OK; ++q) {
        ob_renderer *r = q == HOST_FRAME ? fr : hr;
        ob_renderer_reset_history(r);
        for (int f = 0; f < HOST_RMSE_FRAMES && code == EXIT_OK; ++f) {
            if (q == HOST_FRAME) {
                if (ob_render_frame(fr, &v->cam, &s) != OB_OK) code = cli_fail_from_library();
                continue;
            }
            ob_host_frame hf;
            ob_host_outputs ho;
            host_call_args(in, q, directional, &hf, &ho);
            if (ob_host_ao(hr, &hf, &hs, &ho) != OB_OK) code = cli_fail_from_library();
            else code = host_gl_check(q);
        }
        if (code != EXIT_OK) break;
        if (q == HOST_FRAME) {
            if (ob_read_image(fr, OB_IMAGE_AO_F32, v->ao, px * sizeof(float)) != OB_OK) code = cli_fail_from_library();
        } else {
            glGetTextureImage(in->out[q], 0, GL_RED, GL_FLOAT, (int)(px * sizeof(float)), v->ao);
        }
        if (code == EXIT_OK && ob_compare_images(v->ao, v->ref, v->mask, w, h, 1, &a->m[q]) != OB_OK)
            code = cli_fail_from_library();
    }
    return code;
}

/* One view of --host-rmse: its G-buffer and AO_R, then every configuration graded on it. */
static int host_rmse_view(const bench_opts *o, const char *spec, ob_renderer *fr, ob_renderer *hr, host_inputs *in,
                          const bench_plan *p, host_state *hst)
{
    bool rgb = false;
    for (int k = 0; k < p->count; ++k) rgb = rgb || ob_method_at(p->configs[k].method)->directional;
    host_rmse_frame v = {0};
    int code = host_rmse_frame_make(o, spec, fr, in, rgb, &v);
    for (int k = 0; k < p->count && code == EXIT_OK; ++k) code = host_rmse_grade(o, &v, fr, hr, in, p, k, hst);
    host_rmse_frame_free(&v);
    return code;
}

/* Every --host-rmse view, before anything is timed (a bad scene or camera fails first). */
int bench_host_rmse(const bench_opts *o, ob_context *ctx, const bench_plan *p, host_state *hst)
{
    ob_renderer *fr = ob_make_renderer(ctx, &(ob_renderer_desc){.width = HOST_RMSE_W, .height = HOST_RMSE_H});
    ob_renderer *hr = ob_make_renderer(ctx, &(ob_renderer_desc){.width = HOST_RMSE_W, .height = HOST_RMSE_H});
    host_inputs in = {0};
    int code = fr && hr ? host_inputs_make(&in, HOST_RMSE_W, HOST_RMSE_H) : cli_fail_from_library();
    char list[1024];
    snprintf(list, sizeof list, "%s", o->host_views);
    char *save = NULL;
    for (char *t = strtok_r(list, ",", &save); t && code == EXIT_OK; t = strtok_r(NULL, ",", &save))
        code = host_rmse_view(o, t, fr, hr, &in, p, hst);
    host_inputs_free(&in);
    ob_destroy_renderer(fr);
    ob_destroy_renderer(hr);
    return code;
}

static host_row *new_host_row(host_state *hst)
{
    void *rows = hst->rows;
    host_row *r = bench_grow(&rows, &hst->count, &hst->cap, sizeof *r);
    hst->rows = rows;
    return r;
}

/* One camera's configurations (the sweep's N and r each), host_measure each. */
static int host_camera(const bench_opts *o, ob_renderer **rs, const ob_scene *scene, int camera, const bench_plan *p,
                       host_inputs *in, double *scratch, bench_state *st, host_state *hst)
{
    const cli_common *c = &o->common;
    const float suggested = ob_query_scene_ao_radius(scene);
    const ob_camera cam = ob_query_camera(scene, camera);
    int code = EXIT_OK;
    for (int k = 0; k < p->count && code == EXIT_OK; ++k) {
        const int nn = p->has_samples[k] ? o->sample_count : 1, rn = p->has_radius[k] ? o->radius_count : 1;
        for (int j = 0; j < nn && code == EXIT_OK; ++j)
            for (int q = 0; q < rn && code == EXIT_OK; ++q) {
                const int n = p->has_samples[k] ? o->samples[j] : 0;
                const float r = p->has_radius[k] ? o->radii[q] : 0.0f, rw = r * suggested / 4.0f;
                ob_settings s, hs;
                if ((code = bench_configure(&p->configs[k], n, rw, &s)) != EXIT_OK) break;
                if ((code = host_settings_of(&s, scene, suggested, &hs)) != EXIT_OK) break;
                host_row *row = new_host_row(hst);
                if (!row) return cli_fail(EXIT_RUNTIME, "out of memory");
                *row = (host_row){.camera = camera, .cfg = &p->configs[k], .samples = n, .r = r, .radius_world = rw,
                                  .width = c->width, .height = c->height};
                code = host_measure(rs, &cam, scene, &s, &hs, o, in, scratch, row);
                /* Once per camera: timing an empty frame times nothing. */
                if (code == EXIT_OK && k == 0 && j == 0 && q == 0)
                    code = cli_check_visible(rs[HOST_FRAME], c->width, c->height, ob_query_scene_name(scene), cam.name,
                                             c->allow_empty, EXIT_INPUT);
                char what[512] = "";
                snprintf(what, sizeof what, "%s %s N=%d r=%g", cam.name, p->configs[k].label, n, (double)r);
                if (code == EXIT_OK) bench_progress(st, what);
            }
    }
    return code;
}

/* The timing run: a renderer per path, then every camera's configurations. */
int bench_host_run(const bench_opts *o, ob_context *ctx, const ob_scene *scene, const int *cams, int cam_count,
                   const bench_plan *p, bench_state *st, host_state *hst)
{
    const cli_common *c = &o->common;
    ob_renderer *rs[HOST_PATHS] = {NULL, NULL, NULL, NULL};
    host_inputs in = {0};
    double *scratch = calloc((size_t)HOST_PATHS * HOST_COLS * (size_t)o->frames, sizeof(double));
    int code = scratch ? EXIT_OK : cli_fail(EXIT_RUNTIME, "out of memory");
    for (int q = 0; q < HOST_PATHS && code == EXIT_OK; ++q) {
        rs[q] = ob_make_renderer(ctx, &(ob_renderer_desc){.width = c->width, .height = c->height});
        if (!rs[q]) code = cli_fail_from_library();
    }
    if (code == EXIT_OK && ob_renderer_set_scene(rs[HOST_FRAME], scene) != OB_OK) code = cli_fail_from_library();
    if (code == EXIT_OK) code = cli_common_prepare(c, rs[HOST_FRAME]);
    if (code == EXIT_OK) code = host_inputs_make(&in, c->width, c->height);
    int per_cam = 0;
    for (int k = 0; k < p->count; ++k)
        per_cam += (p->has_samples[k] ? o->sample_count : 1) * (p->has_radius[k] ? o->radius_count : 1);
    st->total = per_cam * cam_count;
    if (code == EXIT_OK) ob_progress_begin(&st->bar, "bench --host", st->total);
    for (int ci = 0; ci < cam_count && code == EXIT_OK; ++ci)
        code = host_camera(o, rs, scene, cams[ci], p, &in, scratch, st, hst);
    host_inputs_free(&in);
    for (int q = 0; q < HOST_PATHS; ++q) ob_destroy_renderer(rs[q]);
    free(scratch);
    return code;
}
