/* The host path under an orthographic projection (issue 45: "a depth buffer with its projection,
 * perspective or orthographic"). The host's scene (host_scene.h: a sphere on a floor against a
 * wall, a box in the corner) is ray-cast on the CPU through an off-centre orthographic camera, a
 * 50-degree perspective camera from the same eye at the same target, and perspective cameras of
 * 5, 2 and 1 degrees framing the same height at the target from farther back along the same line
 * (the orthographic camera is their limit). Each G-buffer goes through ob_host_ao, and its AO is
 * graded against the ray-traced AO_R of its own G-buffer points (ob_reference_ao on the same
 * geometry, written out as an OBJ): for vbao, gtao and ssao, raw and through crease, at AO scale
 * 1/2 and 1/4, with a second depth layer and with the guard band, the orthographic RMSE must be
 * comparable to the 50-degree one and lie among the narrow ones (the bounds and their reasons at
 * "The bounds" below); for vbao and gtao it must also be far below the RMSE of the perspective
 * reconstruction of the same orthographic G-buffer. Then: a D32F depth buffer (standard [-1, 1],
 * reversed [0, 1]) gives the AO of R32F linear depth within its quantisation; every method with
 * every filter (and the programs their switches pick) grades as the perspective views do; the
 * jitter moves P30 and P31 as documented (the call with a jitter is the call with the jittered
 * matrix, bit for bit, and a still camera's temporal reprojection takes the jitter's change out);
 * temporal accumulation under a sideways pan reprojects every point by exactly the pan's pixels
 * and keeps every history; the projections that are orthographic but not takeable are refused.
 * With the shaders' camera forced to perspective (frame.c's `orthographic` 0) the bounds fail for
 * every graded row, ssao's too, 148 of the sweep's 171 combinations and every reprojection check:
 * 183 failures on llvmpipe. */
#define _POSIX_C_SOURCE 200809L /* mkdtemp */
#include <epoxy/egl.h>
#include <epoxy/gl.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "check.h"
#include "host_scene.h"
#include "obscura/eval.h"

enum { W = 128, H = 96 };
#define NPX ((size_t)W * (size_t)H)
#define RADIUS 1.0f /* R in the scene's units: the sphere's radius */

static const float cam_eye[3] = {0.6f, 2.3f, 4.6f}, cam_target[3] = {0.3f, 0.6f, -1.0f};
static const double fov_y = 0.87266; /* 50 degrees */
/* The orthographic box's offset in NDC (P30, P31): an off-centre box, so that every place the
 * offset goes (view positions, the AO grid at 1/2, the guard band, the jitter) is exercised. */
static const float ortho_shift[2] = {0.08f, -0.05f};
static ob_scene *scene;

/* ---- the scene as geometry for the reference ---------------------------------------------------- */
static void quad(FILE *f, int *nv, const float a[3], const float b[3], const float c[3], const float d[3])
{
    const float *p[4] = {a, b, c, d};
    for (int i = 0; i < 4; ++i) fprintf(f, "v %.9g %.9g %.9g\n", (double)p[i][0], (double)p[i][1], (double)p[i][2]);
    fprintf(f, "f %d %d %d\nf %d %d %d\n", *nv + 1, *nv + 2, *nv + 3, *nv + 1, *nv + 3, *nv + 4);
    *nv += 4;
}

/* host_scene.h's scene_hit as triangles: the floor and wall quads, the box's six faces and the
 * sphere as 256 x 128 quads (its facets lie at most 3e-4 inside the true sphere, under the
 * reference's ray offset of 1e-4 of the bounds' diagonal, 2e-3 here). */
static bool write_scene(const char *path)
{
    FILE *f = fopen(path, "w");
    if (!f) return false;
    int nv = 0;
    quad(f, &nv, (float[3]){-8, 0, -3}, (float[3]){-8, 0, 8}, (float[3]){8, 0, 8}, (float[3]){8, 0, -3});
    quad(f, &nv, (float[3]){-8, 0, -3}, (float[3]){8, 0, -3}, (float[3]){8, 3, -3}, (float[3]){-8, 3, -3});
    const float lo[3] = {0.9f, 0.0f, -3.0f}, hi[3] = {2.4f, 1.2f, -1.7f};
    for (int axis = 0; axis < 3; ++axis)
        for (int side = 0; side < 2; ++side) {
            int u = (axis + 1) % 3, v = (axis + 2) % 3;
            float c[4][3];
            for (int k = 0; k < 4; ++k) {
                c[k][axis] = side ? hi[axis] : lo[axis];
                c[k][u] = (k == 1 || k == 2) ? hi[u] : lo[u];
                c[k][v] = (k >= 2) ? hi[v] : lo[v];
            }
            quad(f, &nv, c[0], c[1], c[2], c[3]);
        }
    enum { LON = 256, LAT = 128 };
    const int base = nv;
    for (int j = 0; j <= LAT; ++j)
        for (int i = 0; i < LON; ++i) {
            const double pi = 3.14159265358979323846;
            double th = pi * j / LAT, ph = 2.0 * pi * i / LON;
            fprintf(f, "v %.9g %.9g %.9g\n", -0.6 + sin(th) * cos(ph), 1.0 + cos(th), sin(th) * sin(ph));
            ++nv;
        }
    for (int j = 0; j < LAT; ++j)
        for (int i = 0; i < LON; ++i) {
            int a = base + 1 + j * LON + i, b = base + 1 + j * LON + (i + 1) % LON;
            fprintf(f, "f %d %d %d\nf %d %d %d\n", a, a + LON, b + LON, a, b + LON, b);
        }
    return fclose(f) == 0;
}

/* ---- one camera's G-buffer and its truth ---------------------------------------------------------- */
typedef struct gbuffer {
    host_view v;
    int w, h;
    float *depth, *vn, *wn, *second; /* linear depth, view and world normals (4 floats), second layer */
    float *pos, *nrm;                /* the G-buffer points and their normals, world space, 3 floats */
    float *truth;                    /* AO_R at each point (1 on sky) */
} gbuffer;

/* Ray-cast v into g (host_scene.h's scene_hit along pixel_ray); the second layer is the next
 * surface along each pixel's ray behind the first (the solids are hit from outside only, so that is
 * what stands behind the object). Each ray starts 12 units before the target's plane when the eye
 * is farther: the sphere test's b^2 - c cancels in float with the eye 60 units away (the narrow
 * perspective), and would put noise of 1e-3 units on the sphere. */
static void cast(gbuffer *g, const host_view *v)
{
    const size_t n = (size_t)v->w * (size_t)v->h;
    g->v = *v;
    g->w = v->w, g->h = v->h;
    g->depth = calloc(n, sizeof(float)), g->vn = calloc(4 * n, sizeof(float)), g->wn = calloc(4 * n, sizeof(float));
    g->second = calloc(n, sizeof(float)), g->pos = calloc(3 * n, sizeof(float)), g->nrm = calloc(3 * n, sizeof(float));
    g->truth = calloc(n, sizeof(float));
    const float to_target[3] = {cam_target[0] - v->eye[0], cam_target[1] - v->eye[1], cam_target[2] - v->eye[2]};
    const float skip = fmaxf(dot3(to_target, v->f) - 12.0f, 0.0f);
    for (int y = 0; y < v->h; ++y)
        for (int x = 0; x < v->w; ++x) {
            size_t i = (size_t)y * (size_t)v->w + (size_t)x;
            float o[3], d[3], nw[3] = {0.0f, 0.0f, 0.0f};
            pixel_ray(v, x, y, o, d); /* d's forward component is 1: its parameter is linear depth */
            for (int k = 0; k < 3; ++k) o[k] += skip * d[k];
            float s = scene_hit(o, d, nw);
            if (s <= 0.0f) continue;
            g->depth[i] = skip + s;
            const float vn[3] = {dot3(nw, v->r), dot3(nw, v->u), -dot3(nw, v->f)};
            for (int k = 0; k < 3; ++k) {
                g->vn[4 * i + k] = vn[k], g->wn[4 * i + k] = nw[k];
                g->pos[3 * i + k] = o[k] + s * d[k], g->nrm[3 * i + k] = nw[k];
            }
            g->vn[4 * i + 3] = g->wn[4 * i + 3] = 1.0f;
            const float eps = 1e-3f;
            float o2[3], n2[3];
            for (int k = 0; k < 3; ++k) o2[k] = o[k] + (s + eps) * d[k];
            float s2 = scene_hit(o2, d, n2);
            g->second[i] = s2 > 0.0f ? g->depth[i] + eps + s2 : 0.0f;
        }
}

static bool grade(gbuffer *g)
{
    const ob_reference_desc rd = {.spp = 512, .radius = RADIUS, .seed = 45};
    ob_error e = ob_reference_ao(scene, g->pos, g->nrm, (size_t)g->w * (size_t)g->h, &rd, g->truth, NULL);
    CHECK(e == OB_OK, "ob_reference_ao: %s", ob_error_name(e));
    return e == OB_OK;
}

static void release(gbuffer *g)
{
    free(g->depth), free(g->vn), free(g->wn), free(g->second), free(g->pos), free(g->nrm), free(g->truth);
}

/* ---- textures and calls --------------------------------------------------------------------------- */
static GLuint upload(GLenum internal, int w, int h, GLenum format, const float *data)
{
    GLuint t = make_tex(internal, w, h);
    glTextureSubImage2D(t, 0, 0, 0, w, h, format, GL_FLOAT, data);
    return t;
}

static GLuint depth_buffer(const float proj[16], bool zero_to_one, bool reversed, const float *depth, int w, int h)
{
    size_t n = (size_t)w * (size_t)h;
    float *win = malloc(n * sizeof(float));
    for (size_t i = 0; i < n; ++i) win[i] = window_depth(proj, depth[i], zero_to_one, reversed ? 0.0f : 1.0f);
    GLuint t = make_tex(GL_DEPTH_COMPONENT32F, w, h);
    glTextureSubImage2D(t, 0, 0, 0, w, h, GL_DEPTH_COMPONENT, GL_FLOAT, win);
    free(win);
    return t;
}

static const char *last_error(void)
{
    const char *msg = "";
    ob_get_error(&msg);
    return msg;
}

static ob_settings settings_for(const char *method, const char *filter, int divisor, bool temporal, int guard)
{
    ob_settings s;
    ob_error e = ob_settings_from_host(&s, &(ob_host_settings){.method = method, .radius = RADIUS, .filter = filter,
                                                                .ao_divisor = divisor, .temporal = temporal,
                                                                .guard = guard});
    CHECK(e == OB_OK, "%s settings: %s", method, last_error());
    return s;
}

/* One ob_host_ao call from a fresh history (the same noise for every call) into ao (R32F, the
 * renderer's size), read into px. */
static bool run(ob_renderer *r, const ob_host_frame *f, const ob_settings *s, GLuint ao, float *px, bool reset,
                const char *what)
{
    if (reset) ob_renderer_reset_history(r);
    ob_error e = ob_host_ao(r, f, s, &(ob_host_outputs){.ao = ao});
    CHECK(e == OB_OK, "%s: ob_host_ao: %s", what, last_error());
    GLenum ge = glGetError();
    CHECK(ge == GL_NO_ERROR, "%s: GL error 0x%x", what, ge);
    if (e != OB_OK) return false;
    glGetTextureImage(ao, 0, GL_RED, GL_FLOAT, (GLsizei)(NPX * sizeof(float)), px);
    return true;
}

/* RMSE of ao against the truth over the pixels with geometry. */
static double rmse(const float *ao, const gbuffer *g)
{
    double sum = 0.0;
    size_t n = 0;
    for (size_t i = 0; i < NPX; ++i) {
        if (g->depth[i] <= 0.0f) continue;
        double d = (double)ao[i] - (double)g->truth[i];
        sum += isfinite(d) ? d * d : 1.0;
        ++n;
    }
    return n ? sqrt(sum / (double)n) : INFINITY;
}

static int cmp_double(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return x < y ? -1 : x > y;
}

/* Mean and 99th percentile of |a - b| over every pixel. */
static void diff_stats(const float *a, const float *b, double *mean, double *p99)
{
    static double d[NPX];
    *mean = 0.0;
    for (size_t i = 0; i < NPX; ++i) {
        d[i] = isfinite(a[i]) && isfinite(b[i]) ? fabs((double)a[i] - (double)b[i]) : INFINITY;
        *mean += d[i];
    }
    *mean /= (double)NPX;
    qsort(d, NPX, sizeof d[0], cmp_double);
    *p99 = d[(size_t)(0.99 * (double)(NPX - 1))];
}

static ob_host_frame frame_of(const gbuffer *g, GLuint depth, GLuint normal, const float proj[16], bool zero_to_one)
{
    ob_host_frame f = {.depth = depth, .normal = normal, .normal_space = OB_NORMALS_VIEW,
                       .depth_zero_to_one = zero_to_one};
    memcpy(f.projection, proj, sizeof f.projection);
    memcpy(f.view, g->v.view, sizeof f.view);
    return f;
}

/* ---- the grading ---------------------------------------------------------------------------------- */
/* The views: the 50-degree perspective, TELE perspectives narrowing toward the orthographic limit
 * (each from as far back along the same line as frames the same height at the target), and the
 * orthographic one. */
enum { PERSP, TELE0, TELE = 3, ORTHO = TELE0 + TELE, VIEWS };
static const double tele_fov_deg[TELE] = {5.0, 2.0, 1.0};

typedef struct views {
    gbuffer g[VIEWS];
    float proj[VIEWS][16];
    float naive_proj[16]; /* the perspective matrix of the orthographic framing (see main) */
} views;

/* The bounds.
 * 1. Against the 50-degree perspective: the two cameras see the same surfaces at the same scale at
 *    the target (the sphere's contact, the crease under the wall, the box's corner), so a method's
 *    error, which comes from what the depth buffer hides and how its samples fall, is of the same
 *    size in both; they differ in how much of each surface they show (no foreshortening of the far
 *    floor, the box's side faces at other angles), and the reference's own noise (512 rays, sigma
 *    <= 0.022 a point) adds alike. Orthographic <= 1.25 x perspective + 0.01.
 * 2. Against the narrow perspectives: an orthographic camera is the limit of a perspective one
 *    whose field of view goes to 0 at the same framing, so its RMSE must lie among theirs. They
 *    are not one number: at 5, 2 and 1 degrees the rays across the frame still differ by as much,
 *    and which of the box's faces seen edge-on (87 degrees here) shows a pixel changes gtao's RMSE
 *    by up to 30 % between them (vbao, ssao: under 10 %). Orthographic within [min - 5 %, max + 5 %]
 *    of the three, plus 0.003 (the reference's noise on an RMSE over 10^4 points).
 * 3. The perspective reconstruction of the orthographic G-buffer (its depth and normals handed over
 *    with the perspective matrix of the same framing, all a host could do before) bends every plane
 *    into a curved surface: at least 1.33 x the orthographic RMSE, for vbao and gtao (ssao's error
 *    against AO_R is its own open-surface bias, 0.13 in every view, which hides the distortion; the
 *    bounds 1 and 2 catch ssao with the shaders' camera forced to perspective). */
#define RATIO 1.25
#define SLACK 0.01
#define TELE_RATIO 0.05
#define TELE_SLACK 0.003
#define NAIVE_RATIO 1.33

/* One row: e[view] the RMSE of each view (< 0: not run), naive the perspective reconstruction's. */
static void add_row(const char *what, const double e[VIEWS], double naive, bool bound, bool naive_bound)
{
    double lo = INFINITY, hi = -INFINITY;
    char tele_text[TELE][16];
    for (int k = 0; k < TELE; ++k) {
        lo = fmin(lo, e[TELE0 + k]), hi = fmax(hi, e[TELE0 + k]);
        snprintf(tele_text[k], sizeof tele_text[k], "%.4f", e[TELE0 + k]);
    }
    char naive_text[16] = "-";
    if (naive >= 0.0) snprintf(naive_text, sizeof naive_text, "%.4f", naive);
    printf("%-34s %8.4f %8s %8s %8s %8.4f %10s  %s\n", what, e[PERSP], tele_text[0], tele_text[1], tele_text[2], e[ORTHO],
           naive_text, bound ? "checked" : "reported");
    if (!bound) return;
    const double ortho = e[ORTHO];
    CHECK(ortho <= RATIO * e[PERSP] + SLACK, "%s: orthographic RMSE %.4f above %.2f x the perspective %.4f + %.2f", what,
          ortho, RATIO, e[PERSP], SLACK);
    CHECK(ortho >= (1.0 - TELE_RATIO) * lo - TELE_SLACK && ortho <= (1.0 + TELE_RATIO) * hi + TELE_SLACK,
          "%s: orthographic RMSE %.4f outside the narrow perspectives' %.4f .. %.4f (+- %.0f %% + %.3f)", what, ortho, lo,
          hi, 100.0 * TELE_RATIO, TELE_SLACK);
    if (naive_bound)
        CHECK(naive >= NAIVE_RATIO * ortho,
              "%s: the perspective reconstruction of the orthographic G-buffer (%.4f) is not worse than the "
              "orthographic one (%.4f) by %.2fx",
              what, naive, ortho, NAIVE_RATIO);
}

static void print_header(const char *title)
{
    printf("\n%s\n%-34s %8s %8s %8s %8s %8s %10s\n", title, "method / filter", "persp 50", "persp 5", "persp 2", "persp 1",
           "ortho", "ortho as P");
}

typedef struct inputs {
    GLuint depth[VIEWS], normal[VIEWS], second[VIEWS];
} inputs;

static void upload_views(const views *vw, inputs *in)
{
    for (int k = 0; k < VIEWS; ++k) {
        in->depth[k] = upload(GL_R32F, W, H, GL_RED, vw->g[k].depth);
        in->normal[k] = upload(GL_RGBA32F, W, H, GL_RGBA, vw->g[k].vn);
        in->second[k] = upload(GL_R32F, W, H, GL_RED, vw->g[k].second);
    }
}

static void delete_views(inputs *in)
{
    glDeleteTextures(VIEWS, in->depth), glDeleteTextures(VIEWS, in->normal), glDeleteTextures(VIEWS, in->second);
}

static void grade_methods(ob_renderer *r, const views *vw, const inputs *in)
{
    static float px[NPX], lin[NPX], d32[NPX];
    GLuint ao = make_tex(GL_R32F, W, H);
    const gbuffer *og = &vw->g[ORTHO];
    const float *oproj = vw->proj[ORTHO];
    /* D32F buffers of the orthographic view: standard [-1, 1] and reversed [0, 1], near 0.1, far 20. */
    float std_proj[16], rev_proj[16];
    memcpy(std_proj, oproj, sizeof std_proj);
    orthographic(rev_proj, 1.0 / oproj[0], 1.0 / oproj[5], 0.1, 20.0, true, true);
    rev_proj[12] = oproj[12], rev_proj[13] = oproj[13];
    GLuint o_std = depth_buffer(std_proj, false, false, og->depth, W, H);
    GLuint o_rev = depth_buffer(rev_proj, true, true, og->depth, W, H);

    /* bound: the bounds are checked, else only reported; naive: so is bound 3. */
    static const struct {
        const char *method, *filter;
        bool bound, naive;
    } cases[] = {
        {"vbao", "none", true, true},       {"gtao", "none", true, true},       {"ssao", "none", true, false},
        {"vbao", "crease", true, true},     {"gtao", "crease", true, true},     {"ssao", "crease", true, false},
        {"hbao", "none", false, false},     {"alchemy", "none", false, false},  {"crytek", "none", false, false},
        {"gtao", "bilateral", false, false}, {"vbao", "geometry", false, false},
    };
    printf("\nAO against the ray-traced AO_R of the same points: RMSE over the pixels with geometry, %dx%d, R = %g\n", W,
           H, (double)RADIUS);
    printf("bounds: orthographic <= %.2f x perspective 50 + %.2f; within the narrow perspectives' range +- %.0f %% + %.3f; "
           "the perspective reconstruction of the orthographic G-buffer (ortho as P) >= %.2f x orthographic\n",
           RATIO, SLACK, 100.0 * TELE_RATIO, TELE_SLACK, NAIVE_RATIO);
    print_header("the methods (R32F linear depth, RGBA32F view normals)");
    for (size_t c = 0; c < sizeof cases / sizeof cases[0]; ++c) {
        char what[64];
        snprintf(what, sizeof what, "%s / %s", cases[c].method, cases[c].filter);
        ob_settings s = settings_for(cases[c].method, cases[c].filter, 1, false, 0);
        double e[VIEWS], e_n = -1.0;
        for (int k = 0; k < VIEWS; ++k) {
            ob_host_frame f = frame_of(&vw->g[k], in->depth[k], in->normal[k], vw->proj[k], false);
            e[k] = run(r, &f, &s, ao, k == ORTHO ? lin : px, true, what) ? rmse(k == ORTHO ? lin : px, &vw->g[k]) : -1.0;
        }
        ob_host_frame fn = frame_of(og, in->depth[ORTHO], in->normal[ORTHO], vw->naive_proj, false);
        if (run(r, &fn, &s, ao, px, true, what)) e_n = rmse(px, og);
        add_row(what, e, e_n, cases[c].bound, cases[c].naive);
        if (!cases[c].bound) continue;
        /* The same AO from a depth buffer: D32F's window depth steps by 2^-24 (2^-25 below 0.5),
         * 1.2e-6 units of the 19.9-unit range, and the linearisation rounds to a few ulps of d; a few
         * pixels sit where a sample's test flips on that (a sector of vbao, a sample of ssao's 16). */
        const double tol_mean = 0.002, tol_p99 = 0.02;
        for (int k = 0; k < 2; ++k) {
            ob_host_frame fd = frame_of(og, k ? o_rev : o_std, in->normal[ORTHO], k ? rev_proj : std_proj, k == 1);
            char w2[96];
            snprintf(w2, sizeof w2, "%s, D32F %s", what, k ? "reversed [0,1]" : "standard [-1,1]");
            if (!run(r, &fd, &s, ao, d32, true, w2)) continue;
            double mean, p99;
            diff_stats(d32, lin, &mean, &p99);
            printf("    %-44s |AO - R32F's| mean %.5f p99 %.5f (tol %.3f, %.3f)\n", w2, mean, p99, tol_mean, tol_p99);
            CHECK(mean <= tol_mean && p99 <= tol_p99, "%s: D32F against R32F: mean %.5f p99 %.5f", w2, mean, p99);
        }
    }
    GLuint t[3] = {ao, o_std, o_rev};
    glDeleteTextures(3, t);
}

/* The AO grid at 1/2 and 1/4 (its offset folded into P30, P31), a second depth layer, bent normals
 * and the guard band (ob_guard_projection scales P30, P31 too), each graded as above. */
static void grade_chain(ob_renderer *r, const views *vw, const inputs *in)
{
    static float px[NPX];
    GLuint ao = make_tex(GL_R32F, W, H);
    static const struct {
        const char *what, *method, *extra;
        int divisor;
        bool layers;
    } cases[] = {
        {"vbao / crease, AO at 1/2", "vbao", NULL, 2, false},
        {"gtao / crease, AO at 1/2", "gtao", NULL, 2, false},
        {"ssao / crease, AO at 1/4", "ssao", NULL, 4, false},
        {"vbao / none, layers = 2", "vbao", "layers=2", 1, true},
        {"gtao / none, layers = 2", "gtao", "layers=2", 1, true},
        {"gtao / crease, bent normals", "gtao", "bent_normals=on", 1, false},
    };
    print_header("the chain (R32F linear depth, RGBA32F view normals)");
    for (size_t c = 0; c < sizeof cases / sizeof cases[0]; ++c) {
        ob_settings s = settings_for(cases[c].method, cases[c].layers ? "none" : "crease", cases[c].divisor, false, 0);
        if (cases[c].extra) CHECK(ob_settings_set(&s, cases[c].extra) == OB_OK, "%s: %s", cases[c].what, last_error());
        double e[VIEWS];
        for (int k = 0; k < VIEWS; ++k) {
            ob_host_frame f = frame_of(&vw->g[k], in->depth[k], in->normal[k], vw->proj[k], false);
            f.second_depth = cases[c].layers ? in->second[k] : 0;
            e[k] = run(r, &f, &s, ao, px, true, cases[c].what) ? rmse(px, &vw->g[k]) : -1.0;
        }
        add_row(cases[c].what, e, -1.0, true, false);
    }

    /* The guard band: the host renders W + 2g x H + 2g through the widened projection; the
     * visible frame is the unwidened view pixel for pixel, so the same truth grades it. */
    ob_settings s = settings_for("vbao", "crease", 1, false, 8);
    int iw = 0, ih = 0, guard = 0;
    ob_host_input_size(r, &s, &iw, &ih, &guard);
    CHECK(guard == 8 && iw == W + 16 && ih == H + 16, "guard band: input %dx%d, band %d", iw, ih, guard);
    double e[VIEWS];
    for (int k = 0; k < VIEWS; ++k) {
        e[k] = -1.0;
        float wide[16];
        memcpy(wide, vw->proj[k], sizeof wide);
        ob_guard_projection(wide, W, H, guard);
        host_view v;
        make_view(&v, iw, ih, wide, vw->g[k].v.eye, cam_target);
        gbuffer wg;
        cast(&wg, &v);
        /* The widened raster's centre is the visible one: its depth there must be the same (to the
         * rounding of rays through another matrix: 2e-5 of the depth). */
        double worst = 0.0;
        for (int y = 0; y < H; ++y)
            for (int x = 0; x < W; ++x) {
                const double a = wg.depth[(size_t)(y + guard) * (size_t)iw + (size_t)(x + guard)];
                const double b = vw->g[k].depth[(size_t)y * W + (size_t)x];
                worst = fmax(worst, fabs(a - b) / fmax(b, 1.0));
            }
        CHECK(worst <= 2e-5, "guard band (view %d): the widened raster's centre is the view (depth off by %g of itself)", k,
              worst);
        GLuint td = upload(GL_R32F, iw, ih, GL_RED, wg.depth), tn = upload(GL_RGBA32F, iw, ih, GL_RGBA, wg.vn);
        ob_host_frame f = frame_of(&vw->g[k], td, tn, wide, false);
        if (run(r, &f, &s, ao, px, true, "guard band")) e[k] = rmse(px, &vw->g[k]);
        GLuint t[2] = {td, tn};
        glDeleteTextures(2, t);
        release(&wg);
    }
    add_row("vbao / crease, guard band 8 px", e, -1.0, true, false);
    glDeleteTextures(1, &ao);
}

/* Every method (the indirect-light ones on a grey direct light) with every filter and the programs
 * their switches pick, orthographic against the 50- and 5-degree perspectives: AO
 * finite, in [0, 1], below 0.9 on 1 % of the pixels at least, and an RMSE within their range widened by 25 % + 0.01
 * (a sweep for what the graded rows above do not reach: ssdo's and vbgi's programs, box4,
 * gaussian, bilateral_sep, crease's tiled and plain programs, the depth MIP chain, deinterleaving,
 * adaptive counts, temporal accumulation of M). */
static void sweep(ob_renderer *r, const views *vw, const inputs *in)
{
    static float px[NPX];
    GLuint ao = make_tex(GL_R32F, W, H);
    GLuint radiance = make_tex(GL_RGBA16F, W, H);
    const float grey[4] = {0.5f, 0.5f, 0.5f, 1.0f};
    glClearTexImage(radiance, 0, GL_RGBA, GL_FLOAT, grey);
    /* A method and up to two of its settings; the depth MIP chain's rows search 4 R (radius_scale,
     * graded at R as every row), so that their far steps reach its levels (taps 20 px out). */
    static const char *const methods[][3] = {
        {"ssao", NULL, NULL},
        {"ssao", "deinterleave=on", NULL},
        {"hbao", NULL, NULL},
        {"hbao", "depth_mips=1", "radius_scale=4"},
        {"crytek", NULL, NULL},
        {"alchemy", NULL, NULL},
        {"alchemy", "deinterleave=on", NULL},
        {"ssdo", NULL, NULL},
        {"ssdo", "layers=2", NULL},
        {"ssdo_merged", NULL, NULL},
        {"ssdo_merged", "depth_mips=1", "radius_scale=4"},
        {"gtao", NULL, NULL},
        {"gtao", "depth_mips=1", "radius_scale=4"},
        {"vbao", NULL, NULL},
        {"vbao", "depth_mips=1", "radius_scale=4"},
        {"vbao", "layers=2", NULL},
        {"vbgi", NULL, NULL},
        {"vbgi", "packed=off", NULL},
        {"vbgi", "layers=2", NULL},
    };
    static const char *const filters[][2] = {
        {"none", NULL},       {"box4", NULL},          {"gaussian", NULL},         {"bilateral", NULL},
        {"bilateral_sep", NULL}, {"geometry", NULL},   {"crease", "crease.tiled=off"}, {"crease", "crease.tiled=on"},
        {"crease", "crease.tiled=block"},
    };
    /* Against the 50- and 5-degree perspectives: alchemy's bias is beta x depth (McGuire et al.'s
     * beta z_C), so farther cameras lose its occlusion (at 1 degree, 313 units away, all of it);
     * the 50-degree camera stands where the orthographic one does. */
    const int views_used[3] = {PERSP, TELE0, ORTHO};
    printf("\nevery method and filter, orthographic against the 50- and 5-degree perspectives (RMSE; [out]: outside "
           "their range +- 25 %% + 0.01)\n%-26s", "");
    for (size_t f = 0; f < sizeof filters / sizeof filters[0]; ++f)
        printf(" %-6.6s", filters[f][1] ? filters[f][1] + strlen("crease.tiled=") : filters[f][0]);
    printf("\n");
    int rows = 0, bad = 0;
    for (size_t m = 0; m < sizeof methods / sizeof methods[0]; ++m) {
        char label[64];
        snprintf(label, sizeof label, "%s%s%s%s", methods[m][0], methods[m][1] ? " " : "", methods[m][1] ? methods[m][1] : "",
                 methods[m][2] ? " 4R" : "");
        printf("%-26s", label);
        for (size_t f = 0; f < sizeof filters / sizeof filters[0]; ++f) {
            ob_settings s = settings_for(methods[m][0], filters[f][0], 1, false, 0);
            for (int a = 1; a < 3; ++a)
                if (methods[m][a])
                    CHECK(ob_settings_set(&s, methods[m][a]) == OB_OK, "%s: %s", methods[m][a], last_error());
            if (filters[f][1]) CHECK(ob_settings_set(&s, filters[f][1]) == OB_OK, "%s: %s", filters[f][1], last_error());
            double e[3] = {-1.0, -1.0, -1.0};
            bool sane = true;
            for (int k = 0; k < 3; ++k) {
                const int v = views_used[k];
                ob_host_frame fr = frame_of(&vw->g[v], in->depth[v], in->normal[v], vw->proj[v], false);
                fr.radiance = radiance;
                fr.second_depth = methods[m][1] && strstr(methods[m][1], "layers") ? in->second[v] : 0;
                if (!run(r, &fr, &s, ao, px, true, methods[m][0])) continue;
                size_t occluded = 0;
                for (size_t i = 0; i < NPX; ++i) {
                    sane = sane && isfinite(px[i]) && px[i] >= 0.0f && px[i] <= 1.0f; /* the filters clamp AO (gaussian wrote 1 + 1 ulp) */
                    occluded += px[i] < 0.9f;
                }
                sane = sane && occluded >= NPX / 100; /* the contact, the creases */
                e[k] = rmse(px, &vw->g[v]);
            }
            const double lo = fmin(e[0], e[1]), hi = fmax(e[0], e[1]);
            const bool ok = sane && e[2] >= 0.75 * lo - 0.01 && e[2] <= 1.25 * hi + 0.01;
            printf(" %s%.4f%s", ok ? "" : "[", e[2], ok ? " " : "]");
            CHECK(ok, "%s %s / %s %s: orthographic RMSE %.4f against the narrow perspectives' %.4f .. %.4f (AO %s)",
                  methods[m][0], methods[m][1] ? methods[m][1] : "", filters[f][0], filters[f][1] ? filters[f][1] : "",
                  e[2], lo, hi, sane ? "in [0, 1] with occlusion" : "NOT finite, in [0, 1] and occluded");
            ++rows, bad += !ok;
        }
        printf("\n");
    }
    printf("%d combinations, %d outside (in brackets)\n", rows, bad);

    /* Temporal accumulation of M (ssdo) and of the bounce (vbgi) under the orthographic camera:
     * three calls of a still frame keep their histories. */
    static float age[NPX];
    for (int k = 0; k < 2; ++k) {
        ob_settings s = settings_for(k ? "vbgi" : "ssdo", "crease", 2, true, 0);
        ob_host_frame fr = frame_of(&vw->g[ORTHO], in->depth[ORTHO], in->normal[ORTHO], vw->proj[ORTHO], false);
        fr.radiance = radiance;
        bool ok = true;
        for (int i = 0; i < 3 && ok; ++i) ok = run(r, &fr, &s, ao, px, i == 0, "temporal M");
        /* The age read-back reads the AO grid's own depth: at 1/2 the downsample writes it. */
        size_t n = 0, kept = 0;
        if (ok && ob_read_image(r, OB_IMAGE_HISTORY_AGE_F32, age, sizeof age) == OB_OK)
            for (size_t i = 0; i < (size_t)(W / 2) * (H / 2); ++i) n += age[i] > 0.0f, kept += age[i] > 2.5f;
        printf("%s temporal at 1/2, 3 still frames: %zu of %zu AO pixels keep their history\n", k ? "vbgi" : "ssdo", kept, n);
        CHECK(ok && n > 0 && kept >= n * 9 / 10, "%s: temporal accumulation under an orthographic camera (%zu of %zu kept)",
              k ? "vbgi" : "ssdo", kept, n);
    }
    GLuint t[2] = {ao, radiance};
    glDeleteTextures(2, t);
}

/* TAA jitter: the frame's jitter moves P30, P31 by -2 jitter / size (the image by -jitter px), so a
 * call with the projection and the jitter is the very call with the jittered matrix and none. */
static void check_jitter(ob_renderer *r, const views *vw)
{
    static float a[NPX], b[NPX];
    GLuint ao = make_tex(GL_R32F, W, H);
    GLuint depth = upload(GL_R32F, W, H, GL_RED, vw->g[ORTHO].depth), n = upload(GL_RGBA32F, W, H, GL_RGBA, vw->g[ORTHO].vn);
    ob_settings s = settings_for("vbao", "crease", 1, false, 0);
    const float jitter[2] = {0.37f, -0.21f};
    ob_host_frame f = frame_of(&vw->g[ORTHO], depth, n, vw->proj[ORTHO], false);
    f.jitter[0] = jitter[0], f.jitter[1] = jitter[1];
    ob_host_frame g = frame_of(&vw->g[ORTHO], depth, n, vw->proj[ORTHO], false);
    g.projection[12] -= 2.0f * jitter[0] / (float)W;
    g.projection[13] -= 2.0f * jitter[1] / (float)H;
    if (run(r, &f, &s, ao, a, true, "jitter") && run(r, &g, &s, ao, b, true, "jittered matrix")) {
        double worst = 0.0;
        for (size_t i = 0; i < NPX; ++i) worst = fmax(worst, fabs((double)a[i] - (double)b[i]));
        CHECK(worst == 0.0, "orthographic jitter: the AO differs from the jittered matrix's by %g", worst);
    }
    /* An orthographic jitter moves every reconstructed point alike, so the AO of one depth buffer
     * does not see it; the temporal reprojection takes it out: a frame at jitter 0, then one at
     * `jitter`, of a still camera, reads its history where it wrote it (motion 0: the last
     * frame's camera with this frame's jitter, as TAA reprojects), where through the two
     * jittered cameras every point would have moved by the jitter's change. Through a D32F
     * buffer, so that the input pass writes the depth the motion read-back reads. */
    static float motion[2 * NPX];
    GLuint d32 = depth_buffer(vw->proj[ORTHO], false, false, vw->g[ORTHO].depth, W, H);
    ob_settings st = settings_for("vbao", "crease", 1, true, 0);
    f = frame_of(&vw->g[ORTHO], d32, n, vw->proj[ORTHO], false);
    bool ok = run(r, &f, &st, ao, a, true, "jitter, frame 1");
    f.jitter[0] = jitter[0], f.jitter[1] = jitter[1];
    ok = ok && run(r, &f, &st, ao, a, false, "jitter, frame 2");
    ok = ok && ob_read_image(r, OB_IMAGE_MOTION_F32, motion, sizeof motion) == OB_OK;
    CHECK(ok, "jitter under temporal accumulation: %s", last_error());
    if (ok) {
        double worst = 0.0;
        for (size_t i = 0; i < NPX; ++i)
            if (vw->g[ORTHO].depth[i] > 0.0f)
                worst = fmax(worst, fmax(fabs((double)motion[2 * i]), fabs((double)motion[2 * i + 1])));
        printf("\northographic jitter (%.2f, %.2f) px: a still camera's motion %.2g px at most\n", (double)jitter[0],
               (double)jitter[1], worst);
        CHECK(worst <= 1e-3, "orthographic jitter: a still camera's motion %g px, not 0 (RG16F: 1e-3)", worst);
    }
    GLuint t[4] = {ao, depth, n, d32};
    glDeleteTextures(4, t);
}

/* Temporal accumulation under an orthographic pan: the eye moves 0.04 units to the right a frame,
 * so every point's previous position is the same 0.04 P00 W / 2 pixels to the right of the current
 * one whatever its depth (a perspective camera's parallax would vary it), and the histories are
 * kept where the point was seen the frame before. */
static void check_temporal(ob_renderer *r, const views *vw)
{
    enum { FRAMES = 6 };
    static float px[NPX], age[NPX], motion[2 * NPX];
    GLuint ao = make_tex(GL_R32F, W, H);
    ob_settings s = settings_for("vbao", "crease", 1, true, 0);
    const float step = 0.04f;
    ob_renderer_reset_history(r);
    gbuffer last = {0};
    bool ok = true;
    for (int i = 0; i < FRAMES && ok; ++i) {
        const float dx = step * (float)(i - FRAMES + 1); /* the last frame is the graded view */
        float eye[3], target[3];
        for (int k = 0; k < 3; ++k) eye[k] = cam_eye[k] + dx * vw->g[ORTHO].v.r[k], target[k] = cam_target[k] + dx * vw->g[ORTHO].v.r[k];
        host_view v;
        make_view(&v, W, H, vw->proj[ORTHO], eye, target);
        gbuffer g;
        cast(&g, &v);
        /* D32F: the input pass writes the depth that the motion read-back reprojects. */
        GLuint depth = depth_buffer(vw->proj[ORTHO], false, false, g.depth, W, H);
        GLuint n = upload(GL_RGBA32F, W, H, GL_RGBA, g.vn);
        ob_host_frame f = frame_of(&g, depth, n, vw->proj[ORTHO], false);
        ok = run(r, &f, &s, ao, px, false, "temporal pan");
        GLuint t[2] = {depth, n};
        glDeleteTextures(2, t);
        if (i < FRAMES - 1) release(&g);
        else last = g;
    }
    if (ok) {
        CHECK(ob_read_image(r, OB_IMAGE_HISTORY_AGE_F32, age, sizeof age) == OB_OK, "history age: %s", last_error());
        CHECK(ob_read_image(r, OB_IMAGE_MOTION_F32, motion, sizeof motion) == OB_OK, "motion: %s", last_error());
        const double expect = (double)step * (double)vw->proj[ORTHO][0] * 0.5 * W;
        double worst = 0.0, mean_age = 0.0;
        size_t n = 0, kept = 0;
        for (int y = 0; y < H; ++y)
            for (int x = 2; x < W - 8; ++x) { /* the band the pan brought in on the right has no past */
                size_t i = (size_t)y * W + (size_t)x;
                if (last.depth[i] <= 0.0f) continue;
                worst = fmax(worst, fmax(fabs((double)motion[2 * i] - expect), fabs((double)motion[2 * i + 1])));
                mean_age += age[i];
                kept += age[i] >= (float)FRAMES - 0.5f;
                ++n;
            }
        mean_age /= (double)(n ? n : 1);
        printf("\ntemporal pan (%d frames, %.4f px a frame): motion off by %.2g px at most, mean age %.2f, %.1f %% "
               "with the whole history\n",
               FRAMES, expect, worst, mean_age, 100.0 * (double)kept / (double)(n ? n : 1));
        CHECK(worst <= 1e-3, "orthographic reprojection: motion off by %g px (expected %g everywhere)", worst, expect);
        CHECK(kept >= 0.9 * (double)n, "orthographic reprojection keeps the histories: %zu of %zu pixels", kept, n);
        /* The accumulated AO against the truth of the last frame's own points. */
        double e = INFINITY, single = -1.0;
        if (grade(&last)) e = rmse(px, &last);
        ob_settings s1 = settings_for("vbao", "crease", 1, false, 0);
        GLuint depth = upload(GL_R32F, W, H, GL_RED, last.depth), nn = upload(GL_RGBA32F, W, H, GL_RGBA, last.vn);
        ob_host_frame f = frame_of(&last, depth, nn, vw->proj[ORTHO], false);
        if (run(r, &f, &s1, ao, px, true, "single frame")) single = rmse(px, &last);
        GLuint t[2] = {depth, nn};
        glDeleteTextures(2, t);
        printf("accumulated RMSE %.4f, one frame %.4f\n", e, single);
        CHECK(e <= single * 1.05 + 0.002, "temporal accumulation (%.4f) no worse than one frame (%.4f)", e, single);
    }
    release(&last);
    glDeleteTextures(1, &ao);
}

/* The projections the host path takes and refuses. */
static void check_refusals(ob_renderer *r, const views *vw)
{
    GLuint ao = make_tex(GL_R32F, W, H);
    GLuint depth = upload(GL_R32F, W, H, GL_RED, vw->g[ORTHO].depth);
    ob_settings s = settings_for("vbao", "none", 1, false, 0);
    static const struct {
        const char *what;
        int index;
        float value;
    } bad[] = {{"P22 = 0", 10, 0.0f}, {"P00 = 0", 0, 0.0f}, {"oblique (P20 != 0)", 8, 0.1f}, {"P03 != 0", 3, 0.5f}};
    for (size_t i = 0; i < sizeof bad / sizeof bad[0]; ++i) {
        ob_host_frame f = frame_of(&vw->g[ORTHO], depth, 0, vw->proj[ORTHO], false);
        f.projection[bad[i].index] = bad[i].value;
        ob_error e = ob_host_ao(r, &f, &s, &(ob_host_outputs){.ao = ao});
        const char *msg = last_error();
        CHECK(e == OB_ERR_INVALID_ARGUMENT && strstr(msg, "projection") && strstr(msg, "orthographic"),
              "an orthographic projection with %s: %s (%s)", bad[i].what, ob_error_name(e), msg);
    }
    GLuint t[2] = {ao, depth};
    glDeleteTextures(2, t);
}

int main(void)
{
    ob_context *ctx = NULL;
    ob_renderer *r = make_host_renderer(false, W, H, &ctx);
    if (!r) return 1;
    printf("host context: %s\n", (const char *)glGetString(GL_RENDERER));
    char dir[] = "/tmp/obscura-ortho-XXXXXX", path[64];
    if (!mkdtemp(dir)) {
        fprintf(stderr, "cannot make a temporary directory\n");
        return 1;
    }
    snprintf(path, sizeof path, "%s/scene.obj", dir);
    CHECK(write_scene(path), "write %s", path);
    scene = ob_load_scene(&(ob_scene_desc){.name = path, .up = OB_UP_Y});
    CHECK(scene != NULL, "load %s: %s", path, last_error());
    remove(path);
    rmdir(dir);
    if (!scene) return check_finish("host_ortho");

    /* The cameras: the same eye and target; the orthographic box frames the height the perspective
     * frustum spans at the target's distance, near 0.1, far 20, off-centre by ortho_shift; each
     * narrow perspective frames the same from farther back, with the same offset as its P20, P21. */
    views vw;
    const float aspect = (float)W / (float)H;
    double dist = 0.0;
    for (int k = 0; k < 3; ++k) dist += (double)(cam_target[k] - cam_eye[k]) * (double)(cam_target[k] - cam_eye[k]);
    dist = sqrt(dist);
    const double hh = dist * tan(0.5 * fov_y);
    float eyes[VIEWS][3];
    for (int v = 0; v < VIEWS; ++v) memcpy(eyes[v], cam_eye, sizeof eyes[v]);
    perspective(vw.proj[PERSP], (float)fov_y, aspect, 0.1, 100.0, false, false);
    for (int t = 0; t < TELE; ++t) {
        const double fov = tele_fov_deg[t] * 3.14159265358979 / 180.0, d = hh / tan(0.5 * fov);
        for (int k = 0; k < 3; ++k) eyes[TELE0 + t][k] = cam_target[k] + (cam_eye[k] - cam_target[k]) * (float)(d / dist);
        perspective(vw.proj[TELE0 + t], (float)fov, aspect, 0.5 * d, 2.0 * d, false, false);
        vw.proj[TELE0 + t][8] = -ortho_shift[0], vw.proj[TELE0 + t][9] = -ortho_shift[1];
    }
    orthographic(vw.proj[ORTHO], hh * aspect, hh, 0.1, 20.0, false, false);
    vw.proj[ORTHO][12] = ortho_shift[0], vw.proj[ORTHO][13] = ortho_shift[1];
    /* What a host could hand over before orthographic projections were taken: the orthographic
     * G-buffer with the perspective matrix of the same framing at the target (P00 d0 = the
     * orthographic P00, the offset as P20, P21). */
    memcpy(vw.naive_proj, vw.proj[PERSP], sizeof vw.naive_proj);
    vw.naive_proj[8] = -ortho_shift[0], vw.naive_proj[9] = -ortho_shift[1];
    bool graded = true;
    for (int v = 0; v < VIEWS; ++v) {
        host_view hv;
        make_view(&hv, W, H, vw.proj[v], eyes[v], cam_target);
        cast(&vw.g[v], &hv);
        size_t sky = 0;
        for (size_t i = 0; i < NPX; ++i) sky += vw.g[v].depth[i] <= 0.0f;
        CHECK(sky < NPX / 10, "view %d sees the scene (%zu sky pixels)", v, sky);
        graded = graded && grade(&vw.g[v]);
    }
    if (graded) {
        inputs in;
        upload_views(&vw, &in);
        grade_methods(r, &vw, &in);
        grade_chain(r, &vw, &in);
        sweep(r, &vw, &in);
        delete_views(&in);
        check_jitter(r, &vw);
        check_temporal(r, &vw);
        check_refusals(r, &vw);
    }
    for (int v = 0; v < VIEWS; ++v) release(&vw.g[v]);
    ob_destroy_scene(scene);
    ob_destroy_renderer(r);
    ob_destroy_context(ctx);
    destroy_host_context();
    return check_finish("host_ortho");
}
