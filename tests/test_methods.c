/* Every AO method in the registry on the analytic scenes (issue 3): open planes, the corner
 * crease, concave vs convex edges, convergence with the sample count, determinism. The method
 * list comes from the registry, so a new method is tested the moment it is registered; only
 * documented exceptions (Crytek's self-occlusion) are named here. */
#include <cglm/cglm.h>
#include <stdlib.h>
#include <string.h>

#include "check.h"
#include "methods/method.h"
#include "obscura/eval.h"

enum { W = 192, H = 144 };

static const ob_camera corner_cam = {
    .eye = {5.0f, 3.0f, 5.0f}, .target = {0.8f, 0.4f, 0.8f}, .up = {0.0f, 1.0f, 0.0f},
    .fov_y_deg = 70.0f, .near_z = 0.1f, .far_z = 100.0f, .name = "test"};

/* The published Cornell camera, in metres. */
static const ob_camera cornell_cam = {
    .eye = {0.278f, 0.273f, -0.8f}, .target = {0.278f, 0.273f, 0.0f}, .up = {0.0f, 1.0f, 0.0f},
    .fov_y_deg = 39.3f, .near_z = 0.05f, .far_z = 5.0f, .name = "test"};

static bool project(const ob_camera *cam, const float p[3], int *px, int *py)
{
    mat4 view, proj, vp;
    vec3 eye, target, up;
    memcpy(eye, cam->eye, sizeof eye);
    memcpy(target, cam->target, sizeof target);
    memcpy(up, cam->up, sizeof up);
    glm_lookat(eye, target, up, view);
    glm_perspective(glm_rad(cam->fov_y_deg), (float)W / (float)H, cam->near_z, cam->far_z, proj);
    glm_mat4_mul(proj, view, vp);
    vec4 wp = {p[0], p[1], p[2], 1.0f}, clip;
    glm_mat4_mulv(vp, wp, clip);
    if (clip[3] <= 0.0f) return false;
    *px = (int)((clip[0] / clip[3] * 0.5f + 0.5f) * W);
    *py = (int)((clip[1] / clip[3] * 0.5f + 0.5f) * H);
    return *px >= 0 && *px < W && *py >= 0 && *py < H;
}

static float *render(ob_renderer *r, const ob_camera *cam, const ob_settings *s, ob_image_kind kind)
{
    float *ao = malloc(ob_image_size(r, kind));
    ob_error e = ob_render_frame(r, cam, s);
    const char *msg = NULL;
    ob_get_error(&msg);
    CHECK(e == OB_OK, "%s frame: %s", ob_method_at(s->method)->name, msg);
    CHECK(ob_read_image(r, kind, ao, ob_image_size(r, kind)) == OB_OK, "read");
    return ao;
}

static float at(const float *ao, const ob_camera *cam, float x, float y, float z)
{
    const float p[3] = {x, y, z};
    int px = 0, py = 0;
    if (!project(cam, p, &px, &py)) return NAN;
    return ao[py * W + px];
}

/* The method's own behaviour: the seeds' 4x4 box blur after it (the default geometry-aware
 * filter is tested in test_filters.c). */
static void settings_for(ob_settings *s, const char *method, const char *radius)
{
    ob_settings_init(s, method);
    ob_settings_set_filter(s, "box4");
    if (!radius) return;
    char set[64];
    snprintf(set, sizeof set, "radius=%s", radius);
    ob_settings_set(s, set);
}

/* `extra`: one more "PARAM=VALUE" of the method's, or NULL. */
static void test_corner_with(ob_renderer *r, const char *m, const char *extra)
{
    ob_settings s;
    settings_for(&s, m, "1.5");
    if (extra) {
        char set[64];
        snprintf(set, sizeof set, "%s.%s", m, extra);
        CHECK(ob_settings_set(&s, set) == OB_OK, "%s", set);
    }
    bool crytek = !strcmp(m, "crytek");
    float *ao = render(r, &corner_cam, &s, OB_IMAGE_AO_F32);

    /* Open floor, two radii from both walls. Crytek's sphere is half inside any plane: Puri 2024
     * §2.2 puts flat surfaces at about one half. */
    float open = at(ao, &corner_cam, 3.3f, 0.0f, 3.3f);
    if (crytek)
        CHECK(open > 0.35f && open < 0.65f, "%s: open plane %g near its self-occlusion level 0.5", m, (double)open);
    else
        CHECK(open > 0.9f, "%s: open plane %g > 0.9", m, (double)open);

    /* Toward the crease with the wall x = 0: monotone, and darker by a clear margin. */
    const float xs[] = {1.8f, 1.2f, 0.8f, 0.5f, 0.3f, 0.15f, 0.08f};
    float prev = 2.0f, first = 0.0f, last = 0.0f;
    printf("  %-8s open %.3f  crease walk%s%s:", m, (double)open, extra ? " with " : "", extra ? extra : "");
    for (size_t i = 0; i < sizeof xs / sizeof xs[0]; ++i) {
        float v = at(ao, &corner_cam, xs[i], 0.0f, 2.0f);
        printf(" %.3f", (double)v);
        /* 0.03: what the 4x4 noise leaves after the 4x4 blur at this size. */
        CHECK(v <= prev + 0.03f, "%s: AO %g at %g m from the wall after %g further out", m, (double)v, (double)xs[i],
              (double)prev);
        if (i == 0) first = v;
        last = v;
        prev = v;
    }
    printf("\n");
    /* Relative to the far value, so Crytek's 0.5 plane level is judged like the others' 1. */
    CHECK(first - last > 0.1f * first, "%s: the crease darkens (%g far, %g near)", m, (double)first, (double)last);
    free(ao);

    if (crytek && !extra) {
        ob_settings c = s;
        CHECK(ob_settings_set(&c, "crytek.correction=on") == OB_OK, "correction on");
        ao = render(r, &corner_cam, &c, OB_IMAGE_AO_F32);
        float corrected = at(ao, &corner_cam, 3.3f, 0.0f, 3.3f);
        CHECK(corrected > 0.85f, "crytek with SSDO thesis's correction: open plane %g", (double)corrected);
        free(ao);
    }
}

static void test_corner(ob_renderer *r, const char *m) { test_corner_with(r, m, NULL); }

/* Concave (block meets floor) against convex (block's top edge) on the Cornell box's short
 * block, front face, raw AO averaged along the edge. */
static void test_edges(ob_renderer *r, const char *m)
{
    ob_settings s;
    settings_for(&s, m, NULL);
    ob_settings_set_filter(&s, "none");
    float *ao = render(r, &cornell_cam, &s, OB_IMAGE_AO_RAW_F32);
    float concave = 0.0f, convex = 0.0f;
    int n = 0;
    for (float t = 0.3f; t <= 0.71f; t += 0.1f, ++n) {
        /* The face from (130, 65) to (290, 114) mm, 165 mm tall, facing the camera. */
        float x = (130.0f + 160.0f * t) * 1e-3f, z = (65.0f + 49.0f * t) * 1e-3f;
        concave += at(ao, &cornell_cam, x, 0.012f, z - 0.002f);
        convex += at(ao, &cornell_cam, x, 0.150f, z - 0.002f);
    }
    concave /= (float)n;
    convex /= (float)n;
    printf("  %-8s concave %.3f convex %.3f\n", m, (double)concave, (double)convex);
    CHECK(concave + 0.05f < convex, "%s: concave edge %g should be darker than the convex edge %g", m, (double)concave,
          (double)convex);
    free(ao);
}

/* Pixel-to-pixel variance of the raw AO on a floor patch the wall partly occludes: the noise
 * that more samples must reduce. Differences of neighbours cancel the smooth falloff. */
static double patch_noise(ob_renderer *r, const ob_settings *s)
{
    float *ao = render(r, &corner_cam, s, OB_IMAGE_AO_RAW_F32);
    const float p[3] = {0.5f, 0.0f, 2.0f};
    int cx = 0, cy = 0;
    project(&corner_cam, p, &cx, &cy);
    double sum = 0.0;
    int n = 0;
    for (int y = cy - 4; y <= cy + 4; ++y)
        for (int x = cx - 4; x < cx + 4; ++x) {
            double d = (double)ao[y * W + x + 1] - (double)ao[y * W + x];
            sum += d * d;
            ++n;
        }
    free(ao);
    return sum / n;
}

static void test_convergence(ob_renderer *r, const char *m)
{
    ob_settings s;
    settings_for(&s, m, "1.5");
    ob_settings_set_filter(&s, "none");
    CHECK(ob_settings_set_samples(&s, 12) == OB_OK, "%s: 12 samples", m);
    double low = patch_noise(r, &s);
    CHECK(ob_settings_set_samples(&s, 64) == OB_OK, "%s: 64 samples", m);
    double high = patch_noise(r, &s);
    printf("  %-8s raw neighbour variance: 12 samples %.5f, 64 samples %.5f\n", m, low, high);
    CHECK(high < low * 0.75, "%s: noise does not fall with samples (%.5f at 12, %.5f at 64)", m, low, high);
}

static void test_determinism(ob_renderer *r, const char *m)
{
    ob_settings s;
    settings_for(&s, m, NULL);
    float *a = render(r, &corner_cam, &s, OB_IMAGE_AO_RAW_F32);
    float *b = render(r, &corner_cam, &s, OB_IMAGE_AO_RAW_F32);
    CHECK(memcmp(a, b, ob_image_size(r, OB_IMAGE_AO_RAW_F32)) == 0, "%s: two frames differ", m);
    int outside = 0;
    for (int i = 0; i < W * H; ++i) outside += !(a[i] >= 0.0f && a[i] <= 1.0f);
    CHECK(outside == 0, "%s: %d AO values outside [0,1]", m, outside);
    free(a);
    free(b);
}

/* radius_scale widens the search and nothing else: scale 2 at the scene's radius is the same
 * frame as the radius set to twice it, for every method with a radius. */
static void test_radius_scale(ob_renderer *r, const char *m, float scene_radius)
{
    ob_settings a, b;
    settings_for(&a, m, NULL);
    char twice[32];
    snprintf(twice, sizeof twice, "%g", 2.0 * scene_radius);
    settings_for(&b, m, twice);
    if (isnan(ob_settings_get(&b, "radius"))) return; /* no radius parameter (none) */
    CHECK(ob_settings_set(&a, "radius_scale=2") == OB_OK && ob_settings_get(&a, "radius_scale") == 2.0f,
          "%s: radius_scale=2", m);
    float *x = render(r, &corner_cam, &a, OB_IMAGE_AO_RAW_F32);
    float *y = render(r, &corner_cam, &b, OB_IMAGE_AO_RAW_F32);
    ob_settings c;
    settings_for(&c, m, NULL);
    float *z = render(r, &corner_cam, &c, OB_IMAGE_AO_RAW_F32);
    size_t bytes = ob_image_size(r, OB_IMAGE_AO_RAW_F32);
    CHECK(memcmp(x, y, bytes) == 0, "%s: radius_scale 2 differs from radius %s", m, twice);
    CHECK(memcmp(x, z, bytes) != 0, "%s: radius_scale 2 changed nothing", m);
    free(x);
    free(y);
    free(z);
}

/* The cache-aware tap programs (issue 18; methods/deinterleave.c, shaders/taps.glsl), for every
 * method with a `deinterleave` or `depth_mips` parameter, on the engine path (ob_compute_ao) at
 * 99 x 73, a size whose last texel row and column of the 16 layers hold fewer classes and whose
 * MIP levels are odd: the output texture is cleared to -1 first, so a pixel no class wrote is
 * seen. Against the plain program on the same textures: near taps are the same pixels and far taps
 * move (by up to 2 pixels deinterleaved, to the pixel a coarser MIP texel picked), so the images
 * may differ pixel by pixel but not on average (no class may read lighter or darker as a whole),
 * and the sky and an open plane stay open (test_corner with it on). At five times cornell's
 * radius, so that R reaches past the 20 px from which taps read level 1 of the chain on the nearer
 * walls; a program that changes nothing (the chain not read) fails. */
enum { DW = 99, DH = 73 };
#define TAPS_RADIUS "0.5"

/* An engine's textures at DW x DH: tex[0] its R32F linear depth, tex[1] its normals (xyzw per
 * pixel), tex[2] an R32F output. */
static void engine_textures(const float *depth, const float *n4, GLuint tex[3])
{
    glCreateTextures(GL_TEXTURE_2D, 3, tex);
    glTextureStorage2D(tex[0], 1, GL_R32F, DW, DH);
    glTextureStorage2D(tex[1], 1, GL_RGBA32F, DW, DH);
    glTextureStorage2D(tex[2], 1, GL_R32F, DW, DH);
    glTextureSubImage2D(tex[0], 0, 0, 0, DW, DH, GL_RED, GL_FLOAT, depth);
    glTextureSubImage2D(tex[1], 0, 0, 0, DW, DH, GL_RGBA, GL_FLOAT, n4);
}

/* The AO of method m with tap program `param` (deinterleave, depth_mips) on or off on the textures:
 * raw (ob_compute_ao, whose method writes tex[2] itself) or after the settings' 4x4 box
 * (ob_compute_ao_filtered, where the method writes the renderer's scratch target and the filter
 * tex[2]). */
static float *taps_run(ob_renderer *r, const GLuint tex[3], const float proj[16], const char *m, const char *param,
                       bool on, bool filtered)
{
    ob_settings s;
    settings_for(&s, m, TAPS_RADIUS);
    char set[64];
    snprintf(set, sizeof set, "%s.%s=%s", m, param, on ? "on" : "off");
    CHECK(ob_settings_set(&s, set) == OB_OK, "%s", set);
    const float minus_one = -1.0f;
    glClearTexImage(tex[2], 0, GL_RED, GL_FLOAT, &minus_one);
    ob_error e = filtered ? ob_compute_ao_filtered(r, tex[0], tex[1], proj, &s, tex[2])
                          : ob_compute_ao(r, tex[0], tex[1], proj, &s, tex[2]);
    const char *msg = NULL;
    ob_get_error(&msg);
    CHECK(e == OB_OK, "%s: %s", set, msg ? msg : "?");
    float *ao = malloc(sizeof(float) * DW * DH);
    glGetTextureImage(tex[2], 0, GL_RED, GL_FLOAT, (GLsizei)(sizeof(float) * DW * DH), ao);
    return ao;
}

static void test_taps(ob_context *ctx, ob_scene *cornell, ob_renderer *corner_r, const char *m, const char *param)
{
    ob_renderer *r = ob_make_renderer(ctx, &(ob_renderer_desc){.width = DW, .height = DH});
    CHECK(r != NULL, "%s: a %dx%d renderer", m, DW, DH);
    if (!r) return;
    ob_renderer_set_scene(r, cornell);
    ob_settings g;
    ob_settings_init(&g, "none");
    CHECK(ob_render_frame(r, &cornell_cam, &g) == OB_OK, "the G-buffer");
    float *depth = malloc(sizeof(float) * DW * DH), *n3 = malloc(sizeof(float) * 3 * DW * DH),
          *n4 = malloc(sizeof(float) * 4 * DW * DH);
    CHECK(ob_read_image(r, OB_IMAGE_DEPTH_F32, depth, sizeof(float) * DW * DH) == OB_OK &&
              ob_read_image(r, OB_IMAGE_NORMAL_F32, n3, sizeof(float) * 3 * DW * DH) == OB_OK,
          "read depth and normals");
    for (int i = 0; i < DW * DH; ++i) {
        memcpy(n4 + 4 * i, n3 + 3 * i, 3 * sizeof(float));
        n4[4 * i + 3] = 0.0f;
    }
    GLuint tex[3];
    engine_textures(depth, n4, tex);
    mat4 proj;
    glm_perspective(glm_rad(cornell_cam.fov_y_deg), (float)DW / (float)DH, cornell_cam.near_z, cornell_cam.far_z, proj);

    float *raw = taps_run(r, tex, (const float *)proj, m, param, true, false);
    float *plain = taps_run(r, tex, (const float *)proj, m, param, false, true);
    float *split = taps_run(r, tex, (const float *)proj, m, param, true, true);
    int unwritten = 0, sky_closed = 0, geometry = 0;
    double diff = 0.0, shift = 0.0;
    for (int i = 0; i < DW * DH; ++i) {
        unwritten += !(raw[i] >= 0.0f && raw[i] <= 1.0f);
        if (depth[i] <= 0.0f) {
            sky_closed += split[i] != 1.0f;
            continue;
        }
        diff += fabs((double)split[i] - (double)plain[i]);
        shift += (double)split[i] - (double)plain[i];
        ++geometry;
    }
    diff /= geometry > 0 ? geometry : 1;
    shift /= geometry > 0 ? geometry : 1;
    const bool changed = memcmp(split, plain, sizeof(float) * DW * DH) != 0;
    printf("  %-8s %s at %dx%d: mean |on - off| %.4f, mean shift %+.4f\n", m, param, DW, DH, diff, shift);
    CHECK(unwritten == 0, "%s %s: %d of %d pixels unwritten or outside [0,1]", m, param, unwritten, DW * DH);
    CHECK(sky_closed == 0, "%s %s: %d sky pixels not 1", m, param, sky_closed);
    CHECK(changed, "%s %s: the same image as the plain program (its far taps read nothing else)", m, param);
    /* After the 4x4 box (ob_compute_ao_filtered), which cancels the tile's noise in both: the
     * far taps' moves leave 0.007-0.024 deinterleaved and 0.001-0.016 from the MIP chain (alchemy,
     * whose near samples weigh most, the most; gtao and vbao 0.007). A mean shift is what a lost
     * near field shows (every tap within 2 pixels snapped onto the pixel itself read lighter), or
     * a depth read at another pixel than the tap's (the MIP chain's first sky rule: alchemy
     * -0.014, gtao and vbao -0.006; now within 0.002). */
    CHECK(diff < 0.03, "%s %s: mean |difference| %.4f from the plain program", m, param, diff);
    CHECK(fabs(shift) < 0.01, "%s %s: reads %+.4f on average against the plain program", m, param, shift);
    free(raw);
    free(plain);
    free(split);
    free(depth);
    free(n3);
    free(n4);
    glDeleteTextures(3, tex);
    ob_destroy_renderer(r);

    char extra[32];
    snprintf(extra, sizeof extra, "%s=on", param);
    test_corner_with(corner_r, m, extra);
}

/* A tap program reads the pixel it names: on a plane seen at a grazing angle, where the depth changes
 * fastest from pixel to pixel, taps that moved (to a class pixel, to the pixel a MIP texel picked)
 * must still lie on the plane, so the plane reads as open as with the plain program. A tap
 * reconstructed where it aimed with the depth of where it read lies off the plane by the depth's
 * change in between and occludes. Engine path, raw AO, R = 1.5 x the eye's height over the plane,
 * so that far taps reach level 2 of the chain (40 px) in the nearer rows. Not crytek, whose plane
 * level (half its sphere inside) depends on where its taps land. */
static void test_taps_plane(ob_context *ctx, const char *m, const char *param)
{
    ob_renderer *r = ob_make_renderer(ctx, &(ob_renderer_desc){.width = DW, .height = DH});
    CHECK(r != NULL, "%s: a %dx%d renderer", m, DW, DH);
    if (!r) return;
    mat4 proj;
    glm_perspective(glm_rad(60.0f), (float)DW / (float)DH, 0.05f, 100.0f, proj);
    /* The plane n.P = -1 under the eye, tilted sideways: depth along each pixel's view ray
     * (x / P00, y / P11, -1) in NDC, bottom row first; sky where the ray misses it. */
    const float n[3] = {0.2f, 0.98f, 0.0f};
    float *depth = malloc(sizeof(float) * DW * DH), *n4 = malloc(sizeof(float) * 4 * DW * DH);
    int plane = 0;
    for (int y = 0; y < DH; ++y)
        for (int x = 0; x < DW; ++x) {
            const float ray[3] = {(2.0f * ((float)x + 0.5f) / DW - 1.0f) / proj[0][0],
                                  (2.0f * ((float)y + 0.5f) / DH - 1.0f) / proj[1][1], -1.0f};
            const float along = n[0] * ray[0] + n[1] * ray[1] + n[2] * ray[2];
            const float t = along < -1e-3f ? -1.0f / along : 0.0f;
            depth[y * DW + x] = t > 0.0f && t < 60.0f ? t : 0.0f;
            plane += depth[y * DW + x] > 0.0f;
            memcpy(n4 + 4 * (y * DW + x), n, sizeof n);
            n4[4 * (y * DW + x) + 3] = 0.0f;
        }
    GLuint tex[3];
    engine_textures(depth, n4, tex);
    double mean[2] = {0.0, 0.0};
    float lowest[2] = {1.0f, 1.0f};
    for (int on = 0; on < 2; ++on) {
        ob_settings s;
        ob_settings_init(&s, m);
        char set[64];
        snprintf(set, sizeof set, "%s.%s=%s", m, param, on ? "on" : "off");
        CHECK(ob_settings_set(&s, "radius=1.5") == OB_OK && ob_settings_set(&s, set) == OB_OK, "%s", set);
        ob_error e = ob_compute_ao(r, tex[0], tex[1], (const float *)proj, &s, tex[2]);
        const char *msg = NULL;
        ob_get_error(&msg);
        CHECK(e == OB_OK, "%s: %s", set, msg ? msg : "?");
        float *ao = malloc(sizeof(float) * DW * DH);
        glGetTextureImage(tex[2], 0, GL_RED, GL_FLOAT, (GLsizei)(sizeof(float) * DW * DH), ao);
        for (int i = 0; i < DW * DH; ++i) {
            if (depth[i] <= 0.0f) continue;
            mean[on] += ao[i];
            lowest[on] = ao[i] < lowest[on] ? ao[i] : lowest[on];
        }
        mean[on] /= plane > 0 ? plane : 1;
        free(ao);
    }
    printf("  %-8s %s on a grazing plane (%d px): mean %.4f -> %.4f, lowest %.4f -> %.4f\n", m, param, plane, mean[0],
           mean[1], (double)lowest[0], (double)lowest[1]);
    CHECK(fabs(mean[1] - mean[0]) < 0.002, "%s %s: a plane reads %.4f on average, %.4f with the plain program", m, param,
          mean[1], mean[0]);
    CHECK(lowest[1] >= lowest[0] - 0.002f, "%s %s: a plane pixel reads %.4f, the plain program's lowest %.4f", m, param,
          (double)lowest[1], (double)lowest[0]);
    free(depth);
    free(n4);
    glDeleteTextures(3, tex);
    ob_destroy_renderer(r);
}

static bool has_param(int index, const char *name)
{
    const ob_method_info *info = ob_method_at(index);
    for (int k = 0; k < info->param_count; ++k)
        if (!strcmp(info->params[k].name, name)) return true;
    return false;
}

/* A method takes a sample count when the kit can map one onto its parameters. */
static bool takes_samples(int index)
{
    ob_settings s;
    if (ob_settings_init(&s, ob_method_at(index)->name) != OB_OK) return false;
    ob_error err = ob_settings_set_samples(&s, 12);
    ob_get_error(NULL); /* a method without one refuses: that is the answer, not a failure */
    return err == OB_OK;
}

/* What the registry entry declares agrees with what the public table says and what the kit
 * needs: the renderer trusts these declarations and knows no method by name. */
static void test_registry_entry(int index)
{
    const ob_method_impl *m = ob_method_impl_at(index);
    const ob_method_info *info = ob_method_at(index);
    CHECK(m && info && !strcmp(m->info.name, info->name), "entry %d: impl and info agree", index);
    if (!m || !info) return;
    CHECK(info->directional == ((m->writes & (OB_WRITES_VISIBILITY_RGB | OB_WRITES_BOUNCE)) != 0),
          "%s: directional follows the declared outputs", info->name);
    CHECK((m->writes & (OB_WRITES_VISIBILITY | OB_WRITES_VISIBILITY_RGB)) != 0,
          "%s: writes a visibility (R or RGB)", info->name);
    CHECK(!m->shader || (m->constants_size > 0 && m->constants_size % 16 == 0 && m->state_size >= sizeof(ob_method_kit)),
          "%s: a shader comes with a std140 block and a state that begins with the kit", info->name);
    CHECK(ob_find_method(info->name) == index, "%s: found by name", info->name);
}

int main(void)
{
    ob_context *ctx = check_context();
    if (!ctx) return 1;
    ob_scene *corner = ob_load_scene(&(ob_scene_desc){.name = "corner"});
    ob_scene *cornell = ob_load_scene(&(ob_scene_desc){.name = "cornell"});
    ob_renderer *rc = ob_make_renderer(ctx, &(ob_renderer_desc){.width = W, .height = H});
    ob_renderer *rb = ob_make_renderer(ctx, &(ob_renderer_desc){.width = W, .height = H});
    CHECK(corner && cornell && rc && rb, "scenes and renderers");
    if (!corner || !cornell || !rc || !rb) return check_finish("test_methods");
    ob_renderer_set_scene(rc, corner);
    ob_renderer_set_scene(rb, cornell);
    int tested = 0;
    for (int i = 0; i < ob_method_count(); ++i) {
        const char *m = ob_method_at(i)->name;
        test_registry_entry(i);
        test_determinism(rc, m);
        if (!strcmp(m, "none")) continue;
        test_radius_scale(rc, m, ob_query_scene_ao_radius(corner));
        test_corner(rc, m);
        test_edges(rb, m);
        /* Only methods with a sample count can be asked to converge with it. */
        /* ob_compute_ao runs the methods that read depth and normals alone; test_ssdo.c has ssdo's. */
        const bool engine = !(ob_method_impl_at(i)->reads & OB_READS_RADIANCE);
        if (has_param(i, "deinterleave") && engine) test_taps(ctx, cornell, rc, m, "deinterleave");
        if (has_param(i, "depth_mips") && engine) test_taps(ctx, cornell, rc, m, "depth_mips");
        const bool open_plane = strcmp(m, "crytek") != 0;
        if (has_param(i, "deinterleave") && engine && open_plane) test_taps_plane(ctx, m, "deinterleave");
        if (has_param(i, "depth_mips") && engine && open_plane) test_taps_plane(ctx, m, "depth_mips");
        if (takes_samples(i)) test_convergence(rc, m);
        else printf("  %-8s takes no sample count: convergence not tested\n", m);
        ++tested;
    }
    CHECK(tested >= 3, "only %d occlusion methods registered", tested);
    ob_destroy_renderer(rc);
    ob_destroy_renderer(rb);
    ob_destroy_scene(corner);
    ob_destroy_scene(cornell);
    ob_destroy_context(ctx);
    return check_finish("test_methods");
}
