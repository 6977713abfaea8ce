/* One AO chain, two front doors (issue 45): ob_host_ao on copies of a frame's own G-buffer (linear
 * depth, view normals, direct light, albedo at the enlarged size, the frame's view and projection)
 * gives the very bits ob_render_frame gave: the AO, a directional method's M, the bounce and the
 * bent normals, at AO scale 1, 1/2 and 1/4, with temporal accumulation over several frames of a
 * moving camera, with a guard band (the host's textures enlarged, the output cropped) and with
 * adaptive sampling. Then the same frame through the input pass from a depth buffer (standard and
 * reversed Z) and octahedral world-space normals, within the tolerance their quantisation allows,
 * and with no normals at all (rebuilt from depth), whose error is only reported. */
#include <cglm/cglm.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "check.h"
#include "core/renderer.h"
#include "gpu/gpu.h"

enum { W = 80, H = 60 };

static const char *error_text(void)
{
    const char *msg = "";
    ob_get_error(&msg);
    return msg;
}

static GLuint copy_of(GLuint src, GLenum format, int w, int h)
{
    GLuint t = ob_make_texture_2d(format, w, h);
    glCopyImageSubData(src, GL_TEXTURE_2D, 0, 0, 0, 0, t, GL_TEXTURE_2D, 0, 0, 0, 0, w, h, 1);
    return t;
}

static void read_tex(GLuint t, GLenum format, int channels, size_t n, float *out)
{
    (void)format;
    glGetTextureImage(t, 0, channels == 1 ? GL_RED : GL_RGBA, GL_FLOAT, (GLsizei)(n * sizeof(float)), out);
}

static double worst_diff(const float *a, const float *b, size_t n)
{
    double w = 0.0;
    for (size_t i = 0; i < n; ++i) w = fmax(w, fabs((double)a[i] - (double)b[i]));
    return w;
}

typedef struct host_inputs {
    GLuint depth, normal, radiance, albedo, second;
    int w, h;
    float view[16], proj[16];
} host_inputs;

/* The frame just rendered, as a host would hand it over. */
static void grab(ob_renderer *r, host_inputs *in)
{
    in->w = r->inner_width;
    in->h = r->inner_height;
    in->depth = copy_of(r->gbuffer.linear_depth, GL_R32F, in->w, in->h);
    in->normal = copy_of(r->gbuffer.normal, GL_RGBA16F, in->w, in->h);
    in->radiance = copy_of(r->direct, GL_RGBA16F, in->w, in->h);
    in->albedo = copy_of(r->gbuffer.albedo, GL_RGBA16F, in->w, in->h);
    in->second = r->last.second_layer ? copy_of(r->peel.linear_depth, GL_R32F, in->w, in->h) : 0;
    memcpy(in->view, r->frame_constants.view, sizeof in->view);
    memcpy(in->proj, r->frame_constants.proj, sizeof in->proj);
}

static void release(host_inputs *in)
{
    GLuint t[5] = {in->depth, in->normal, in->radiance, in->albedo, in->second};
    glDeleteTextures(in->second ? 5 : 4, t);
}

/* The settings a host would pass for the frame's: the radius the frame took from the scene. */
static ob_settings host_settings(const ob_settings *s, float radius)
{
    ob_settings h = *s;
    const ob_method_impl *m = ob_method_impl_at(s->method);
    int i = ob_method_role(m, OB_ROLE_RADIUS);
    if (i >= 0 && !(s->params_set & (1u << i))) {
        char set[64];
        snprintf(set, sizeof set, "radius=%.9g", (double)radius);
        ob_settings_set(&h, set);
    }
    return h;
}

/* The scene's first camera, turned 1.5 degrees a frame about its target. */
static ob_camera base_camera;
static ob_camera camera_at(int i) { return ob_camera_orbit(&base_camera, 1.5f * (float)i); }

/* `frames` frames of a moving camera through both doors; the last frame's outputs compared. */
static void same_bits(ob_context *ctx, ob_scene *scene, const char *method, const char *extra, int divisor,
                      bool temporal, int guard, bool adaptive, int frames)
{
    char label[160];
    snprintf(label, sizeof label, "%s%s%s 1/%d%s guard %d%s", method, extra ? " " : "", extra ? extra : "", divisor,
             temporal ? " temporal" : "", guard, adaptive ? " adaptive" : "");
    ob_renderer *a = ob_make_renderer(ctx, &(ob_renderer_desc){.width = W, .height = H});
    ob_renderer *b = ob_make_renderer(ctx, &(ob_renderer_desc){.width = W, .height = H});
    CHECK(a && b && ob_renderer_set_scene(a, scene) == OB_OK, "%s: renderers", label);
    if (!a || !b) return;
    ob_settings s;
    ob_settings_init(&s, method);
    /* A host's frame has no facet normals (the G-buffer's fifth target) and no planes of the
     * second layer (the peel pass's second target), so ob_host_ao runs gtao's, vbao's and vbgi's
     * facet wedge, and vbao's and vbgi's planes, off: the frame it must match has them off too. */
    if (!strcmp(method, "vbao") || !strcmp(method, "vbgi") || !strcmp(method, "gtao")) {
        char facets[32];
        snprintf(facets, sizeof facets, "%s.facets=off", method);
        CHECK(ob_settings_set(&s, facets) == OB_OK, "%s: %s", label, error_text());
    }
    if (!strcmp(method, "vbao") || !strcmp(method, "vbgi")) {
        char planes[32];
        snprintf(planes, sizeof planes, "%s.planes=off", method);
        CHECK(ob_settings_set(&s, planes) == OB_OK, "%s: %s", label, error_text());
    }
    if (extra) CHECK(ob_settings_set(&s, extra) == OB_OK, "%s: %s", label, error_text());
    ob_settings_set_ao_divisor(&s, divisor);
    s.temporal = temporal;
    s.guard = guard;
    s.adaptive = adaptive;
    ob_settings hs = host_settings(&s, ob_query_scene_ao_radius(scene));
    /* SSDO spreads the lights into lobes: a host names its lights in the settings. */
    hs.light_count = ob_query_scene_light_count(scene);
    for (int i = 0; i < hs.light_count && i < OB_MAX_LIGHTS; ++i) hs.lights[i] = ob_query_scene_light(scene, i);
    const bool rgb = ob_method_at(s.method)->directional && (ob_method_impl_at(s.method)->writes & OB_WRITES_VISIBILITY_RGB);
    GLuint ao = ob_make_texture_2d(rgb ? GL_RGBA16F : GL_R32F, W, H);
    GLuint bent = ob_make_texture_2d(GL_RGBA16F, W, H), indirect = ob_make_texture_2d(GL_RGBA16F, W, H);
    bool ok = true;
    for (int i = 0; i < frames && ok; ++i) {
        const ob_camera cam = camera_at(i);
        ok = ob_render_frame(a, &cam, &s) == OB_OK;
        CHECK(ok, "%s: frame %d: %s", label, i, error_text());
        if (!ok) break;
        host_inputs in;
        grab(a, &in);
        ob_host_frame f = {.depth = in.depth, .normal = in.normal, .radiance = in.radiance, .albedo = in.albedo,
                           .second_depth = in.second};
        if (extra && strstr(extra, "layers=2")) CHECK(in.second != 0, "%s: the frame peeled a second layer", label);
        memcpy(f.view, in.view, sizeof f.view);
        memcpy(f.projection, in.proj, sizeof f.projection);
        const ob_host_outputs o = {.ao = ao, .bent_normal = bent, .indirect = indirect};
        ok = ob_host_ao(b, &f, &hs, &o) == OB_OK;
        CHECK(ok, "%s: host frame %d: %s", label, i, error_text());
        release(&in);
    }
    if (ok) {
        const size_t n = (size_t)W * H;
        float *x = malloc(4 * n * sizeof(float)), *y = malloc(4 * n * sizeof(float)), *z = malloc(4 * n * sizeof(float));
        if (rgb) {
            ob_read_image(a, OB_IMAGE_AO_RGB_F32, x, 3 * n * sizeof(float));
            read_tex(ao, GL_RGBA16F, 4, 4 * n, y);
            for (size_t i = 0; i < n; ++i)
                for (int c = 0; c < 3; ++c) z[3 * i + c] = y[4 * i + c];
            CHECK(worst_diff(x, z, 3 * n) == 0.0, "%s: M differs by %g", label, worst_diff(x, z, 3 * n));
        } else {
            ob_read_image(a, OB_IMAGE_AO_F32, x, n * sizeof(float));
            read_tex(ao, GL_R32F, 1, n, y);
            CHECK(worst_diff(x, y, n) == 0.0, "%s: AO differs by %g", label, worst_diff(x, y, n));
            double mean = 0.0;
            for (size_t i = 0; i < n; ++i) mean += x[i];
            if (strcmp(method, "none") != 0)
                CHECK(mean / (double)n < 0.99, "%s: the frame has AO to compare (mean %g)", label, mean / (double)n);
        }
        const ob_image_kind kinds[2] = {OB_IMAGE_BOUNCE_F32, OB_IMAGE_BENT_NORMAL_F32};
        const GLuint outs[2] = {indirect, bent};
        for (int k = 0; k < 2; ++k) {
            ob_read_image(a, kinds[k], x, 3 * n * sizeof(float));
            read_tex(outs[k], GL_RGBA16F, 4, 4 * n, y);
            double w = 0.0;
            for (size_t i = 0; i < n; ++i) {
                float len = 1.0f;
                if (k == 1) { /* the host gets them renormalised (and stored as RGBA16F) */
                    len = sqrtf(x[3 * i] * x[3 * i] + x[3 * i + 1] * x[3 * i + 1] + x[3 * i + 2] * x[3 * i + 2]);
                    if (!(len > 0.0f)) len = INFINITY;
                }
                for (int c = 0; c < 3; ++c) w = fmax(w, fabs((double)(x[3 * i + c] / len) - (double)y[4 * i + c]));
            }
            if (k == 0) CHECK(w == 0.0, "%s: the bounce differs by %g", label, w);
            else CHECK(w <= 1e-3, "%s: the bent normals differ by %g (RGBA16F: 1e-3)", label, w);
        }
        free(x);
        free(y);
        free(z);
    }
    GLuint t[3] = {ao, bent, indirect};
    glDeleteTextures(3, t);
    ob_destroy_renderer(a);
    ob_destroy_renderer(b);
}

/* The same frame from a depth buffer and packed normals: window depth through the projection, as
 * the hardware writes it, and octahedral world-space normals in RG16F. */
static void through_input_pass(ob_context *ctx, ob_scene *scene)
{
    ob_renderer *a = ob_make_renderer(ctx, &(ob_renderer_desc){.width = W, .height = H});
    ob_renderer *b = ob_make_renderer(ctx, &(ob_renderer_desc){.width = W, .height = H});
    CHECK(a && b && ob_renderer_set_scene(a, scene) == OB_OK, "input pass: renderers");
    if (!a || !b) return;
    ob_settings s;
    ob_settings_init(&s, "vbao");
    const ob_settings hs = host_settings(&s, ob_query_scene_ao_radius(scene));
    const ob_camera cam = camera_at(0);
    CHECK(ob_render_frame(a, &cam, &s) == OB_OK, "input pass: frame: %s", error_text());
    const size_t n = (size_t)W * H;
    float *d = malloc(n * sizeof(float)), *nv = malloc(4 * n * sizeof(float)), *ref = malloc(n * sizeof(float));
    float *win = malloc(n * sizeof(float)), *oct = malloc(2 * n * sizeof(float)), *got = malloc(n * sizeof(float));
    read_tex(a->gbuffer.linear_depth, GL_R32F, 1, n, d);
    read_tex(a->gbuffer.normal, GL_RGBA16F, 4, 4 * n, nv);
    ob_read_image(a, OB_IMAGE_AO_F32, ref, n * sizeof(float));
    mat4 view, inv_view;
    memcpy(view, a->frame_constants.view, sizeof view);
    glm_mat4_inv(view, inv_view);
    const float *P = a->frame_constants.proj;
    /* The planes of this projection: P22 = -(f + n) / (f - n), P32 = -2 f n / (f - n). */
    const double zn = P[14] / (P[10] - 1.0), zf = P[14] / (P[10] + 1.0);
    for (size_t i = 0; i < n; ++i) {
        vec3 v = {nv[4 * i], nv[4 * i + 1], nv[4 * i + 2]}, w;
        glm_mat4_mulv3(inv_view, v, 0.0f, w);
        float l1 = fabsf(w[0]) + fabsf(w[1]) + fabsf(w[2]);
        float ex = l1 > 0.0f ? w[0] / l1 : 0.0f, ey = l1 > 0.0f ? w[1] / l1 : 0.0f;
        if (w[2] < 0.0f) {
            float tx = (1.0f - fabsf(ey)) * (ex >= 0.0f ? 1.0f : -1.0f);
            float ty = (1.0f - fabsf(ex)) * (ey >= 0.0f ? 1.0f : -1.0f);
            ex = tx;
            ey = ty;
        }
        oct[2 * i] = ex;
        oct[2 * i + 1] = ey;
    }
    struct {
        const char *name;
        bool reversed;
        GLenum format;
        double tol;
    } cases[] = {
        /* D32F standard Z: float window depth near 1 keeps ~2^-24 relative steps of w, a depth error
         * of about d^2 / n x 6e-8 (0.3 % at the back of this scene). */
        {"D32F standard", false, GL_DEPTH_COMPONENT32F, 0.02},
        /* D32F reversed Z [0,1]: the float exponent follows 1/d, so the depth is exact to ~1e-7. */
        {"D32F reversed", true, GL_DEPTH_COMPONENT32F, 0.02},
        /* D24: 2^-24 steps of w near 1: a few mm at the back of the scene. */
        {"D24S8 standard", false, GL_DEPTH24_STENCIL8, 0.05},
    };
    GLuint normal_tex = ob_make_texture_2d(GL_RG16F, W, H);
    glTextureSubImage2D(normal_tex, 0, 0, 0, W, H, GL_RG, GL_FLOAT, oct);
    GLuint out = ob_make_texture_2d(GL_R32F, W, H);
    for (size_t c = 0; c < sizeof cases / sizeof cases[0]; ++c) {
        float proj[16];
        memcpy(proj, P, sizeof proj);
        if (cases[c].reversed) {
            /* glClipControl's [0, 1] with reversed Z and this frame's planes: ndc = n (f - d) / (d (f - n)). */
            proj[10] = (float)(zn / (zf - zn));
            proj[14] = (float)(zf * zn / (zf - zn));
        }
        for (size_t i = 0; i < n; ++i) {
            if (!(d[i] > 0.0f)) {
                win[i] = cases[c].reversed ? 0.0f : 1.0f;
                continue;
            }
            double ndc = -proj[10] + proj[14] / (double)d[i];
            win[i] = (float)(cases[c].reversed ? ndc : ndc * 0.5 + 0.5);
        }
        GLuint depth = 0;
        glCreateTextures(GL_TEXTURE_2D, 1, &depth);
        glTextureStorage2D(depth, 1, cases[c].format, W, H);
        glTextureSubImage2D(depth, 0, 0, 0, W, H, GL_DEPTH_COMPONENT, GL_FLOAT, win);
        ob_host_frame f = {.depth = depth, .normal = normal_tex, .normal_space = OB_NORMALS_WORLD,
                           .depth_zero_to_one = cases[c].reversed};
        memcpy(f.view, a->frame_constants.view, sizeof f.view);
        memcpy(f.projection, proj, sizeof f.projection);
        CHECK(ob_host_ao(b, &f, &hs, &(ob_host_outputs){.ao = out}) == OB_OK, "%s: %s", cases[c].name, error_text());
        read_tex(out, GL_R32F, 1, n, got);
        double sum = 0.0;
        for (size_t i = 0; i < n; ++i) sum += fabs((double)got[i] - (double)ref[i]);
        CHECK(sum / (double)n <= cases[c].tol, "%s: mean |AO - frame's AO| %g above %g", cases[c].name, sum / (double)n,
              cases[c].tol);
        printf("  %-16s mean |diff| %.5f  max %.4f\n", cases[c].name, sum / (double)n, worst_diff(got, ref, n));
        glDeleteTextures(1, &depth);
    }
    /* No normals: rebuilt from the linear depth (flat, one-sided differences). */
    ob_host_frame f = {.depth = copy_of(a->gbuffer.linear_depth, GL_R32F, W, H)};
    memcpy(f.view, a->frame_constants.view, sizeof f.view);
    memcpy(f.projection, P, sizeof f.projection);
    CHECK(ob_host_ao(b, &f, &hs, &(ob_host_outputs){.ao = out}) == OB_OK, "no normals: %s", error_text());
    read_tex(out, GL_R32F, 1, n, got);
    double sum = 0.0;
    for (size_t i = 0; i < n; ++i) sum += fabs((double)got[i] - (double)ref[i]);
    printf("  %-16s mean |diff| %.5f  max %.4f (reported, no bound)\n", "rebuilt normals", sum / (double)n,
           worst_diff(got, ref, n));
    CHECK(sum / (double)n < 0.1, "rebuilt normals: mean |diff| %g", sum / (double)n);
    glDeleteTextures(1, &f.depth);
    GLuint t[2] = {normal_tex, out};
    glDeleteTextures(2, t);
    free(d);
    free(nv);
    free(ref);
    free(win);
    free(oct);
    free(got);
    ob_destroy_renderer(a);
    ob_destroy_renderer(b);
}

/* A host's motion vectors: the camera's own motion, as a host computes it per pixel (previous
 * minus current position, +y up), gives the accumulation the camera's reprojection gave without
 * them (to float rounding); vectors that point elsewhere give another history. */
static void motion_vectors(ob_context *ctx, ob_scene *scene)
{
    ob_renderer *a = ob_make_renderer(ctx, &(ob_renderer_desc){.width = W, .height = H});
    ob_renderer *b = ob_make_renderer(ctx, &(ob_renderer_desc){.width = W, .height = H});
    ob_renderer *c = ob_make_renderer(ctx, &(ob_renderer_desc){.width = W, .height = H});
    CHECK(a && b && c && ob_renderer_set_scene(a, scene) == OB_OK, "motion: renderers");
    if (!a || !b || !c) return;
    ob_settings s;
    ob_settings_init(&s, "vbao");
    s.temporal = true;
    const ob_settings hs = host_settings(&s, ob_query_scene_ao_radius(scene));
    const size_t n = (size_t)W * H;
    float *d = malloc(n * sizeof(float)), *mv = malloc(2 * n * sizeof(float)), *bad = malloc(2 * n * sizeof(float));
    float *x = malloc(n * sizeof(float)), *y = malloc(n * sizeof(float)), *z = malloc(n * sizeof(float));
    GLuint motion = ob_make_texture_2d(GL_RG32F, W, H), wrong = ob_make_texture_2d(GL_RG32F, W, H);
    GLuint out[3] = {ob_make_texture_2d(GL_R32F, W, H), ob_make_texture_2d(GL_R32F, W, H), ob_make_texture_2d(GL_R32F, W, H)};
    mat4 prev_vp = GLM_MAT4_IDENTITY_INIT;
    bool ok = true;
    for (int i = 0; i < 4 && ok; ++i) {
        const ob_camera cam = camera_at(i);
        ok = ob_render_frame(a, &cam, &s) == OB_OK;
        host_inputs in;
        grab(a, &in);
        read_tex(in.depth, GL_R32F, 1, n, d);
        mat4 view, proj, inv_view, vp;
        memcpy(view, in.view, sizeof view);
        memcpy(proj, in.proj, sizeof proj);
        glm_mat4_inv(view, inv_view);
        glm_mat4_mul(proj, view, vp);
        for (int py = 0; py < H; ++py)
            for (int px = 0; px < W; ++px) {
                size_t k = (size_t)py * W + (size_t)px;
                float dd = d[k];
                mv[2 * k] = mv[2 * k + 1] = 0.0f;
                bad[2 * k] = 3.0f;
                bad[2 * k + 1] = -2.0f;
                if (!(dd > 0.0f) || i == 0) continue;
                /* The view point of this pixel (common.glsl's ob_view_position), to world, to the
                 * previous frame's pixel. */
                float ndx = 2.0f * ((float)px + 0.5f) / W - 1.0f, ndy = 2.0f * ((float)py + 0.5f) / H - 1.0f;
                vec4 pv = {(ndx + proj[2][0]) * dd / proj[0][0], (ndy + proj[2][1]) * dd / proj[1][1], -dd, 1.0f}, pw, clip;
                glm_mat4_mulv(inv_view, pv, pw);
                glm_mat4_mulv(prev_vp, pw, clip);
                float qx = (clip[0] / clip[3] * 0.5f + 0.5f) * W, qy = (clip[1] / clip[3] * 0.5f + 0.5f) * H;
                mv[2 * k] = qx - ((float)px + 0.5f);
                mv[2 * k + 1] = qy - ((float)py + 0.5f);
            }
        glm_mat4_copy(vp, prev_vp);
        glTextureSubImage2D(motion, 0, 0, 0, W, H, GL_RG, GL_FLOAT, mv);
        glTextureSubImage2D(wrong, 0, 0, 0, W, H, GL_RG, GL_FLOAT, bad);
        ob_renderer *who[3] = {b, c, NULL};
        ob_host_frame f = {.depth = in.depth, .normal = in.normal};
        memcpy(f.view, in.view, sizeof f.view);
        memcpy(f.projection, in.proj, sizeof f.projection);
        ok = ok && ob_host_ao(b, &f, &hs, &(ob_host_outputs){.ao = out[0]}) == OB_OK;
        f.motion = motion;
        ok = ok && ob_host_ao(c, &f, &hs, &(ob_host_outputs){.ao = out[1]}) == OB_OK;
        (void)who;
        release(&in);
        CHECK(ok, "motion: frame %d: %s", i, error_text());
    }
    /* One more frame on b with the wrong vectors: a different accumulation. */
    read_tex(out[0], GL_R32F, 1, n, x);
    read_tex(out[1], GL_R32F, 1, n, y);
    double diff = 0.0;
    for (size_t i = 0; i < n; ++i) diff += fabs((double)x[i] - (double)y[i]);
    printf("  motion vectors = the camera's: mean |diff| %.6f  max %.6f\n", diff / (double)n, worst_diff(x, y, n));
    CHECK(diff / (double)n < 2e-3, "motion vectors equal to the camera's motion: mean |diff| %g", diff / (double)n);
    const ob_camera cam = camera_at(4);
    ok = ob_render_frame(a, &cam, &s) == OB_OK;
    host_inputs in;
    grab(a, &in);
    ob_host_frame f = {.depth = in.depth, .normal = in.normal, .motion = wrong};
    memcpy(f.view, in.view, sizeof f.view);
    memcpy(f.projection, in.proj, sizeof f.projection);
    CHECK(ok && ob_host_ao(c, &f, &hs, &(ob_host_outputs){.ao = out[2]}) == OB_OK, "motion: wrong vectors: %s", error_text());
    f.motion = 0;
    CHECK(ob_host_ao(b, &f, &hs, &(ob_host_outputs){.ao = out[0]}) == OB_OK, "motion: last frame: %s", error_text());
    read_tex(out[0], GL_R32F, 1, n, x);
    read_tex(out[2], GL_R32F, 1, n, z);
    diff = 0.0;
    for (size_t i = 0; i < n; ++i) diff += fabs((double)x[i] - (double)z[i]);
    CHECK(diff / (double)n > 1e-3, "vectors pointing 3.6 px away change the history (mean |diff| %g)", diff / (double)n);
    release(&in);
    GLuint t[5] = {motion, wrong, out[0], out[1], out[2]};
    glDeleteTextures(5, t);
    free(d);
    free(mv);
    free(bad);
    free(x);
    free(y);
    free(z);
    ob_destroy_renderer(a);
    ob_destroy_renderer(b);
    ob_destroy_renderer(c);
}

/* After a host call the renderer's own frame is gone: its read-backs are refused, not stale; the
 * AO grid's own images (raw AO, history age) are the call's; the motion only where the depth went
 * through the input pass (the read-back reprojects the G-buffer's depth). */
static void read_back_after_host(ob_context *ctx, ob_scene *scene)
{
    ob_renderer *a = ob_make_renderer(ctx, &(ob_renderer_desc){.width = W, .height = H});
    CHECK(a && ob_renderer_set_scene(a, scene) == OB_OK, "read-back: renderer");
    if (!a) return;
    ob_settings s;
    ob_settings_init(&s, "vbao");
    s.temporal = true;
    const ob_settings hs = host_settings(&s, ob_query_scene_ao_radius(scene));
    const ob_camera cam = camera_at(0);
    CHECK(ob_render_frame(a, &cam, &s) == OB_OK, "read-back: frame: %s", error_text());
    host_inputs in;
    grab(a, &in);
    static float img[4 * W * H];
    CHECK(ob_read_image(a, OB_IMAGE_AO_F32, img, sizeof img) == OB_OK, "read-back: the frame's AO");
    ob_host_frame f = {.depth = in.depth, .normal = in.normal};
    memcpy(f.view, in.view, sizeof f.view);
    memcpy(f.projection, in.proj, sizeof f.projection);
    GLuint out = ob_make_texture_2d(GL_R32F, W, H);
    CHECK(ob_host_ao(a, &f, &hs, &(ob_host_outputs){.ao = out}) == OB_OK, "read-back: host call: %s", error_text());
    const ob_image_kind refused[] = {OB_IMAGE_AO_F32, OB_IMAGE_FINAL_RGBA8, OB_IMAGE_DEPTH_F32, OB_IMAGE_MOTION_F32};
    for (size_t i = 0; i < sizeof refused / sizeof refused[0]; ++i) {
        CHECK(ob_read_image(a, refused[i], img, sizeof img) == OB_ERR_INVALID_ARGUMENT,
              "read-back of image kind %d after a host call on linear depth is refused", (int)refused[i]);
        ob_get_error(NULL);
    }
    CHECK(ob_read_image(a, OB_IMAGE_AO_RAW_F32, img, sizeof img) == OB_OK, "raw AO after a host call: %s", error_text());
    CHECK(ob_read_image(a, OB_IMAGE_HISTORY_AGE_F32, img, sizeof img) == OB_OK, "history age after a host call: %s",
          error_text());
    CHECK(ob_present(a, OB_VIEW_FINAL, 0, 0, 0, W, H) == OB_ERR_INVALID_ARGUMENT, "ob_present after a host call");
    ob_get_error(NULL);
    CHECK(ob_render_frame(a, &cam, &s) == OB_OK && ob_read_image(a, OB_IMAGE_AO_F32, img, sizeof img) == OB_OK,
          "a frame after the host call reads back again: %s", error_text());
    release(&in);
    glDeleteTextures(1, &out);
    ob_destroy_renderer(a);
}

/* ob_camera_matrices gives the very matrices ob_render_frame drew with, and refuses what it cannot
 * fill in. */
static void camera_matrices(ob_context *ctx, ob_scene *scene)
{
    ob_renderer *a = ob_make_renderer(ctx, &(ob_renderer_desc){.width = W, .height = H});
    CHECK(a && ob_renderer_set_scene(a, scene) == OB_OK, "camera matrices: renderer");
    if (!a) return;
    ob_settings s;
    ob_settings_init(&s, "vbao");
    ob_camera cam = camera_at(3);
    CHECK(ob_render_frame(a, &cam, &s) == OB_OK, "camera matrices: frame: %s", error_text());
    const ob_scene_stats st = ob_query_scene_stats(scene);
    float view[16], proj[16];
    CHECK(ob_camera_matrices(&cam, st.bounds_min, st.bounds_max, W, H, view, proj) == OB_OK, "ob_camera_matrices: %s",
          error_text());
    CHECK(!memcmp(view, a->frame_constants.view, sizeof view) && !memcmp(proj, a->frame_constants.proj, sizeof proj),
          "ob_camera_matrices gives the frame's view and projection bit for bit");
    CHECK(cam.near_z > 0.0f && cam.far_z > cam.near_z, "the fitted planes are left in the camera");
    ob_camera no_planes = camera_at(0);
    no_planes.near_z = no_planes.far_z = 0.0f;
    CHECK(ob_camera_matrices(&no_planes, NULL, NULL, W, H, view, proj) == OB_ERR_INVALID_ARGUMENT,
          "no planes and no bounds are refused");
    ob_get_error(NULL);
    CHECK(ob_camera_matrices(&cam, NULL, NULL, 0, H, view, proj) == OB_ERR_INVALID_ARGUMENT, "a 0-wide frame is refused");
    ob_get_error(NULL);
    ob_destroy_renderer(a);
}

int main(void)
{
    ob_context *ctx = check_context();
    if (!ctx) return 1;
    ob_scene *scene = ob_load_scene(&(ob_scene_desc){.name = "cornell"});
    CHECK(scene != NULL, "scene: %s", error_text());
    if (!scene) return check_finish("host_chain");
    base_camera = ob_query_camera(scene, 0);
    same_bits(ctx, scene, "vbao", NULL, 1, false, 0, false, 1);
    same_bits(ctx, scene, "gtao", "bent_normals=on", 2, false, 0, false, 1);
    same_bits(ctx, scene, "vbao", NULL, 4, false, 0, false, 1);
    same_bits(ctx, scene, "vbao", NULL, 2, true, 0, false, 4);
    same_bits(ctx, scene, "gtao", NULL, 1, true, 8, false, 3);
    same_bits(ctx, scene, "ssao", NULL, 1, false, 0, true, 1);
    same_bits(ctx, scene, "hbao", NULL, 2, false, 8, false, 1);
    same_bits(ctx, scene, "vbgi", NULL, 2, false, 0, false, 1);
    same_bits(ctx, scene, "ssdo", NULL, 1, false, 0, false, 1);
    same_bits(ctx, scene, "none", NULL, 1, false, 0, false, 1);
    same_bits(ctx, scene, "vbao", "layers=2", 1, false, 0, false, 1);
    same_bits(ctx, scene, "gtao", "layers=2", 2, false, 0, false, 1);
    through_input_pass(ctx, scene);
    motion_vectors(ctx, scene);
    read_back_after_host(ctx, scene);
    camera_matrices(ctx, scene);
    ob_destroy_scene(scene);
    ob_destroy_context(ctx);
    return check_finish("host_chain");
}
