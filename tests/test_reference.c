/* Ray-traced reference tests (CPU only): ob_reference_ao against an independent quadrature of the
 * same integral over analytic geometry, open-plane and sky points, determinism across seeds and
 * thread counts, ob_reference_bounce's terms, and ob_reference_points against a forward
 * projection. Runs on tests/check.h: the exit status is the failure count. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "check.h"
#include "obscura/eval.h"
#include "eval/reference.h"

#define PI 3.14159265358979323846

/* ---- the independent integral --------------------------------------------------------------
 * AO_R = 1/pi * int_0^2pi int_0^pi/2 V cos(t) sin(t) dt dphi. With u = sin^2(t) the weight
 * cos(t) sin(t) dt becomes du / 2, so AO_R = 1/(2 pi) int_0^2pi int_0^1 V du dphi: a midpoint rule
 * on a (u, phi) grid, deterministic, with its own analytic ray casts. V is a step function, so
 * the rule's error is about the fraction of cells its boundary crosses (~1e-3 at 600 x 1200), far
 * below the Monte Carlo tolerance. */
typedef bool (*hit_fn)(const double o[3], const double d[3], double tmax);

static bool in01(double a, double lo, double hi)
{
    return a >= lo && a <= hi;
}

/* An axis plane coordinate[axis] = 0, restricted to [lo, hi] in the other two coordinates. */
static bool hit_axis_plane(const double o[3], const double d[3], double tmax, int axis, double lo, double hi)
{
    if (d[axis] == 0.0) return false;
    double t = -o[axis] / d[axis];
    if (!(t > 1e-9 && t <= tmax)) return false;
    for (int k = 0; k < 3; ++k) {
        if (k == axis) continue;
        if (!in01(o[k] + t * d[k], lo, hi)) return false;
    }
    return true;
}

/* Built-in "corner": floor y = 0 and walls x = 0, z = 0, each [0, 4]^2. */
static bool hit_corner(const double o[3], const double d[3], double tmax)
{
    return hit_axis_plane(o, d, tmax, 0, 0.0, 4.0) || hit_axis_plane(o, d, tmax, 1, 0.0, 4.0) ||
           hit_axis_plane(o, d, tmax, 2, 0.0, 4.0);
}

/* Built-in "sphere-on-plane": unit sphere at (0, 1, 0) on the plane y = 0, [-5, 5]^2. */
static bool hit_sphere_plane(const double o[3], const double d[3], double tmax)
{
    if (hit_axis_plane(o, d, tmax, 1, -5.0, 5.0)) return true;
    double oc[3] = {o[0], o[1] - 1.0, o[2]};
    double b = oc[0] * d[0] + oc[1] * d[1] + oc[2] * d[2];
    double c = oc[0] * oc[0] + oc[1] * oc[1] + oc[2] * oc[2] - 1.0;
    double disc = b * b - c;
    if (disc < 0.0) return false;
    double s = sqrt(disc);
    double t0 = -b - s, t1 = -b + s;
    return (t0 > 1e-9 && t0 <= tmax) || (t1 > 1e-9 && t1 <= tmax && c > 0.0);
}

static double quadrature_ao(hit_fn hit, const double p[3], const double n[3], double radius)
{
    /* A frame around n, chosen independently of the library's. */
    double a[3] = {fabs(n[0]) < 0.9 ? 1.0 : 0.0, fabs(n[0]) < 0.9 ? 0.0 : 1.0, 0.0};
    double t[3] = {a[1] * n[2] - a[2] * n[1], a[2] * n[0] - a[0] * n[2], a[0] * n[1] - a[1] * n[0]};
    double tl = sqrt(t[0] * t[0] + t[1] * t[1] + t[2] * t[2]);
    for (int k = 0; k < 3; ++k) t[k] /= tl;
    double b[3] = {n[1] * t[2] - n[2] * t[1], n[2] * t[0] - n[0] * t[2], n[0] * t[1] - n[1] * t[0]};
    const int nu = 600, nphi = 1200;
    long open = 0;
    for (int i = 0; i < nu; ++i) {
        double u = ((double)i + 0.5) / (double)nu;
        double st = sqrt(u), ct = sqrt(1.0 - u);
        for (int j = 0; j < nphi; ++j) {
            double phi = 2.0 * PI * ((double)j + 0.5) / (double)nphi;
            double lx = st * cos(phi), ly = st * sin(phi);
            double d[3];
            for (int k = 0; k < 3; ++k) d[k] = lx * t[k] + ly * b[k] + ct * n[k];
            if (!hit(p, d, radius)) ++open;
        }
    }
    return (double)open / ((double)nu * (double)nphi);
}

/* ---- AO against the quadrature --------------------------------------------------------------- */

typedef struct test_point {
    double p[3], n[3];
    const char *what;
} test_point;

static ob_scene *load(const char *name)
{
    ob_scene_desc desc = {.name = name};
    ob_scene *s = ob_load_scene(&desc);
    CHECK(s != NULL, "load %s", name);
    return s;
}

/* `slack`: what the scene's tessellation may move the true value by (0 for flat geometry). */
static void check_against_quadrature(const char *scene_name, hit_fn hit, const test_point *pts, int count,
                                     double slack)
{
    ob_scene *s = load(scene_name);
    if (!s) return;
    float *pos = calloc((size_t)count * 3, sizeof(float));
    float *nrm = calloc((size_t)count * 3, sizeof(float));
    float *ao = calloc((size_t)count, sizeof(float));
    float *se = calloc((size_t)count, sizeof(float));
    for (int i = 0; i < count; ++i)
        for (int k = 0; k < 3; ++k) {
            pos[3 * i + k] = (float)pts[i].p[k];
            nrm[3 * i + k] = (float)pts[i].n[k];
        }
    const float radii[2] = {0.5f, 1.0f};
    for (int r = 0; r < 2; ++r) {
        ob_reference_desc desc = {.spp = 4096, .radius = radii[r], .seed = 7u + (uint64_t)r};
        ob_error err = ob_reference_ao(s, pos, nrm, (size_t)count, &desc, ao, se);
        CHECK(err == OB_OK, "ob_reference_ao %s: %s", scene_name, ob_error_name(err));
        for (int i = 0; i < count; ++i) {
            double q = quadrature_ao(hit, pts[i].p, pts[i].n, radii[r]);
            double tol = 3.0 * (double)se[i] + slack + 2e-3; /* 2e-3: the quadrature's own error */
            printf("  %-16s %-26s R=%.1f  embree %.4f +- %.4f  quadrature %.4f  (%+.1f se)\n", scene_name,
                   pts[i].what, (double)radii[r], (double)ao[i], (double)se[i], q,
                   se[i] > 0.0f ? ((double)ao[i] - q) / (double)se[i] : 0.0);
            CHECK(fabs((double)ao[i] - q) <= tol, "%s %s R=%.1f: embree %.4f vs quadrature %.4f (tol %.4f)",
                  scene_name, pts[i].what, (double)radii[r], (double)ao[i], q, tol);
        }
    }
    free(pos);
    free(nrm);
    free(ao);
    free(se);
    ob_destroy_scene(s);
}

static void test_corner(void)
{
    const test_point pts[] = {
        {{0.05, 0.0, 2.0}, {0.0, 1.0, 0.0}, "floor 0.05 from wall"},
        {{0.1, 0.0, 2.0}, {0.0, 1.0, 0.0}, "floor 0.1 from wall"},
        {{0.25, 0.0, 2.0}, {0.0, 1.0, 0.0}, "floor 0.25 from wall"},
        {{0.5, 0.0, 2.0}, {0.0, 1.0, 0.0}, "floor 0.5 from wall"},
        {{1.0, 0.0, 2.0}, {0.0, 1.0, 0.0}, "floor 1 from wall"},
        {{0.1, 0.0, 0.2}, {0.0, 1.0, 0.0}, "floor in the corner"},
        {{0.0, 0.1, 2.0}, {1.0, 0.0, 0.0}, "wall x=0, 0.1 above floor"},
        {{2.0, 0.3, 0.0}, {0.0, 0.0, 1.0}, "wall z=0, 0.3 above floor"},
        {{0.0, 2.0, 2.0}, {1.0, 0.0, 0.0}, "wall x=0, middle"},
    };
    check_against_quadrature("corner", hit_corner, pts, (int)(sizeof pts / sizeof pts[0]), 0.0);
}

static void test_sphere_on_plane(void)
{
    const double s30 = sin(30.0 * PI / 180.0), c30 = cos(30.0 * PI / 180.0);
    const test_point pts[] = {
        {{0.05, 0.0, 0.0}, {0.0, 1.0, 0.0}, "floor 0.05 from contact"},
        {{0.0, 0.0, 0.1}, {0.0, 1.0, 0.0}, "floor 0.1 from contact"},
        {{0.25, 0.0, 0.0}, {0.0, 1.0, 0.0}, "floor 0.25 from contact"},
        {{-0.5, 0.0, 0.0}, {0.0, 1.0, 0.0}, "floor 0.5 from contact"},
        {{0.0, 0.0, 1.0}, {0.0, 1.0, 0.0}, "floor 1 from contact"},
        {{s30, 1.0 - c30, 0.0}, {s30, -c30, 0.0}, "sphere 30 deg from bottom"},
        {{1.0, 1.0, 0.0}, {1.0, 0.0, 0.0}, "sphere equator"},
    };
    /* The sphere is 48 x 24 flat facets inscribed in the unit sphere: they sit up to
     * 1 - cos(7.5 deg) = 0.009 inside it near the bottom, which moves AO by a few thousandths. */
    check_against_quadrature("sphere-on-plane", hit_sphere_plane, pts, (int)(sizeof pts / sizeof pts[0]), 0.01);
}

/* ---- exact cases ---------------------------------------------------------------------------- */

static void test_open_and_sky(void)
{
    ob_scene *s = load("sphere-on-plane");
    if (!s) return;
    /* A floor point 4 m from the sphere's contact, and a sky point (zero normal). */
    const float pos[6] = {4.0f, 0.0f, 4.0f, 1.0f, 2.0f, 3.0f};
    const float nrm[6] = {0.0f, 1.0f, 0.0f, 0.0f, 0.0f, 0.0f};
    float ao[2] = {0.0f, 0.0f}, se[2] = {-1.0f, -1.0f};
    ob_reference_desc desc = {.spp = 1024, .radius = 1.0f, .seed = 1};
    CHECK(ob_reference_ao(s, pos, nrm, 2, &desc, ao, se) == OB_OK, "open plane");
    CHECK(ao[0] == 1.0f && se[0] == 0.0f, "open plane: ao %.9g se %.9g, want exactly 1 and 0", (double)ao[0],
          (double)se[0]);
    CHECK(ao[1] == 1.0f && se[1] == 0.0f, "sky point: ao %.9g se %.9g", (double)ao[1], (double)se[1]);
    /* stderr_out may be NULL. */
    ao[0] = 0.0f;
    CHECK(ob_reference_ao(s, pos, nrm, 1, &desc, ao, NULL) == OB_OK && ao[0] == 1.0f, "NULL stderr_out");

    /* Argument errors. */
    ob_reference_desc bad = {.radius = 0.0f};
    CHECK(ob_reference_ao(s, pos, nrm, 1, &bad, ao, se) == OB_ERR_INVALID_ARGUMENT, "radius 0");
    bad.radius = 1.0f;
    bad.spp = 1;
    CHECK(ob_reference_ao(s, pos, nrm, 1, &bad, ao, se) == OB_ERR_INVALID_ARGUMENT, "spp 1");
    bad.spp = 0;
    bad.threads = -1;
    CHECK(ob_reference_ao(s, pos, nrm, 1, &bad, ao, se) == OB_ERR_INVALID_ARGUMENT, "threads -1");
    CHECK(ob_reference_ao(NULL, pos, nrm, 1, &desc, ao, se) == OB_ERR_INVALID_ARGUMENT, "NULL scene");
    CHECK(ob_reference_ao(s, NULL, nrm, 1, &desc, ao, se) == OB_ERR_INVALID_ARGUMENT, "NULL positions");
    CHECK(ob_reference_ao(s, NULL, NULL, 0, &desc, NULL, NULL) == OB_OK, "zero points");
    ob_destroy_scene(s);
}

/* ---- determinism ------------------------------------------------------------------------------ */

static void test_determinism(void)
{
    ob_scene *s = load("corner");
    if (!s) return;
    /* Enough points for several chunks per thread, spread over floor and walls near the corner. */
    const size_t n = 2000;
    float *pos = calloc(n * 3, sizeof(float));
    float *nrm = calloc(n * 3, sizeof(float));
    float *a = calloc(n, sizeof(float)), *b = calloc(n, sizeof(float)), *c = calloc(n, sizeof(float));
    float *sa = calloc(n, sizeof(float)), *sb = calloc(n, sizeof(float));
    for (size_t i = 0; i < n; ++i) {
        int axis = (int)(i % 3);
        float u = 0.01f + 1.5f * (float)((i * 37u) % 101u) / 101.0f;
        float v = 0.01f + 1.5f * (float)((i * 53u) % 97u) / 97.0f;
        float p[3] = {u, v, u + v};
        p[axis] = 0.0f;
        for (int k = 0; k < 3; ++k) {
            pos[3 * i + k] = p[k];
            nrm[3 * i + k] = k == axis ? 1.0f : 0.0f;
        }
    }
    ob_reference_desc d1 = {.spp = 64, .radius = 0.5f, .threads = 1, .seed = 42};
    ob_reference_desc d2 = d1;
    d2.threads = 2;
    CHECK(ob_reference_ao(s, pos, nrm, n, &d1, a, sa) == OB_OK, "1 thread");
    CHECK(ob_reference_ao(s, pos, nrm, n, &d1, c, NULL) == OB_OK, "1 thread again");
    CHECK(ob_reference_ao(s, pos, nrm, n, &d2, b, sb) == OB_OK, "2 threads");
    CHECK(memcmp(a, c, n * sizeof(float)) == 0, "same seed twice: different bytes");
    CHECK(memcmp(a, b, n * sizeof(float)) == 0, "1 vs 2 threads: different AO bytes");
    CHECK(memcmp(sa, sb, n * sizeof(float)) == 0, "1 vs 2 threads: different stderr bytes");
    ob_reference_desc d3 = d1;
    d3.seed = 43;
    CHECK(ob_reference_ao(s, pos, nrm, n, &d3, c, NULL) == OB_OK, "seed 43");
    CHECK(memcmp(a, c, n * sizeof(float)) != 0, "another seed gives the same bytes");
    free(pos);
    free(nrm);
    free(a);
    free(b);
    free(c);
    free(sa);
    free(sb);
    ob_destroy_scene(s);
}

/* ---- one bounce ------------------------------------------------------------------------------- */

static void test_bounce(void)
{
    ob_scene *s = load("corner");
    if (!s) return;
    const float pos[6] = {0.1f, 0.0f, 2.0f, 3.5f, 0.0f, 3.5f};
    const float nrm[6] = {0.0f, 1.0f, 0.0f, 0.0f, 1.0f, 0.0f};
    const float albedo[6] = {0.5f, 0.25f, 1.0f, 0.5f, 0.25f, 1.0f};
    float rgb[6] = {0.0f};

    /* Ambient only (a black light): albedo x ambient x AO_R, the same rays as ob_reference_ao. */
    ob_light black = {.type = OB_LIGHT_DIRECTIONAL, .direction = {0.0f, 1.0f, 0.0f}, .intensity = 0.0f};
    const float ambient[3] = {1.0f, 2.0f, 0.5f};
    ob_reference_desc desc = {.spp = 2048, .radius = 0.5f, .seed = 3};
    float ao[2] = {0.0f, 0.0f}, se[2] = {0.0f, 0.0f};
    CHECK(ob_reference_bounce(s, &black, 1, ambient, pos, nrm, albedo, 2, &desc, rgb) == OB_OK, "bounce ambient");
    CHECK(ob_reference_ao(s, pos, nrm, 2, &desc, ao, se) == OB_OK, "ao for bounce");
    for (int i = 0; i < 2; ++i)
        for (int k = 0; k < 3; ++k)
            CHECK_NEAR(rgb[3 * i + k], albedo[3 * i + k] * ambient[k] * ao[i], 1e-3 * ambient[k],
                       "ambient term = albedo x ambient x AO_R");

    /* A directional light straight down, no ambient: the open floor point (3.5, 0, 3.5) sees only
     * the light (its bounce rays reach nothing within R), and the one beside the wall gets the
     * light plus light bounced off the wall... which faces away from a light straight down: none.
     * Tilt the light toward +x so the wall x = 0 is lit, and the wall's bounce must add. */
    ob_light sun = {.type = OB_LIGHT_DIRECTIONAL, .direction = {1.0f, 1.0f, 0.0f}, .color = {1.0f, 1.0f, 1.0f},
                    .intensity = 2.0f};
    CHECK(ob_reference_bounce(s, &sun, 1, NULL, pos, nrm, albedo, 2, &desc, rgb) == OB_OK, "bounce sun");
    float direct = 2.0f * (float)(1.0 / sqrt(2.0)); /* intensity x n.l */
    for (int k = 0; k < 3; ++k)
        CHECK_NEAR(rgb[3 + k], albedo[3 + k] * direct, 1e-5, "open point: direct light only");
    for (int k = 0; k < 3; ++k)
        CHECK(rgb[k] > albedo[k] * direct * 1.05f, "floor beside a lit wall gains bounce: %g vs direct %g",
              (double)rgb[k], (double)(albedo[k] * direct));

    /* A point light's 1/d^2 matches the CPU light function. */
    ob_light lamp = {.type = OB_LIGHT_POINT, .position = {3.5f, 2.0f, 3.5f}, .color = {1.0f, 0.5f, 0.25f},
                     .intensity = 8.0f};
    float l[3] = {0.0f}, lr[3] = {0.0f}, dist = 0.0f;
    CHECK(ob_reference_light(&lamp, pos + 3, nrm + 3, l, &dist, lr), "lamp reaches");
    CHECK_NEAR(dist, 2.0f, 1e-6, "lamp distance");
    CHECK_NEAR(lr[0], 8.0f / 4.0f, 1e-6, "lamp 1/d^2");
    CHECK(ob_reference_bounce(s, &lamp, 1, NULL, pos + 3, nrm + 3, albedo + 3, 1, &desc, rgb) == OB_OK, "lamp");
    CHECK_NEAR(rgb[1], albedo[4] * 0.5f * 2.0f, 1e-5, "lamp radiance");
    CHECK(ob_reference_bounce(s, &lamp, 9, NULL, pos, nrm, albedo, 1, &desc, rgb) == OB_ERR_INVALID_ARGUMENT,
          "9 lights");
    ob_destroy_scene(s);
}

/* ---- G-buffer points ------------------------------------------------------------------------ */

static void test_points(void)
{
    /* A camera at eye looking along -Z of an orthonormal frame (right, up, back), and an
     * off-centre (jittered) projection so P20, P21 matter. */
    const float eye[3] = {1.0f, 2.0f, 3.0f};
    float back[3] = {0.3f, 0.4f, 0.866f};
    float bl = sqrtf(back[0] * back[0] + back[1] * back[1] + back[2] * back[2]);
    for (int k = 0; k < 3; ++k) back[k] /= bl;
    float right[3] = {back[2], 0.0f, -back[0]};
    float rl = sqrtf(right[0] * right[0] + right[2] * right[2]);
    right[0] /= rl;
    right[2] /= rl;
    float up[3] = {back[1] * right[2] - back[2] * right[1], back[2] * right[0] - back[0] * right[2],
                   back[0] * right[1] - back[1] * right[0]};
    float inv_view[16] = {right[0], right[1], right[2], 0.0f, up[0], up[1], up[2], 0.0f,
                          back[0],  back[1],  back[2],  0.0f, eye[0], eye[1], eye[2], 1.0f};
    const float p00 = 1.2f, p11 = 1.6f, p20 = 0.01f, p21 = -0.02f;
    const float proj_info[4] = {1.0f / p00, 1.0f / p11, p20, p21};
    enum { W = 8, H = 6 };
    float depth[W * H] = {0.0f}, vn[W * H * 3] = {0.0f}, pos[W * H * 3] = {0.0f}, nrm[W * H * 3] = {0.0f};
    const int px = 5, py = 2; /* row 2 from the bottom */
    const int i = py * W + px;
    depth[i] = 3.25f;
    vn[3 * i + 0] = 0.0f;
    vn[3 * i + 1] = 0.6f;
    vn[3 * i + 2] = 0.8f;
    CHECK(ob_reference_points(depth, vn, W, H, proj_info, inv_view, pos, nrm) == OB_OK, "points");
    /* Forward: world -> view (R^T (w - eye)) -> clip with the projection -> ndc -> pixel. */
    float rel[3] = {pos[3 * i] - eye[0], pos[3 * i + 1] - eye[1], pos[3 * i + 2] - eye[2]};
    float v[3] = {rel[0] * right[0] + rel[1] * right[1] + rel[2] * right[2],
                  rel[0] * up[0] + rel[1] * up[1] + rel[2] * up[2],
                  rel[0] * back[0] + rel[1] * back[1] + rel[2] * back[2]};
    float w = -v[2];
    float ndc_x = (p00 * v[0] + p20 * v[2]) / w, ndc_y = (p11 * v[1] + p21 * v[2]) / w;
    CHECK_NEAR(w, 3.25f, 1e-5, "round trip: depth");
    CHECK_NEAR((ndc_x + 1.0f) * 0.5f * W, px + 0.5f, 1e-4, "round trip: pixel x centre");
    CHECK_NEAR((ndc_y + 1.0f) * 0.5f * H, py + 0.5f, 1e-4, "round trip: pixel y centre");
    float nv[3] = {nrm[3 * i] * right[0] + nrm[3 * i + 1] * right[1] + nrm[3 * i + 2] * right[2],
                   nrm[3 * i] * up[0] + nrm[3 * i + 1] * up[1] + nrm[3 * i + 2] * up[2],
                   nrm[3 * i] * back[0] + nrm[3 * i + 1] * back[1] + nrm[3 * i + 2] * back[2]};
    CHECK_NEAR(nv[0], 0.0f, 1e-5, "round trip: normal x");
    CHECK_NEAR(nv[1], 0.6f, 1e-5, "round trip: normal y");
    CHECK_NEAR(nv[2], 0.8f, 1e-5, "round trip: normal z");
    /* Sky pixels: zero position and normal, which ob_reference_ao skips. */
    CHECK(nrm[0] == 0.0f && nrm[1] == 0.0f && nrm[2] == 0.0f && pos[0] == 0.0f, "sky pixel zeroed");
    CHECK(ob_reference_points(depth, vn, 0, H, proj_info, inv_view, pos, nrm) == OB_ERR_BAD_SIZE, "bad size");
    CHECK(ob_reference_points(NULL, vn, W, H, proj_info, inv_view, pos, nrm) == OB_ERR_INVALID_ARGUMENT, "NULL");
}

int main(void)
{
    test_corner();
    test_sphere_on_plane();
    test_open_and_sky();
    test_determinism();
    test_bounce();
    test_points();
    return check_finish("reference");
}
