/* Left/right AO consistency of a stereo pair (Belonogov 2018 §5.2: each eye has its own G-buffer and AO).
 *
 * AO_R (Belonogov 2018 eq. 2.6-2.7) belongs to the surface point, not to the view, so a perfect method
 * gives the same value to a point in both eyes. A screen-space method sees a different depth
 * buffer from each eye (other silhouettes, other hidden parts, other noise), so the two disagree;
 * in a headset that disagreement flickers between the eyes ("binocular rivalry"). The measure:
 * every right-eye point reprojected into the left eye, the left AO read there, the mean absolute
 * difference over the points both eyes see. The ray-traced reference, traced from each eye's own
 * G-buffer points, gives the floor this reaches with no screen-space error (its Monte Carlo noise
 * and the resampling). */
#include <cglm/cglm.h>
#include <math.h>
#include <string.h>

#include "base/error.h"
#include "obscura/eval.h"

/* Relative depth agreement for "the same point": above the depth buffer's float error and the
 * bilinear depth's deviation from a plane, below the gap between a surface and what stands in
 * front of it at a few centimetres per metre. */
#define DEFAULT_DEPTH_TOLERANCE 0.02f

typedef struct eye_geometry {
    mat4 view, inv_view;
    float p00, p11, p20, p21; /* the projection's entries that map view space to NDC */
} eye_geometry;

static ob_error eye_make(const ob_camera *c, int width, int height, const char *which, eye_geometry *g)
{
    float fov = c->fov_y_deg > 0.0f ? c->fov_y_deg : 60.0f;
    float up[3] = {c->up[0], c->up[1], c->up[2]};
    if (up[0] == 0.0f && up[1] == 0.0f && up[2] == 0.0f) up[1] = 1.0f;
    float f[3] = {c->target[0] - c->eye[0], c->target[1] - c->eye[1], c->target[2] - c->eye[2]};
    float dist = sqrtf(f[0] * f[0] + f[1] * f[1] + f[2] * f[2]);
    if (!(fov < 179.0f) || !(dist > 0.0f) || !isfinite(dist) || !isfinite(c->shift[0] + c->shift[1]))
        return ob_set_error(OB_ERR_INVALID_ARGUMENT,
                            "ob_metric_stereo_consistency: the %s camera has eye = target, fov %g outside (0, 179) "
                            "or a shift that is not finite", which, (double)fov);
    vec3 eye = {c->eye[0], c->eye[1], c->eye[2]}, target = {c->target[0], c->target[1], c->target[2]};
    vec3 upv = {up[0], up[1], up[2]};
    glm_lookat(eye, target, upv, g->view);
    glm_mat4_inv(g->view, g->inv_view);
    /* As ob_render_frame's glm_perspective plus the lens shift (ob_camera.shift). */
    g->p11 = 1.0f / tanf(0.5f * fov * 3.14159265358979f / 180.0f);
    g->p00 = g->p11 * (float)height / (float)width;
    g->p20 = c->shift[0];
    g->p21 = c->shift[1];
    return OB_OK;
}

static float bilinear(const float *img, int w, int x0, int y0, float fx, float fy)
{
    const float *r0 = img + (size_t)y0 * (size_t)w + (size_t)x0;
    const float *r1 = r0 + w;
    return (1.0f - fy) * ((1.0f - fx) * r0[0] + fx * r0[1]) + fy * ((1.0f - fx) * r1[0] + fx * r1[1]);
}

static bool view_ok(const ob_stereo_view *v) { return v && v->ao && v->linear_depth && v->width >= 1 && v->height >= 1; }

ob_error ob_metric_stereo_consistency(const ob_stereo_view *left, const ob_stereo_view *right,
                                      float depth_tolerance, ob_stereo_consistency *out)
{
    if (out) memset(out, 0, sizeof *out);
    if (!view_ok(left) || !view_ok(right) || !out)
        return ob_set_error(OB_ERR_INVALID_ARGUMENT,
                            "ob_metric_stereo_consistency: a NULL argument or image, or a size below 1x1");
    if (!isfinite(depth_tolerance) || depth_tolerance < 0.0f)
        return ob_set_error(OB_ERR_INVALID_ARGUMENT, "ob_metric_stereo_consistency: depth tolerance %g",
                            (double)depth_tolerance);
    const float tol = depth_tolerance > 0.0f ? depth_tolerance : DEFAULT_DEPTH_TOLERANCE;
    eye_geometry gl, gr;
    if (eye_make(&left->camera, left->width, left->height, "left", &gl) != OB_OK ||
        eye_make(&right->camera, right->width, right->height, "right", &gr) != OB_OK)
        return ob_peek_error(NULL);
    /* Right view space -> left view space in one matrix. */
    mat4 r_to_l;
    glm_mat4_mul(gl.view, gr.inv_view, r_to_l);

    const int wl = left->width, hl = left->height, wr = right->width, hr = right->height;
    double sum = 0.0;
    size_t count = 0, geometry = 0;
    for (int y = 0; y < hr; ++y) {
        for (int x = 0; x < wr; ++x) {
            const size_t i = (size_t)y * (size_t)wr + (size_t)x;
            const float d = right->linear_depth[i];
            if (!(d > 0.0f) || !isfinite(d)) continue;
            ++geometry;
            /* shaders/common.glsl ob_view_position: the pixel centre's view position. */
            const float ndc_x = ((float)x + 0.5f) / (float)wr * 2.0f - 1.0f;
            const float ndc_y = ((float)y + 0.5f) / (float)hr * 2.0f - 1.0f;
            vec4 vr = {(ndc_x + gr.p20) * d / gr.p00, (ndc_y + gr.p21) * d / gr.p11, -d, 1.0f};
            vec4 vl;
            glm_mat4_mulv(r_to_l, vr, vl);
            const float dl = -vl[2];
            if (!(dl > 0.0f)) continue;
            /* ndc = P00 X / d - P20 (clip x = P00 X + P20 Z, w = -Z = d), then the pixel whose
             * centre it is (bottom row first, as the images). */
            const float px = ((gl.p00 * vl[0] / dl - gl.p20) + 1.0f) * 0.5f * (float)wl - 0.5f;
            const float py = ((gl.p11 * vl[1] / dl - gl.p21) + 1.0f) * 0.5f * (float)hl - 0.5f;
            if (!(px >= 0.0f && py >= 0.0f && px <= (float)(wl - 1) && py <= (float)(hl - 1))) continue;
            if (wl < 2 || hl < 2) continue; /* no 2x2 taps to read */
            int x0 = (int)px, y0 = (int)py;
            if (x0 > wl - 2) x0 = wl - 2;
            if (y0 > hl - 2) y0 = hl - 2;
            const float fx = px - (float)x0, fy = py - (float)y0;
            const float *dt = left->linear_depth + (size_t)y0 * (size_t)wl + (size_t)x0;
            if (!(dt[0] > 0.0f && dt[1] > 0.0f && dt[wl] > 0.0f && dt[wl + 1] > 0.0f)) continue;
            /* Occluded in the left eye: the left depth buffer holds something nearer (or, across
             * a silhouette, a mix that matches neither). */
            const float dseen = bilinear(left->linear_depth, wl, x0, y0, fx, fy);
            if (!(fabsf(dseen - dl) <= tol * dl)) continue;
            const float ao_l = bilinear(left->ao, wl, x0, y0, fx, fy);
            const float ao_r = right->ao[i];
            sum += fabs((double)ao_r - (double)ao_l);
            ++count;
        }
    }
    if (count == 0)
        return ob_set_error(OB_ERR_INVALID_ARGUMENT,
                            "ob_metric_stereo_consistency: no pixel is seen by both eyes (%zu right-eye geometry pixels)",
                            geometry);
    out->mean_abs = sum / (double)count;
    out->fraction = (double)count / (double)geometry;
    out->count = count;
    return OB_OK;
}
