/* Lights, shadows, ambient modes and HDR through the whole frame (issue 5):
 *   - a sphere on a plane shadows the floor on the side away from a directional light, for
 *     hard, pcf and vsm, and pcf and vsm soften the edge more than hard;
 *   - point and spot lights: 1/d^2 falloff, nothing outside the spot's cone;
 *   - a constant environment map lights exactly like the same constant ambient;
 *   - --hdr off clamps, and a brighter scene raises the automatic key. */
#include <cglm/cglm.h>
#include <stb/stb_image_write.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "check.h"
#include "obscura/eval.h"

enum { W = 160, H = 120 };

static const ob_camera top_cam = {
    .eye = {0.0f, 9.0f, 0.01f}, .target = {0.0f, 0.0f, 0.0f}, .up = {0.0f, 0.0f, -1.0f},
    .fov_y_deg = 50.0f, .near_z = 0.1f, .far_z = 50.0f, .name = "top"};

static bool project(const float p[3], int *px, int *py)
{
    mat4 view, proj, vp;
    vec3 eye, target, up;
    memcpy(eye, top_cam.eye, sizeof eye);
    memcpy(target, top_cam.target, sizeof target);
    memcpy(up, top_cam.up, sizeof up);
    glm_lookat(eye, target, up, view);
    glm_perspective(glm_rad(top_cam.fov_y_deg), (float)W / (float)H, top_cam.near_z, top_cam.far_z, proj);
    glm_mat4_mul(proj, view, vp);
    vec4 wp = {p[0], p[1], p[2], 1.0f}, clip;
    glm_mat4_mulv(vp, wp, clip);
    *px = (int)((clip[0] / clip[3] * 0.5f + 0.5f) * W);
    *py = (int)((clip[1] / clip[3] * 0.5f + 0.5f) * H);
    return *px >= 0 && *px < W && *py >= 0 && *py < H;
}

static float at(const float *img, int channels, float x, float y, float z)
{
    const float p[3] = {x, y, z};
    int px = 0, py = 0;
    if (!project(p, &px, &py)) return NAN;
    return img[(py * W + px) * channels];
}

static float *read_image(ob_renderer *r, ob_image_kind kind)
{
    float *img = malloc(ob_image_size(r, kind));
    CHECK(ob_read_image(r, kind, img, ob_image_size(r, kind)) == OB_OK, "read image %d", (int)kind);
    return img;
}

static void test_shadows(ob_renderer *r)
{
    ob_settings s;
    ob_settings_init(&s, "none");
    CHECK(ob_parse_light("directional dir=1,1.2,0 intensity=1", &s.lights[0]) == OB_OK, "light");
    s.light_count = 1;
    const ob_shadow_method methods[3] = {OB_SHADOW_HARD, OB_SHADOW_PCF, OB_SHADOW_VSM};
    const char *names[3] = {"hard", "pcf", "vsm"};
    int widths[3] = {0, 0, 0};
    for (int m = 0; m < 3; ++m) {
        s.shadow.method = methods[m];
        s.shadow.size = 512;
        CHECK(ob_render_frame(r, &top_cam, &s) == OB_OK, "%s frame", names[m]);
        float *vis = read_image(r, OB_IMAGE_SHADOW_F32);
        /* The sphere (radius 1 at y = 1) under light from +x: its shadow lies on -x. */
        float away = at(vis, 1, -1.4f, 0.0f, 0.0f), toward = at(vis, 1, 1.6f, 0.0f, 0.0f);
        float far_side = at(vis, 1, -3.5f, 0.0f, 2.5f);
        CHECK(away < 0.1f, "%s: floor away from the light is lit (%g)", names[m], (double)away);
        CHECK(toward > 0.9f && far_side > 0.9f, "%s: floor toward the light / far off is shadowed (%g, %g)", names[m],
              (double)toward, (double)far_side);
        /* The penumbra: pixels of the image that are partly lit. */
        for (int i = 0; i < W * H; ++i) widths[m] += vis[i] > 0.05f && vis[i] < 0.95f;
        free(vis);
    }
    printf("  penumbra pixels: hard %d, pcf %d, vsm %d\n", widths[0], widths[1], widths[2]);
    CHECK(widths[1] > widths[0] && widths[2] > widths[0], "pcf (%d) and vsm (%d) soften more than hard (%d)", widths[1],
          widths[2], widths[0]);
}

static void test_point_and_spot(ob_renderer *r)
{
    ob_settings s;
    ob_settings_init(&s, "none");
    s.ambient[0] = s.ambient[1] = s.ambient[2] = 0.0f;
    /* The floor straight below a point light 2 m up, then 4 m up: the same angles (so the same
     * Lambert and specular factors), a quarter of the light (1/d^2). */
    float below[2] = {0.0f, 0.0f};
    const char *heights[2] = {"point pos=3,2,3 intensity=4", "point pos=3,4,3 intensity=4"};
    for (int k = 0; k < 2; ++k) {
        CHECK(ob_parse_light(heights[k], &s.lights[0]) == OB_OK, "point");
        s.light_count = 1;
        CHECK(ob_render_frame(r, &top_cam, &s) == OB_OK, "point frame");
        float *rad = read_image(r, OB_IMAGE_RADIANCE_F32);
        below[k] = at(rad, 3, 3.0f, 0.0f, 3.0f);
        free(rad);
    }
    CHECK(fabsf(below[1] / below[0] - 0.25f) < 0.01f, "point light 2 m vs 4 m up: ratio %g, want 0.25 (1/d^2)",
          (double)(below[1] / below[0]));
    float *rad = NULL;

    CHECK(ob_parse_light("spot pos=-3,3,-3 dir=0,-1,0 cone=10,15 intensity=9", &s.lights[0]) == OB_OK, "spot");
    CHECK(ob_render_frame(r, &top_cam, &s) == OB_OK, "spot frame");
    rad = read_image(r, OB_IMAGE_RADIANCE_F32);
    float inside = at(rad, 3, -3.0f, 0.0f, -3.0f), outside = at(rad, 3, -3.0f + 1.5f, 0.0f, -3.0f);
    CHECK(inside > 0.1f && outside == 0.0f, "spot: %g inside the cone, %g outside (tan 15 x 3 m = 0.8 m)",
          (double)inside, (double)outside);
    free(rad);
}

static void test_ambient(ob_renderer *r)
{
    ob_settings s;
    ob_settings_init(&s, "none");
    s.lights[0] = (ob_light){.direction = {0.0f, 1.0f, 0.0f}, .color = {1.0f, 1.0f, 1.0f}, .intensity = 0.0f};
    s.light_count = 1;
    s.ambient[0] = s.ambient[1] = s.ambient[2] = 0.5f;
    CHECK(ob_render_frame(r, &top_cam, &s) == OB_OK, "constant frame");
    float *constant = read_image(r, OB_IMAGE_HDR_F32);

    char path[] = "/tmp/obscura-env-XXXXXX.hdr";
    int fd = mkstemps(path, 4);
    CHECK(fd >= 0, "temp file");
    close(fd);
    static float env[64 * 32 * 3];
    for (int i = 0; i < 64 * 32 * 3; ++i) env[i] = 0.5f;
    CHECK(stbi_write_hdr(path, 64, 32, 3, env) != 0, "write %s", path);
    CHECK(ob_renderer_set_environment(r, path) == OB_OK, "load the environment");
    unlink(path);
    s.ambient_mode = OB_AMBIENT_ENVIRONMENT;
    CHECK(ob_render_frame(r, &top_cam, &s) == OB_OK, "environment frame");
    float *environment = read_image(r, OB_IMAGE_HDR_F32);
    float *depth = read_image(r, OB_IMAGE_DEPTH_F32);
    double worst = 0.0;
    for (int i = 0; i < W * H * 3; ++i) {
        if (depth[i / 3] <= 0.0f) continue; /* the background shows the map itself, not the ambient */
        worst = fmax(worst, fabs(environment[i] - constant[i]) / fmax(constant[i], 1e-3));
    }
    free(depth);
    /* RGBE stores 0.5 exactly; SH and 16-bit floats leave well under 1%. */
    CHECK(worst < 0.01, "a constant environment lights like the constant ambient (worst %.4f relative)", worst);

    s.ambient_mode = OB_AMBIENT_HEMISPHERE;
    CHECK(ob_render_frame(r, &top_cam, &s) == OB_OK, "hemisphere frame");
    float *hemi = read_image(r, OB_IMAGE_HDR_F32);
    /* The floor faces the sky: albedo x sky colour. The sphere's top also; its side half sky. */
    float floor_r = at(hemi, 3, 3.5f, 0.0f, 3.5f);
    CHECK(fabsf(floor_r - 0.8f * s.sky[0]) < 0.01f, "hemisphere floor %g, want albedo x sky %g", (double)floor_r,
          (double)(0.8f * s.sky[0]));
    free(constant);
    free(environment);
    free(hemi);
    CHECK(ob_renderer_set_environment(r, "/nonexistent.hdr") == OB_ERR_IO, "missing environment map");
}

static void test_hdr(ob_renderer *r)
{
    ob_settings s;
    ob_settings_init(&s, "none");
    CHECK(ob_parse_light("directional dir=0.3,1,0.2 intensity=6", &s.lights[0]) == OB_OK, "bright light");
    s.light_count = 1;
    s.hdr.enabled = false;
    CHECK(ob_render_frame(r, &top_cam, &s) == OB_OK, "hdr off");
    unsigned char *clamped = malloc(ob_image_size(r, OB_IMAGE_FINAL_RGBA8));
    ob_read_image(r, OB_IMAGE_FINAL_RGBA8, clamped, ob_image_size(r, OB_IMAGE_FINAL_RGBA8));
    int white = 0;
    for (int i = 0; i < W * H; ++i) white += clamped[4 * i] == 255 && clamped[4 * i + 1] == 255;
    CHECK(white > W * H / 4, "--hdr off burns a 6x light to white (%d pixels)", white);
    s.hdr.enabled = true;
    CHECK(ob_render_frame(r, &top_cam, &s) == OB_OK, "hdr on");
    unsigned char *mapped = malloc(ob_image_size(r, OB_IMAGE_FINAL_RGBA8));
    ob_read_image(r, OB_IMAGE_FINAL_RGBA8, mapped, ob_image_size(r, OB_IMAGE_FINAL_RGBA8));
    int white2 = 0;
    for (int i = 0; i < W * H; ++i) white2 += mapped[4 * i] == 255 && mapped[4 * i + 1] == 255;
    CHECK(white2 < white / 4, "tone mapping brings the burnt floor back (%d white pixels, %d clamped)", white2, white);
    free(clamped);
    free(mapped);
}

/* Compose's multi-bounce option (Jimenez et al. 2016 §5): the composed radiance is
 * direct + ambient x albedo x max(v, ((a v + b) v + c) v) per channel, with the fit's constants,
 * checked pixel by pixel against the frame's own direct light, albedo and AO. */
static void test_multibounce(ob_renderer *r)
{
    ob_settings s;
    ob_settings_init(&s, "gtao");
    /* The plane beside the unit sphere, seen from above, is occluded by its lower half. */
    CHECK(ob_settings_set(&s, "gtao.radius=2") == OB_OK, "radius");
    s.shadow.method = OB_SHADOW_NONE;
    s.hdr.enabled = false;
    CHECK(ob_render_frame(r, &top_cam, &s) == OB_OK, "frame without multi-bounce");
    float *plain = read_image(r, OB_IMAGE_HDR_F32);
    s.multibounce = true;
    CHECK(ob_render_frame(r, &top_cam, &s) == OB_OK, "frame with multi-bounce");
    float *hdr = read_image(r, OB_IMAGE_HDR_F32), *direct = read_image(r, OB_IMAGE_RADIANCE_F32);
    float *albedo = read_image(r, OB_IMAGE_ALBEDO_F32), *ao = read_image(r, OB_IMAGE_AO_F32);
    float *depth = read_image(r, OB_IMAGE_DEPTH_F32);
    double worst = 0.0;
    int lifted = 0, darker = 0, occluded = 0;
    for (int i = 0; i < W * H; ++i) {
        if (depth[i] <= 0.0f) continue;
        float v = ao[i];
        occluded += v < 0.9f;
        for (int c = 0; c < 3; ++c) {
            float a = albedo[3 * i + c];
            float fa = 2.0404f * a - 0.3324f, fb = -4.7951f * a + 0.6417f, fc = 2.7552f * a + 0.6903f;
            float mb = fmaxf(v, ((v * fa + fb) * v + fc) * v);
            float want = direct[3 * i + c] + s.ambient[c] * a * mb;
            /* RGBA16F targets: about 1e-3 relative. */
            worst = fmax(worst, fabs((double)hdr[3 * i + c] - want) / fmax(1e-3, (double)want));
            lifted += hdr[3 * i + c] > plain[3 * i + c] + 1e-3f;
            darker += hdr[3 * i + c] < plain[3 * i + c] - 1e-3f;
        }
    }
    printf("  multi-bounce: %d occluded pixels, %d channel values lifted, worst relative error %.2g\n", occluded,
           lifted, worst);
    CHECK(occluded > 50, "the sphere on the plane occludes (%d pixels below 0.9)", occluded);
    CHECK(worst < 4e-3, "composed radiance follows the fit (worst relative error %.3g)", worst);
    CHECK(lifted > 50 && darker == 0, "the fit only lifts occluded pixels (%d lifted, %d darker)", lifted, darker);
    free(plain);
    free(hdr);
    free(direct);
    free(albedo);
    free(ao);
    free(depth);
}

/* VSM's 16-bit moments (ob_shadow_settings.vsm_bits): they render, agree with 32 bits on a
 * simple directional shadow (sphere-on-plane: measured mean |16 - 32| 0.0000, max 0.08 on a few
 * penumbra pixels), and a width other than 16 or 32 is refused. */
static void test_vsm_bits(ob_renderer *r)
{
    size_t px = (size_t)W * H;
    float *vis[2] = {malloc(px * sizeof(float)), malloc(px * sizeof(float))};
    const int bits[2] = {16, 32};
    ob_settings s;
    for (int k = 0; k < 2; ++k) {
        ob_settings_init(&s, "none");
        s.shadow.method = OB_SHADOW_VSM;
        s.shadow.vsm_bits = bits[k];
        CHECK(ob_render_frame(r, &top_cam, &s) == OB_OK, "VSM %d-bit frame", bits[k]);
        ob_read_image(r, OB_IMAGE_SHADOW_F32, vis[k], px * sizeof(float));
    }
    double sum = 0.0;
    int shadowed = 0;
    for (size_t i = 0; i < px; ++i) {
        sum += fabs((double)vis[0][i] - (double)vis[1][i]);
        shadowed += vis[1][i] < 0.5f;
    }
    printf("  VSM 16 vs 32 bits on sphere-on-plane: mean |difference| %.5f, %d shadowed pixels\n", sum / (double)px,
           shadowed);
    CHECK(shadowed > 100, "the sphere casts a shadow (%d pixels)", shadowed);
    CHECK(sum / (double)px < 0.01, "16-bit moments agree with 32-bit ones on a simple shadow (%.4f)", sum / (double)px);
    s.shadow.vsm_bits = 8;
    CHECK(ob_render_frame(r, &top_cam, &s) == OB_ERR_OUT_OF_RANGE, "vsm_bits 8 is refused");
    ob_clear_error();
    free(vis[0]);
    free(vis[1]);
}

/* Textures on and off (ob_settings.textures_off): Khronos' BoxTextured, whose one material has a
 * 211 x 211 diffuse texture. On, the albedo varies over the box; off, every box pixel is the
 * material's diffuse colour alone. */
static void test_textures(ob_context *ctx)
{
    const char *path = "/usr/share/assimp/models/glTF2/BoxTextured-glTF/BoxTextured.gltf";
    if (access(path, R_OK) != 0) {
        printf("  skip: %s not installed\n", path);
        return;
    }
    ob_scene *scene = ob_load_scene(&(ob_scene_desc){.name = path});
    ob_renderer *r = ob_make_renderer(ctx, &(ob_renderer_desc){.width = W, .height = H});
    CHECK(scene && r && ob_renderer_set_scene(r, scene) == OB_OK, "BoxTextured");
    if (!scene || !r) return;
    ob_camera cam;
    CHECK(ob_find_camera(scene, "default", &cam) == OB_OK, "default camera");
    const ob_material_info m = ob_query_scene_material(scene, 0);
    CHECK(m.has_texture, "BoxTextured has a texture");
    size_t px = (size_t)W * H;
    float *albedo = malloc(px * 3 * sizeof(float)), *depth = malloc(px * sizeof(float));
    double spread[2] = {0.0, 0.0}, off_diff = 0.0;
    int geometry = 0;
    for (int off = 0; off < 2; ++off) {
        ob_settings s;
        ob_settings_init(&s, "none");
        s.textures_off = off != 0;
        CHECK(ob_render_frame(r, &cam, &s) == OB_OK, "frame");
        ob_read_image(r, OB_IMAGE_ALBEDO_F32, albedo, px * 3 * sizeof(float));
        ob_read_image(r, OB_IMAGE_DEPTH_F32, depth, px * sizeof(float));
        float lo = 1e9f, hi = -1e9f;
        geometry = 0;
        for (size_t i = 0; i < px; ++i) {
            if (depth[i] <= 0.0f) continue;
            ++geometry;
            float g = albedo[3 * i + 1];
            lo = g < lo ? g : lo;
            hi = g > hi ? g : hi;
            if (off)
                for (int c = 0; c < 3; ++c) off_diff = fmax(off_diff, fabs((double)albedo[3 * i + (size_t)c] - m.diffuse[c]));
        }
        spread[off] = (double)(hi - lo);
    }
    printf("  textures: albedo (green) spread over the box on %.3f, off %.6f; off differs from Kd by at most %.2g "
           "(%d box pixels)\n",
           spread[0], spread[1], off_diff, geometry);
    CHECK(geometry > 500, "the box fills part of the frame (%d pixels)", geometry);
    CHECK(spread[0] > 0.2, "textures on: the albedo varies over the box (%.3f)", spread[0]);
    CHECK(spread[1] < 1e-3 && off_diff < 2e-3, "textures off: the material's colour alone (spread %.2g, off Kd %.2g)",
          spread[1], off_diff);
    free(albedo);
    free(depth);
    ob_destroy_renderer(r);
    ob_destroy_scene(scene);
}

int main(void)
{
    ob_context *ctx = check_context();
    if (!ctx) return 1;
    ob_scene *scene = ob_load_scene(&(ob_scene_desc){.name = "sphere-on-plane"});
    ob_renderer *r = ob_make_renderer(ctx, &(ob_renderer_desc){.width = W, .height = H});
    CHECK(scene && r && ob_renderer_set_scene(r, scene) == OB_OK, "scene");
    if (scene && r) {
        test_shadows(r);
        test_point_and_spot(r);
        test_ambient(r);
        test_hdr(r);
        test_multibounce(r);
        test_vsm_bits(r);
    }
    test_textures(ctx);
    ob_destroy_renderer(r);
    ob_destroy_scene(scene);
    ob_destroy_context(ctx);
    return check_finish("test_lighting");
}
