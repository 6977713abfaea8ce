/* The quality gate (issue 15): every registered method (`none` included), at its defaults with
 * the default filter, on two built-in views at 64 x 64, graded by the RMSE of the filtered AO
 * (OB_IMAGE_AO_F32; a directional method's is the mean of M's channels) against AO_R ray traced
 * here from the same G-buffer points (ob_reference_ao, 256 rays, fixed seed, the scene's
 * suggested radius, which every method's radius follows by default), over the non-sky pixels.
 * A method fails when its RMSE on a view rises above the threshold in
 * tests/quality_thresholds.txt (the rule that sets a threshold, and when it may change, is at
 * the top of that file and in docs/testing.md). The method list comes from the registry: a
 * method with no threshold fails, and so does a line naming no registered method or no view,
 * so adding a method means measuring it here and writing its lines.
 *
 * Usage: test_quality [THRESHOLDS]  (default: the source tree's tests/quality_thresholds.txt) */
#include <cglm/cglm.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "check.h"
#include "obscura/eval.h"

#ifndef OB_QUALITY_THRESHOLDS
#define OB_QUALITY_THRESHOLDS "tests/quality_thresholds.txt"
#endif

/* Small: llvmpipe renders two frames per method and view, and Embree traces 256 rays per pixel. */
enum { W = 64, H = 64, SPP = 256 };
static const uint64_t ref_seed = 15; /* the number: any fixed seed will do */

typedef struct view_def {
    const char *scene, *camera;
    const char *name; /* "scene/camera", as the thresholds file names it */
} view_def;

/* The Cornell box (R 0.1: the blocks' contact creases, the box's inner edges) and the open
 * corner of three planes (R 0.5: two-plane creases, the three-plane vertex, open floor, sky). */
static const view_def views[] = {
    {"cornell", "front", "cornell/front"},
    {"corner", "diagonal", "corner/diagonal"},
};
enum { VIEW_COUNT = sizeof views / sizeof views[0] };

/* ---- the thresholds file ---------------------------------------------------------------------- */

enum { MAX_THRESHOLDS = 256 };

typedef struct threshold {
    char method[64], view[64];
    double value;
    int line;
} threshold;

typedef struct threshold_file {
    threshold rows[MAX_THRESHOLDS];
    int count;
} threshold_file;

static bool known_view(const char *name)
{
    for (int v = 0; v < VIEW_COUNT; ++v)
        if (!strcmp(views[v].name, name)) return true;
    return false;
}

/* "cornell/front, corner/diagonal": the views, for messages. */
static const char *view_list(void)
{
    static char list[256];
    size_t used = 0;
    for (int v = 0; v < VIEW_COUNT && used < sizeof list; ++v)
        used += (size_t)snprintf(list + used, sizeof list - used, "%s%s", v ? ", " : "", views[v].name);
    return list;
}

/* "METHOD VIEW RMSE" per line; '#' starts a comment. Every malformed, duplicate or unknown line
 * is a failed CHECK naming the file and line. */
static bool read_thresholds(const char *path, threshold_file *tf)
{
    memset(tf, 0, sizeof *tf);
    FILE *f = fopen(path, "r");
    CHECK(f != NULL, "thresholds file %s could not be opened", path);
    if (!f) return false;
    char line[512];
    int line_no = 0;
    while (fgets(line, sizeof line, f)) {
        ++line_no;
        char *hash = strchr(line, '#');
        if (hash) *hash = '\0';
        char method[64] = "", view[64] = "", value[64] = "", extra[8] = "";
        int n = sscanf(line, "%63s %63s %63s %7s", method, view, value, extra);
        if (n <= 0) continue;
        char *end = NULL;
        double v = n >= 3 ? strtod(value, &end) : NAN;
        bool ok = n == 3 && end && *end == '\0' && v > 0.0 && v <= 1.0;
        CHECK(ok, "%s:%d: expected 'METHOD VIEW RMSE' with 0 < RMSE <= 1", path, line_no);
        if (!ok) continue;
        bool method_ok = ob_find_method(method) >= 0, view_ok = known_view(view);
        CHECK(method_ok, "%s:%d: unknown method '%s' (not in the registry: remove the line)", path, line_no, method);
        CHECK(view_ok, "%s:%d: unknown view '%s' (test_quality renders %s)", path, line_no, view, view_list());
        if (!method_ok || !view_ok) continue;
        bool dup = false;
        for (int i = 0; i < tf->count; ++i)
            dup |= !strcmp(tf->rows[i].method, method) && !strcmp(tf->rows[i].view, view);
        CHECK(!dup, "%s:%d: a second threshold for %s on %s", path, line_no, method, view);
        CHECK(tf->count < MAX_THRESHOLDS, "%s:%d: more than %d thresholds", path, line_no, MAX_THRESHOLDS);
        if (dup || tf->count >= MAX_THRESHOLDS) continue;
        threshold *t = &tf->rows[tf->count++];
        snprintf(t->method, sizeof t->method, "%s", method);
        snprintf(t->view, sizeof t->view, "%s", view);
        t->value = v;
        t->line = line_no;
    }
    fclose(f);
    return true;
}

static threshold *find_threshold(threshold_file *tf, const char *method, const char *view)
{
    for (int i = 0; i < tf->count; ++i)
        if (!strcmp(tf->rows[i].method, method) && !strcmp(tf->rows[i].view, view)) return &tf->rows[i];
    return NULL;
}

/* ---- one view ---------------------------------------------------------------------------------- */

typedef struct view_ref {
    float *depth, *normals, *pos, *wn, *ao_r, *ao_r_err;
    uint8_t *mask; /* non-sky pixels */
    size_t pixels;
    double sigma; /* RMS standard error of AO_R over the mask */
} view_ref;

static void view_ref_free(view_ref *v)
{
    free(v->depth);
    free(v->normals);
    free(v->pos);
    free(v->wn);
    free(v->ao_r);
    free(v->ao_r_err);
    free(v->mask);
    memset(v, 0, sizeof *v);
}

/* The standard error of an RMSE against AO_R that comes from AO_R's own noise (delta method):
 * with d_i = ao_i - AO_R_i and s_i the standard error of AO_R_i, independent across pixels,
 * var(MSE) = sum(4 d_i^2 s_i^2 + 2 s_i^4) / N^2 and sd(RMSE) = sd(MSE) / (2 RMSE). Checked against
 * the spread of each row's RMSE over 10 reference seeds: 0.00045 predicted, 0.00056 measured
 * (gtao on cornell/front), 0.00071 and 0.00067 (none on corner/diagonal), 0.00018 both (crytek). */
static double rmse_sigma(const float *ao, const view_ref *v, double rmse)
{
    double var = 0.0;
    for (size_t i = 0; i < (size_t)W * H; ++i) {
        if (!v->mask[i]) continue;
        double d = (double)ao[i] - v->ao_r[i], s2 = (double)v->ao_r_err[i] * v->ao_r_err[i];
        var += 4.0 * d * d * s2 + 2.0 * s2 * s2;
    }
    return rmse > 0.0 ? sqrt(var) / (double)v->pixels / (2.0 * rmse) : 0.0;
}

/* The file's rule: the measured RMSE + max(0.01, 3 x its standard error from the reference),
 * rounded up to 0.005. Printed beside each row, so that a new method's lines can be copied. */
static double rule_threshold(double rmse, double sigma)
{
    return ceil((rmse + fmax(0.01, 3.0 * sigma)) * 200.0 - 1e-9) / 200.0;
}

/* AO_R from the G-buffer of the frame just rendered by `r` (every method sees the same one). */
static bool make_reference(ob_renderer *r, const ob_scene *scene, const ob_camera *cam, view_ref *v)
{
    size_t n = (size_t)W * H;
    v->depth = malloc(n * sizeof(float));
    v->normals = malloc(n * 3 * sizeof(float));
    v->pos = malloc(n * 3 * sizeof(float));
    v->wn = malloc(n * 3 * sizeof(float));
    v->ao_r = malloc(n * sizeof(float));
    v->ao_r_err = malloc(n * sizeof(float));
    v->mask = malloc(n);
    bool ok = v->depth && v->normals && v->pos && v->wn && v->ao_r && v->ao_r_err && v->mask &&
              ob_read_image(r, OB_IMAGE_DEPTH_F32, v->depth, n * sizeof(float)) == OB_OK &&
              ob_read_image(r, OB_IMAGE_NORMAL_F32, v->normals, n * 3 * sizeof(float)) == OB_OK;
    CHECK(ok, "read back the G-buffer");
    if (!ok) return false;
    /* Only fov and aspect reach proj_info (P20 = P21 = 0): any near/far will do. */
    vec3 eye, target, up = {0.0f, 1.0f, 0.0f};
    memcpy(eye, cam->eye, sizeof eye);
    memcpy(target, cam->target, sizeof target);
    if (cam->up[0] != 0.0f || cam->up[1] != 0.0f || cam->up[2] != 0.0f) memcpy(up, cam->up, sizeof up);
    mat4 view, proj, inv_view;
    glm_lookat(eye, target, up, view);
    glm_perspective(glm_rad(cam->fov_y_deg > 0.0f ? cam->fov_y_deg : 60.0f), (float)W / (float)H, 0.05f, 20.0f, proj);
    glm_mat4_inv(view, inv_view);
    const float info[4] = {1.0f / proj[0][0], 1.0f / proj[1][1], proj[2][0], proj[2][1]};
    ok = ob_reference_points(v->depth, v->normals, W, H, info, (const float *)inv_view, v->pos, v->wn) == OB_OK;
    CHECK(ok, "reference points");
    const float radius = ob_query_scene_ao_radius(scene);
    const ob_reference_desc rd = {.spp = SPP, .radius = radius, .seed = ref_seed};
    ok = ok && ob_reference_ao(scene, v->pos, v->wn, n, &rd, v->ao_r, v->ao_r_err) == OB_OK;
    CHECK(ok, "reference AO");
    if (!ok) return false;
    double sum_var = 0.0;
    for (size_t i = 0; i < n; ++i) {
        v->mask[i] = v->depth[i] > 0.0f;
        v->pixels += v->mask[i];
        if (v->mask[i]) sum_var += (double)v->ao_r_err[i] * v->ao_r_err[i];
    }
    v->sigma = v->pixels ? sqrt(sum_var / (double)v->pixels) : 0.0;
    /* Both views are mostly geometry: a camera preset that moved off the scene would grade
     * nothing. */
    CHECK(v->pixels >= n / 4, "more than a quarter of the frame is geometry (%zu of %zu pixels)", v->pixels, n);
    return v->pixels > 0;
}

/* Each method on `vd`: two frames (bit-identical, or the threshold's margin would have to cover
 * the method's own noise), the RMSE of the first against AO_R, a table row, the gate. */
static void grade_view(ob_context *ctx, const view_def *vd, threshold_file *tf, const char *path)
{
    ob_scene *scene = ob_load_scene(&(ob_scene_desc){.name = vd->scene});
    ob_camera cam = {0};
    bool found = scene && ob_find_camera(scene, vd->camera, &cam) == OB_OK;
    CHECK(found, "scene %s with camera %s", vd->scene, vd->camera);
    ob_renderer *r = found ? ob_make_renderer(ctx, &(ob_renderer_desc){.width = W, .height = H}) : NULL;
    CHECK(!found || r != NULL, "renderer");
    bool uploaded = r && ob_renderer_set_scene(r, scene) == OB_OK;
    CHECK(!r || uploaded, "upload %s", vd->scene);
    size_t n = (size_t)W * H;
    float *ao = uploaded ? malloc(n * sizeof(float)) : NULL, *again = uploaded ? malloc(n * sizeof(float)) : NULL;
    CHECK(!uploaded || (ao && again), "memory");
    if (!ao || !again) {
        free(ao);
        free(again);
        ob_destroy_renderer(r);
        ob_destroy_scene(scene);
        return;
    }
    view_ref ref = {0};
    bool have_ref = false;
    for (int m = 0; m < ob_method_count(); ++m) {
        const char *name = ob_method_at(m)->name;
        ob_settings s;
        CHECK(ob_settings_init(&s, name) == OB_OK, "%s: settings", name);
        ob_error e = ob_render_frame(r, &cam, &s);
        bool ok = e == OB_OK && ob_read_image(r, OB_IMAGE_AO_F32, ao, n * sizeof(float)) == OB_OK &&
                  ob_render_frame(r, &cam, &s) == OB_OK &&
                  ob_read_image(r, OB_IMAGE_AO_F32, again, n * sizeof(float)) == OB_OK;
        const char *msg = NULL;
        ob_get_error(&msg);
        CHECK(ok, "%s on %s: %s", name, vd->name, msg);
        if (!ok) continue;
        CHECK(memcmp(ao, again, n * sizeof(float)) == 0, "%s on %s: two frames differ", name, vd->name);
        if (!have_ref && !(have_ref = make_reference(r, scene, &cam, &ref))) break;
        ob_metrics mt;
        ok = ob_compare_images(ao, ref.ao_r, ref.mask, W, H, 1, &mt) == OB_OK && isfinite(mt.rmse);
        CHECK(ok, "%s on %s: RMSE", name, vd->name);
        if (!ok) continue;
        threshold *t = find_threshold(tf, name, vd->name);
        double sigma = rmse_sigma(ao, &ref, mt.rmse), rule = rule_threshold(mt.rmse, sigma);
        printf("  %-14s %-16s %7.4f %8.5f %+8.4f %9.3f %6.3f%s\n", name, vd->name, mt.rmse, sigma, mt.bias,
               t ? t->value : NAN, rule, t && mt.rmse > t->value ? "  FAIL" : "");
        CHECK(t != NULL,
              "%s on %s has no threshold in %s: add the line '%s %s %.3f' (RMSE %.4f + the file's margin)", name,
              vd->name, path, name, vd->name, rule, mt.rmse);
        if (!t) continue;
        CHECK(mt.rmse <= t->value,
              "%s on %s: RMSE %.4f against AO_R is above its threshold %.3f (%s:%d): a quality regression, or a "
              "change that needs a commit saying why the threshold moves",
              name, vd->name, mt.rmse, t->value, path, t->line);
    }
    if (have_ref)
        printf("  %s: %zu non-sky pixels, R %.3g, AO_R at %d rays: per-pixel standard error RMS %.4f\n", vd->name,
               ref.pixels, (double)ob_query_scene_ao_radius(scene), SPP, ref.sigma);
    free(ao);
    free(again);
    view_ref_free(&ref);
    ob_destroy_renderer(r);
    ob_destroy_scene(scene);
}

int main(int argc, char **argv)
{
    const char *path = argc > 1 ? argv[1] : OB_QUALITY_THRESHOLDS;
    threshold_file *tf = calloc(1, sizeof *tf);
    if (!tf || !read_thresholds(path, tf)) {
        free(tf);
        return check_finish("test_quality");
    }
    ob_context *ctx = check_context();
    if (!ctx) {
        free(tf);
        return 1;
    }
    /* sd: the RMSE's standard error from AO_R's noise; rule: the threshold the file's rule gives. */
    printf("  %-14s %-16s %7s %8s %8s %9s %6s\n", "method", "view", "RMSE", "sd", "bias", "threshold", "rule");
    for (int v = 0; v < VIEW_COUNT; ++v) grade_view(ctx, &views[v], tf, path);
    free(tf);
    ob_destroy_context(ctx);
    return check_finish("test_quality");
}
