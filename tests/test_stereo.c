/* Stereo (Belonogov 2018 §5.2): the eyes ob_stereo_cameras makes (parallel axes, off-axis frusta that
 * meet on the convergence plane, the Vive preset) and ob_metric_stereo_consistency on two CPU
 * views of a plane whose AO is a known function of the surface point. */
#include <cglm/cglm.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "check.h"

/* The projection as ob_render_frame builds it: glm_perspective, then the lens shift in P20/P21. */
static void eye_ndc(const ob_camera *c, float aspect, const float p[3], float ndc[2])
{
    mat4 view, proj;
    vec3 eye = {c->eye[0], c->eye[1], c->eye[2]}, target = {c->target[0], c->target[1], c->target[2]};
    vec3 up = {0.0f, 1.0f, 0.0f};
    glm_lookat(eye, target, up, view);
    glm_perspective(glm_rad(c->fov_y_deg), aspect, 0.1f, 100.0f, proj);
    proj[2][0] = c->shift[0];
    proj[2][1] = c->shift[1];
    mat4 vp;
    glm_mat4_mul(proj, view, vp);
    vec4 w = {p[0], p[1], p[2], 1.0f}, clip;
    glm_mat4_mulv(vp, w, clip);
    ndc[0] = clip[0] / clip[3];
    ndc[1] = clip[1] / clip[3];
}

static void test_convergence_plane(void)
{
    const ob_camera centre = {.eye = {1.0f, 2.0f, 6.0f}, .target = {1.0f, 2.0f, 1.0f}, .fov_y_deg = 50.0f, .name = "c"};
    const float aspect = 1.5f, ipd = 0.2f;
    ob_camera eyes[2];
    CHECK(ob_stereo_cameras(&centre, &(ob_stereo_desc){.ipd = ipd, .aspect = aspect}, eyes) == OB_OK, "eyes");
    /* Eyes -+ipd/2 along +x (the right vector of a camera looking down -z), views parallel. */
    CHECK_NEAR(eyes[0].eye[0], 1.0f - 0.5f * ipd, 1e-6, "left eye x");
    CHECK_NEAR(eyes[1].eye[0], 1.0f + 0.5f * ipd, 1e-6, "right eye x");
    CHECK_NEAR(eyes[0].target[0] - eyes[0].eye[0], 0.0f, 1e-6, "left view parallel");
    CHECK_NEAR(eyes[1].target[2] - eyes[1].eye[2], -5.0f, 1e-6, "right view parallel");
    /* Bourke's shift: (ipd/2) / (D tan(fov_x/2)), left eye's window to the right. */
    const float tan_x = aspect * tanf(glm_rad(25.0f));
    CHECK_NEAR(eyes[0].shift[0], 0.5f * ipd / (5.0f * tan_x), 1e-6, "left shift");
    CHECK_NEAR(eyes[1].shift[0], -0.5f * ipd / (5.0f * tan_x), 1e-6, "right shift");
    CHECK(!strcmp(eyes[0].name, "c-left") && !strcmp(eyes[1].name, "c-right"), "names %s %s", eyes[0].name, eyes[1].name);
    /* Points on the convergence plane (z = 1, 5 in front) land at the same NDC in both eyes. */
    const float on_plane[3][3] = {{1.0f, 2.0f, 1.0f}, {2.3f, 1.1f, 1.0f}, {-0.5f, 3.0f, 1.0f}};
    for (int i = 0; i < 3; ++i) {
        float l[2], r[2];
        eye_ndc(&eyes[0], aspect, on_plane[i], l);
        eye_ndc(&eyes[1], aspect, on_plane[i], r);
        CHECK_NEAR(l[0], r[0], 1e-5, "ndc x on the convergence plane");
        CHECK_NEAR(l[1], r[1], 1e-5, "ndc y on the convergence plane");
    }
    /* Beyond the plane: uncrossed parallax (the right eye sees it further right); nearer: crossed. */
    float l[2], r[2];
    eye_ndc(&eyes[0], aspect, (const float[3]){1.0f, 2.0f, -9.0f}, l);
    eye_ndc(&eyes[1], aspect, (const float[3]){1.0f, 2.0f, -9.0f}, r);
    CHECK(r[0] > l[0] + 1e-3f, "far point: right %g vs left %g", (double)r[0], (double)l[0]);
    eye_ndc(&eyes[0], aspect, (const float[3]){1.0f, 2.0f, 4.0f}, l);
    eye_ndc(&eyes[1], aspect, (const float[3]){1.0f, 2.0f, 4.0f}, r);
    CHECK(r[0] < l[0] - 1e-3f, "near point: right %g vs left %g", (double)r[0], (double)l[0]);
    /* An explicit convergence distance moves the plane. */
    CHECK(ob_stereo_cameras(&centre, &(ob_stereo_desc){.ipd = ipd, .aspect = aspect, .convergence = 10.0f}, eyes) == OB_OK,
          "eyes at 10");
    eye_ndc(&eyes[0], aspect, (const float[3]){1.7f, 2.4f, -4.0f}, l);
    eye_ndc(&eyes[1], aspect, (const float[3]){1.7f, 2.4f, -4.0f}, r);
    CHECK_NEAR(l[0], r[0], 1e-5, "ndc x on the plane at 10");
}

static void test_headset(void)
{
    ob_headset h;
    CHECK(ob_find_headset("vive", &h) == OB_OK && h.width == 1080 && h.height == 1200 && h.ipd == 0.064f, "vive");
    CHECK(ob_headset_count() >= 1 && ob_headset_at(0) && !ob_headset_at(ob_headset_count()), "headset list");
    CHECK(ob_find_headset("nosuch", &h) == OB_ERR_INVALID_ARGUMENT, "unknown headset");
    const ob_camera centre = {.eye = {0.0f, 1.6f, 0.0f}, .target = {0.0f, 1.6f, -1.0f}, .fov_y_deg = 60.0f};
    ob_camera eyes[2];
    CHECK(ob_stereo_cameras(&centre, &(ob_stereo_desc){.headset = "vive"}, eyes) == OB_OK, "vive eyes");
    /* OpenVR's Vive frustum: P20 -0.0578 on the left (canted outward), mirrored on the right. */
    CHECK_NEAR(eyes[0].shift[0], -0.0577721, 1e-6, "left P20");
    CHECK_NEAR(eyes[1].shift[0], 0.0577721, 1e-6, "right P20");
    CHECK_NEAR(eyes[0].shift[1], -0.006465, 1e-6, "P21");
    CHECK_NEAR(eyes[0].fov_y_deg, 111.506, 1e-3, "vive fov");
    CHECK_NEAR(eyes[1].eye[0] - eyes[0].eye[0], 0.064, 1e-6, "vive ipd");
    /* The preset's tangents come back: the left eye's left edge at tan 1.39811 (ndc -1; the pixel
     * aspect 0.9 is the tangents' 0.89985 to 0.02 %). */
    float ndc[2];
    eye_ndc(&eyes[0], 0.9f, (const float[3]){eyes[0].eye[0] - 1.3981138f, 1.6f, -1.0f}, ndc);
    CHECK_NEAR(ndc[0], -1.0f, 2e-3, "left edge of the Vive's left eye");
    CHECK(ob_stereo_cameras(&centre, &(ob_stereo_desc){.ipd = -1.0f}, eyes) == OB_ERR_INVALID_ARGUMENT, "negative ipd");
    CHECK(ob_stereo_cameras(&centre, &(ob_stereo_desc){.headset = "nosuch"}, eyes) == OB_ERR_INVALID_ARGUMENT, "bad preset");
    const ob_camera same = {.eye = {1.0f, 1.0f, 1.0f}, .target = {1.0f, 1.0f, 1.0f}};
    CHECK(ob_stereo_cameras(&same, NULL, eyes) == OB_ERR_INVALID_ARGUMENT, "eye = target");
    const ob_camera down = {.eye = {0.0f, 5.0f, 0.0f}, .target = {0.0f, 0.0f, 0.0f}};
    CHECK(ob_stereo_cameras(&down, NULL, eyes) == OB_ERR_INVALID_ARGUMENT, "forward parallel to up");
}

/* ---- the consistency metric on a CPU-traced plane --------------------------------------------- */
enum { W = 96, H = 64 };

/* A known AO on the plane z = 0, a function of the surface point only (as AO_R is). */
static float plane_ao(float x, float y, float offset) { return 0.5f + 0.4f * sinf(3.0f * (x + offset)) * cosf(2.0f * y); }

/* Depth and AO of the plane z = 0 seen by c (bottom row first, as the renderer's images). */
static void trace_plane(const ob_camera *c, float offset, float *depth, float *ao)
{
    mat4 view, inv;
    vec3 eye = {c->eye[0], c->eye[1], c->eye[2]}, target = {c->target[0], c->target[1], c->target[2]};
    vec3 up = {0.0f, 1.0f, 0.0f};
    glm_lookat(eye, target, up, view);
    glm_mat4_inv(view, inv);
    const float p11 = 1.0f / tanf(glm_rad(c->fov_y_deg) * 0.5f), p00 = p11 * (float)H / (float)W;
    for (int y = 0; y < H; ++y)
        for (int x = 0; x < W; ++x) {
            const float nx = ((float)x + 0.5f) / (float)W * 2.0f - 1.0f, ny = ((float)y + 0.5f) / (float)H * 2.0f - 1.0f;
            /* View direction with z = -1: the hit's parameter is its linear depth. */
            vec4 dv = {(nx + c->shift[0]) / p00, (ny + c->shift[1]) / p11, -1.0f, 0.0f}, dw;
            glm_mat4_mulv(inv, dv, dw);
            const float t = -c->eye[2] / dw[2];
            const size_t i = (size_t)y * W + (size_t)x;
            depth[i] = t > 0.0f ? t : 0.0f;
            ao[i] = t > 0.0f ? plane_ao(c->eye[0] + t * dw[0], c->eye[1] + t * dw[1], offset) : 1.0f;
        }
}

static void test_consistency(void)
{
    const ob_camera centre = {.eye = {0.2f, 0.3f, 4.0f}, .target = {0.2f, 0.3f, 0.0f}, .fov_y_deg = 50.0f};
    ob_camera eyes[2];
    CHECK(ob_stereo_cameras(&centre, &(ob_stereo_desc){.ipd = 0.4f, .aspect = (float)W / (float)H}, eyes) == OB_OK, "eyes");
    float *buf = malloc(sizeof(float) * W * H * 5);
    float *dl = buf, *al = buf + W * H, *dr = buf + 2 * W * H, *ar = buf + 3 * W * H, *shifted = buf + 4 * W * H;
    trace_plane(&eyes[0], 0.0f, dl, al);
    trace_plane(&eyes[1], 0.0f, dr, ar);
    float scratch_depth[W * H];
    trace_plane(&eyes[1], 0.35f, scratch_depth, shifted);
    ob_stereo_view left = {.ao = al, .linear_depth = dl, .width = W, .height = H, .camera = eyes[0]};
    ob_stereo_view right = {.ao = ar, .linear_depth = dr, .width = W, .height = H, .camera = eyes[1]};
    ob_stereo_consistency same, moved, hidden;
    CHECK(ob_metric_stereo_consistency(&left, &right, 0.0f, &same) == OB_OK, "consistent pair");
    /* Only the bilinear read of a smooth pattern differs: far below the pattern's 0.4 amplitude. */
    CHECK(same.mean_abs < 0.005, "consistent: %g", same.mean_abs);
    /* The eyes overlap except for a strip of ipd / (view width at the plane) on one side. */
    CHECK(same.fraction > 0.85 && same.fraction < 1.0, "overlap %g", same.fraction);
    right.ao = shifted;
    CHECK(ob_metric_stereo_consistency(&left, &right, 0.0f, &moved) == OB_OK && moved.mean_abs > 0.1,
          "a pattern that moved with the eye: %g", moved.mean_abs);
    CHECK_NEAR(moved.fraction, same.fraction, 1e-12, "the same pixels");
    /* Something nearer in front of a block of the left image: those points are not seen by the
     * left eye, so they are skipped (their left AO, 0 here, would be far off). */
    right.ao = ar;
    for (int y = 16; y < 48; ++y)
        for (int x = 30; x < 60; ++x) {
            dl[(size_t)y * W + (size_t)x] *= 0.5f;
            al[(size_t)y * W + (size_t)x] = 0.0f;
        }
    CHECK(ob_metric_stereo_consistency(&left, &right, 0.0f, &hidden) == OB_OK, "occluded pair");
    CHECK(hidden.mean_abs < 0.005, "occluded pixels skipped: %g", hidden.mean_abs);
    CHECK(hidden.fraction < same.fraction - 0.12, "fewer pixels: %g vs %g", hidden.fraction, same.fraction);
    /* Bad input. */
    CHECK(ob_metric_stereo_consistency(NULL, &right, 0.0f, &same) == OB_ERR_INVALID_ARGUMENT, "NULL");
    CHECK(ob_metric_stereo_consistency(&left, &right, -1.0f, &same) == OB_ERR_INVALID_ARGUMENT, "negative tolerance");
    memset(dl, 0, sizeof(float) * W * H);
    CHECK(ob_metric_stereo_consistency(&left, &right, 0.0f, &same) == OB_ERR_INVALID_ARGUMENT && same.count == 0,
          "no pixel seen by both");
    free(buf);
}

int main(void)
{
    test_convergence_plane();
    test_headset();
    test_consistency();
    return check_finish("stereo");
}
