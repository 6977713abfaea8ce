/* gtao (shaders/gtao.glsl) against what it estimates:
 *   - the closed-form AO_R next to one wall (docs/architecture.md): a floor point at h from the wall has
 *     AO_R = 1 - (acos a - a sqrt(1 - a^2)) / π, a = h / R; open floor reads exactly 1;
 *   - one test body, two implementations: a CPU port of the same slice integral on a synthetic
 *     depth buffer (a box on a floor, ray cast here) agrees with the GPU pass. */
#include <cglm/cglm.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "check.h"
#include "corner_wall.h"
#include "gpu/gpu.h"
#include "obscura/eval.h"
#include "sampling/sampling.h"

#ifndef M_PI
#define M_PI 3.14159265358979323846
#endif

enum { W = 160, H = 120 };

/* ---- the analytic corner -------------------------------------------------------------------- */
static void test_corner(ob_context *ctx)
{
    const float radius = 0.5f;
    ob_settings s;
    ob_settings_init(&s, "gtao");
    ob_settings_set_filter(&s, "none");
    /* Many slices and steps: the estimator converged, no filter, the definition's hard cut. */
    CHECK(ob_settings_set(&s, "gtao.radius=0.5") == OB_OK && ob_settings_set(&s, "gtao.slices=16") == OB_OK &&
              ob_settings_set(&s, "gtao.steps=32") == OB_OK && ob_settings_set(&s, "gtao.falloff=0") == OB_OK &&
              ob_settings_set(&s, "gtao.bent_normals=on") == OB_OK,
          "settings");
    corner_wall f;
    if (!corner_wall_render(ctx, &s, W, H, &f)) {
        corner_wall_free(&f);
        return;
    }
    size_t n = (size_t)W * H;
    mat4 inv_view;
    memcpy(inv_view, f.inv_view, sizeof inv_view);

    /* Bins of h / R: the mean of gtao against the mean of the closed form over the same pixels. */
    enum { BINS = 10 };
    double sum_ao[BINS] = {0}, sum_ref[BINS] = {0};
    int count[BINS] = {0}, open_count = 0, near_count = 0, near_away = 0;
    float open_min = 1.0f;
    double open_bent_worst = 0.0, near_tilt = 0.0;
    for (size_t i = 0; i < n; ++i) {
        double h = 0.0;
        if (!corner_wall_floor(&f, i, radius, &h)) continue;
        /* The bent normal in world space (filter none: as the pass wrote it). */
        vec3 bv = {f.bent[3 * i], f.bent[3 * i + 1], f.bent[3 * i + 2]}, bw;
        glm_mat4_mulv3(inv_view, bv, 0.0f, bw);
        glm_vec3_normalize(bw);
        if (h >= radius * 1.02) {
            open_min = fminf(open_min, f.ao[i]);
            /* Open: the bent normal is the normal (0, 1, 0). */
            open_bent_worst = fmax(open_bent_worst, acos(fmin(1.0, (double)bw[1])));
            ++open_count;
            continue;
        }
        if (h < 0.3 * radius) {
            /* Next to the wall x = 0 the visible cone leans away from it, toward +x. */
            ++near_count;
            near_away += bw[0] > 0.05f;
            near_tilt += asin(fmax(-1.0, fmin(1.0, (double)bw[0])));
        }
        int b = (int)(h / radius * BINS);
        if (b < 0 || b >= BINS) continue;
        sum_ao[b] += f.ao[i];
        sum_ref[b] += ao_r_one_wall(h, radius);
        ++count[b];
    }
    printf("  gtao beside one wall (R 0.5, 16 x 32, no filter): h/R bin, pixels, gtao, AO_R\n");
    for (int b = 0; b < BINS; ++b) {
        if (count[b] == 0) continue;
        double g = sum_ao[b] / count[b], ref = sum_ref[b] / count[b];
        printf("    %.1f-%.1f %4d %.3f %.3f\n", (double)b / BINS, (double)(b + 1) / BINS, count[b], g, ref);
        CHECK(fabs(g - ref) <= 0.03, "h/R %.1f-%.1f: gtao %.3f, AO_R %.3f", (double)b / BINS, (double)(b + 1) / BINS,
              g, ref);
    }
    int covered = 0;
    for (int b = 0; b < BINS; ++b) covered += count[b] >= 10;
    CHECK(covered >= 8, "the bins near the wall have pixels (%d of %d)", covered, BINS);
    CHECK(open_count > 500 && open_min >= 0.9999f, "open floor reads 1 (%d pixels, lowest %.6f)", open_count,
          (double)open_min);
    printf("  bent normal: open floor within %.3f deg of the normal; within 0.3 R of the wall %d of %d lean away, "
           "mean %.1f deg\n",
           open_bent_worst * 180.0 / M_PI, near_away, near_count, near_count ? near_tilt / near_count * 180.0 / M_PI : 0.0);
    CHECK(open_bent_worst < 0.5 * M_PI / 180.0, "open floor: bent normal = normal (off by %.3f deg)",
          open_bent_worst * 180.0 / M_PI);
    CHECK(near_count > 50 && near_away == near_count, "beside the wall the bent normal leans away (%d of %d)", near_away,
          near_count);
    corner_wall_free(&f);
}

/* ---- one test body, two implementations ------------------------------------------------------ */

/* A synthetic G-buffer: the floor y = 0 and an axis-aligned box on it, ray cast from a camera. */
typedef struct synth {
    float depth[W * H];      /* linear view depth, 0 = sky */
    float normal[W * H * 4]; /* view space, w = 1 */
    float proj_info[4];
    mat4 proj;
} synth;

static bool hit_box(const vec3 o, const vec3 d, const vec3 lo, const vec3 hi, float *t_out, vec3 n_out)
{
    float t0 = 0.0f, t1 = 1e30f;
    int axis = -1;
    float sign = 0.0f;
    for (int k = 0; k < 3; ++k) {
        if (fabsf(d[k]) < 1e-12f) {
            if (o[k] < lo[k] || o[k] > hi[k]) return false;
            continue;
        }
        float a = (lo[k] - o[k]) / d[k], b = (hi[k] - o[k]) / d[k];
        float s = -1.0f;
        if (a > b) {
            float tmp = a;
            a = b;
            b = tmp;
            s = 1.0f;
        }
        if (a > t0) {
            t0 = a;
            axis = k;
            sign = s;
        }
        if (b < t1) t1 = b;
        if (t0 > t1) return false;
    }
    if (axis < 0) return false;
    *t_out = t0;
    glm_vec3_zero(n_out);
    n_out[axis] = sign;
    return true;
}

static void make_synth(synth *g)
{
    vec3 eye = {0.0f, 1.6f, 3.2f}, target = {0.0f, 0.3f, 0.0f}, up = {0, 1, 0};
    mat4 view;
    glm_lookat(eye, target, up, view);
    glm_perspective(glm_rad(55.0f), (float)W / (float)H, 0.1f, 30.0f, g->proj);
    g->proj_info[0] = 1.0f / g->proj[0][0];
    g->proj_info[1] = 1.0f / g->proj[1][1];
    g->proj_info[2] = g->proj[2][0];
    g->proj_info[3] = g->proj[2][1];
    const vec3 lo = {-0.5f, 0.0f, -0.6f}, hi = {0.4f, 0.7f, 0.2f};
    mat4 inv; /* view -> world, for the rays */
    glm_mat4_inv(view, inv);
    for (int y = 0; y < H; ++y)
        for (int x = 0; x < W; ++x) {
            /* The ray through the pixel centre, in view space, as common.glsl reconstructs it. */
            float ndc_x = ((float)x + 0.5f) / W * 2.0f - 1.0f, ndc_y = ((float)y + 0.5f) / H * 2.0f - 1.0f;
            vec3 dv = {(ndc_x + g->proj_info[2]) * g->proj_info[0], (ndc_y + g->proj_info[3]) * g->proj_info[1], -1.0f};
            vec3 dw;
            glm_mat4_mulv3(inv, dv, 0.0f, dw);
            float best = 1e30f;
            vec3 nw = {0, 0, 0};
            if (dw[1] < -1e-6f) {
                float t = -eye[1] / dw[1]; /* the floor */
                vec3 p;
                glm_vec3_scale(dw, t, p);
                glm_vec3_add(p, eye, p);
                if (fabsf(p[0]) < 6.0f && fabsf(p[2]) < 6.0f) {
                    best = t;
                    glm_vec3_copy((vec3){0, 1, 0}, nw);
                }
            }
            float tb = 0.0f;
            vec3 nb;
            if (hit_box(eye, dw, lo, hi, &tb, nb) && tb < best) {
                best = tb;
                glm_vec3_copy(nb, nw);
            }
            size_t i = (size_t)y * W + (size_t)x;
            /* dv has z = -1, so t along it is the linear depth. */
            g->depth[i] = best < 1e29f ? best : 0.0f;
            vec3 nv;
            glm_mat4_mulv3(view, nw, 0.0f, nv);
            memcpy(&g->normal[4 * i], nv, sizeof nv);
            g->normal[4 * i + 3] = 1.0f;
        }
}

/* shaders/gtao.glsl on the CPU, texture4 noise, full-resolution depth; the same constants. */
static const float bayer4[16] = {0, 8, 2, 10, 12, 4, 14, 6, 3, 11, 1, 9, 15, 7, 13, 5};

static void view_position(const synth *g, float px, float py, float d, vec3 out)
{
    float ndc_x = px * (1.0f / W) * 2.0f - 1.0f, ndc_y = py * (1.0f / H) * 2.0f - 1.0f;
    out[0] = (ndc_x + g->proj_info[2]) * d * g->proj_info[0];
    out[1] = (ndc_y + g->proj_info[3]) * d * g->proj_info[1];
    out[2] = -d;
}

/* The angle from V of offset w above the side's tangent: the tangent less its rise in [0, π]; on
 * or below the tangent's plane (y <= 0) none: a sample exactly on P's plane behind the tangent
 * would otherwise get atan2(+0, x < 0) = π. Rises under 1e-3 rad are none (slice_march.glsl
 * ob_rise_key). */
static float rise_theta(const vec3 w, const vec3 n, const vec3 t, float inv_len_n, float tangent)
{
    float y = glm_vec3_dot((float *)w, (float *)n) * inv_len_n, x = glm_vec3_dot((float *)w, (float *)t);
    float rise = y > 1e-3f * sqrtf(x * x + y * y) ? atan2f(y, x) : 0.0f;
    return tangent - rise;
}

enum { NONE = 0, INSIDE = 1, BEYOND = 2 };

/* The sample at (ax, ay): its kind, its angle theta from V (the tangent when it does not rise) and
 * its offset w from P. */
static int sample_theta(const synth *g, float ax, float ay, const vec3 p, const vec3 n, const vec3 t, float inv_len_n,
                        float tangent, float radius, float *theta, vec3 w)
{
    *theta = tangent;
    glm_vec3_zero(w);
    int qx = (int)floorf(ax), qy = (int)floorf(ay);
    float sd = g->depth[qy * W + qx];
    if (sd <= 0.0f) return NONE;
    vec3 s;
    view_position(g, (float)qx + 0.5f, (float)qy + 0.5f, sd, s);
    glm_vec3_sub(s, (float *)p, w);
    if (glm_vec3_dot(w, w) <= 1e-12f * glm_vec3_dot((float *)p, (float *)p)) return NONE; /* P's own texel (slice_march.glsl) */
    *theta = rise_theta(w, n, t, inv_len_n, tangent);
    return glm_vec3_norm(w) >= radius ? BEYOND : INSIDE;
}

/* gtao.glsl's column_rise: where the view ray behind the candidate w (at most `column` behind its
 * front) enters the sphere of radius R; its theta, or the tangent when it does not. */
static float column_theta(const vec3 p, const vec3 w, const vec3 n, const vec3 t, float inv_len_n, float tangent,
                          float radius, float column)
{
    vec3 u, s, e;
    glm_vec3_add((float *)p, (float *)w, s);
    glm_vec3_normalize_to(s, u);
    float b = glm_vec3_dot((float *)w, u), c = glm_vec3_dot((float *)w, (float *)w) - radius * radius, disc = b * b - c;
    float tc = -(b + sqrtf(fmaxf(disc, 0.0f)));
    if (!(c > 0.0f && b < 0.0f && disc >= 0.0f && tc <= column)) return tangent;
    glm_vec3_scale(u, tc, e);
    glm_vec3_add(e, (float *)w, e);
    return rise_theta(e, n, t, inv_len_n, tangent);
}

static float cpu_gtao(const synth *g, const float rot[16][2], int x, int y, float radius, float column, int slices,
                      int steps)
{
    const float half_pi = 1.57079632679490f, pi = 3.14159265358979f;
    float d = g->depth[y * W + x];
    if (d <= 0.0f) return 1.0f;
    float cx = (float)x + 0.5f, cy = (float)y + 0.5f;
    vec3 p, v, n;
    view_position(g, cx, cy, d, p);
    glm_vec3_negate_to(p, v);
    glm_vec3_normalize(v);
    glm_vec3_copy((float *)&g->normal[4 * (y * W + x)], n);
    glm_vec3_normalize(n);
    float nv = glm_vec3_dot(n, v);
    if (nv < 0.02f) {
        vec3 tmp;
        glm_vec3_scale(v, 0.02f - nv, tmp);
        glm_vec3_add(n, tmp, n);
        glm_vec3_normalize(n);
    }
    const float to_view[2] = {g->proj_info[0] * (1.0f / W) * 2.0f, g->proj_info[1] * (1.0f / H) * 2.0f};
    int tx = x % 4, ty = y % 4;
    const float *r = rot[ty * 4 + tx];
    float jx = atan2f(r[1], r[0]) / (2.0f * pi) + 1.0f;
    jx -= floorf(jx);
    float jy = (bayer4[ty * 4 + tx] + 0.5f) / 16.0f;
    float vis = 0.0f, open_sky = 0.0f;
    for (int k = 0; k < slices; ++k) {
        float phi = ((float)k + jx) * pi / (float)slices;
        float dir[2] = {cosf(phi), sinf(phi)};
        vec3 dv = {dir[0] * to_view[0], dir[1] * to_view[1], 0.0f}, axis, o, pn, tmp;
        glm_vec3_cross(v, dv, axis);
        glm_vec3_normalize(axis);
        glm_vec3_cross(axis, v, o);
        glm_vec3_scale(axis, glm_vec3_dot(n, axis), tmp);
        glm_vec3_sub(n, tmp, pn);
        float len_n = glm_vec3_norm(pn);
        if (len_n < 1e-4f) continue;
        float ang_n = atan2f(glm_vec3_dot(pn, o), glm_vec3_dot(pn, v));
        float radius_px = radius / (d * sqrtf(dv[0] * dv[0] + dv[1] * dv[1]));
        float h[2];
        for (int side = 0; side < 2; ++side) {
            float sgn = side == 0 ? 1.0f : -1.0f;
            float tangent = half_pi + sgn * ang_n;
            vec3 t, a, b;
            glm_vec3_scale(v, cosf(tangent), a);
            glm_vec3_scale(o, sinf(tangent) * sgn, b);
            glm_vec3_add(a, b, t);
            float horizon = tangent, inside_px = 0.0f, theta = 0.0f;
            bool refined = false;
            /* The candidate for the column (gtao.glsl column_candidate): the highest sample beyond R
             * within R + column of P; cand_theta = tangent: none yet. */
            float cand_theta = tangent;
            vec3 cand_w = {0, 0, 0}, w;
            const float shell = (radius + column) * (radius + column);
            for (int j = 0; j < steps; ++j) {
                float s = ((float)j + jy) / (float)steps;
                float dist = 1.5f + s * fmaxf(radius_px - 1.5f, 0.0f);
                if (dist > radius_px) break;
                float ax = cx + sgn * dir[0] * dist, ay = cy + sgn * dir[1] * dist;
                if (ax < 0.0f || ay < 0.0f || ax >= W || ay >= H) break;
                int st = sample_theta(g, ax, ay, p, n, t, 1.0f / len_n, tangent, radius, &theta, w);
                if (st == BEYOND && glm_vec3_dot(w, w) <= shell && theta < cand_theta) {
                    cand_theta = theta;
                    glm_vec3_copy(w, cand_w);
                }
                if (st == INSIDE) {
                    horizon = fminf(horizon, theta);
                    inside_px = dist;
                } else if (st == BEYOND && !refined && theta < horizon) {
                    refined = true;
                    float lo = inside_px, hi = dist;
                    for (int it = 0; it < 2; ++it) {
                        float mid = 0.5f * (lo + hi);
                        int m = sample_theta(g, cx + sgn * dir[0] * mid, cy + sgn * dir[1] * mid, p, n, t,
                                             1.0f / len_n, tangent, radius, &theta, w);
                        if (m == BEYOND && glm_vec3_dot(w, w) <= shell && theta < cand_theta) {
                            cand_theta = theta;
                            glm_vec3_copy(w, cand_w);
                        }
                        if (m == INSIDE) {
                            horizon = fminf(horizon, theta);
                            lo = mid;
                        } else {
                            hi = mid;
                        }
                    }
                }
            }
            if (cand_theta < tangent)
                horizon = fminf(horizon, column_theta(p, cand_w, n, t, 1.0f / len_n, tangent, radius, column));
            h[side] = fmaxf(horizon, 0.0f);
        }
        float h0 = -h[1], h1 = h[0], cn = cosf(ang_n), sn = sinf(ang_n);
        float a = 0.25f * (-cosf(2.0f * h0 - ang_n) + cn + 2.0f * h0 * sn) +
                  0.25f * (-cosf(2.0f * h1 - ang_n) + cn + 2.0f * h1 * sn);
        vis += len_n * a;
        open_sky += len_n * (cn + ang_n * sn);
    }
    return open_sky > 0.0f ? fminf(fmaxf(vis / open_sky, 0.0f), 1.0f) : 1.0f;
}

/* The GPU pass against the CPU port at one `thickness` (x R; < 0: gtao's default). Returns the
 * CPU port's mean AO, or -1 when the pass could not run. */
static double port_at(ob_renderer *r, const synth *g, const GLuint tex[3], float thickness)
{
    const float radius = 0.4f;
    ob_settings s;
    ob_settings_init(&s, "gtao");
    CHECK(ob_settings_set(&s, "gtao.radius=0.4") == OB_OK, "radius");
    char set[64];
    if (thickness >= 0.0f) {
        snprintf(set, sizeof set, "gtao.thickness=%g", (double)thickness);
        CHECK(ob_settings_set(&s, set) == OB_OK, "%s", set);
    }
    const float column = (thickness >= 0.0f ? thickness : ob_settings_get(&s, "thickness")) * radius;
    if (ob_compute_ao(r, tex[0], tex[1], (const float *)g->proj, &s, tex[2]) != OB_OK) {
        const char *message = NULL;
        ob_get_error(&message);
        CHECK(false, "ob_compute_ao gtao: %s", message ? message : "?");
        return -1.0;
    }
    float *gpu = malloc((size_t)W * H * sizeof(float));
    glGetTextureImage(tex[2], 0, GL_RED, GL_FLOAT, (GLsizei)((size_t)W * H * sizeof(float)), gpu);
    float rot[16][2];
    ob_rotation_noise_4x4(&rot[0][0], 0x4E01u);
    double worst = 0.0, sum = 0.0, mean_ao = 0.0;
    int over = 0, occluded = 0, worst_x = 0, worst_y = 0;
    float worst_cpu = 0.0f;
    for (int y = 0; y < H; ++y)
        for (int x = 0; x < W; ++x) {
            float c = cpu_gtao(g, rot, x, y, radius, column, 3, 6);
            double d = fabs((double)c - (double)gpu[y * W + x]);
            if (d > worst) {
                worst_x = x;
                worst_y = y;
                worst_cpu = c;
            }
            worst = fmax(worst, d);
            sum += d;
            over += d > 1e-3;
            mean_ao += c;
            occluded += c < 0.9f;
        }
    printf("  gtao CPU port vs GPU, %dx%d box on a floor, thickness %.2f R: mean |diff| %.2g, worst %.2g, %d pixels "
           "over 1e-3, mean AO %.4f, %d pixels below 0.9\n",
           W, H, (double)(column / radius), sum / (W * H), worst, over, mean_ao / (W * H), occluded);
    CHECK(occluded > 300, "the synthetic scene has occlusion to compare (%d pixels below 0.9)", occluded);
    if (over > 0) { /* the neighbourhood of the worst pixel, to see which samples the two disagree on */
        for (int y = worst_y + 3; y >= worst_y - 3; --y) {
            printf("   row %3d:", y);
            for (int x = worst_x - 4; x <= worst_x + 4; ++x)
                if (x >= 0 && x < W && y >= 0 && y < H)
                    printf(" %.3f/%.3f", (double)cpu_gtao(g, rot, x, y, radius, column, 3, 6), (double)gpu[y * W + x]);
            printf("\n");
        }
    }
    CHECK(over == 0, "CPU and GPU agree within 1e-3 (%d pixels over, worst %.3g at (%d, %d): CPU %.4f, GPU %.4f)", over,
          worst, worst_x, worst_y, (double)worst_cpu, (double)gpu[worst_y * W + worst_x]);
    free(gpu);
    return mean_ao / (W * H);
}

static void test_cpu_port(ob_context *ctx)
{
    synth *g = calloc(1, sizeof *g);
    make_synth(g);
    ob_renderer *r = ob_make_renderer(ctx, &(ob_renderer_desc){.width = W, .height = H});
    CHECK(r != NULL, "renderer");
    if (!r) {
        free(g);
        return;
    }
    GLuint tex[3] = {ob_make_texture_2d(GL_R32F, W, H), ob_make_texture_2d(GL_RGBA32F, W, H),
                     ob_make_texture_2d(GL_R32F, W, H)};
    glTextureSubImage2D(tex[0], 0, 0, 0, W, H, GL_RED, GL_FLOAT, g->depth);
    glTextureSubImage2D(tex[1], 0, 0, 0, W, H, GL_RGBA, GL_FLOAT, g->normal);
    /* No column (only samples within R occlude), the default, and a thick one: the box's sides
     * hide its far faces, so the thick column must darken, and the port follows each. */
    double none = port_at(r, g, tex, 0.0f);
    port_at(r, g, tex, -1.0f);
    double thick = port_at(r, g, tex, 2.0f);
    CHECK(thick < none - 1e-3, "a thick column darkens the box's surroundings (mean AO %.4f, without %.4f)", thick,
          none);
    glDeleteTextures(3, tex);
    free(g);
    ob_destroy_renderer(r);
}

int main(void)
{
    ob_context *ctx = check_context();
    if (!ctx) return 1;
    test_corner(ctx);
    test_cpu_port(ctx);
    ob_destroy_context(ctx);
    return check_finish("test_gtao");
}
