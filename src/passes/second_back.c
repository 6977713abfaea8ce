/* The second layer over each pixel's footprint: what a method reads as its samples' backs
 * (docs/methods.md, "The back over a pixel's footprint"). Shader and reasons:
 * shaders/second_back.glsl. */
#include <math.h>
#include <stdbool.h>
#include <string.h>

#include "base/error.h"
#include "passes/passes.h"

/* shaders/second_back.glsl's second_back_block (std140). */
typedef struct second_back_block {
    GLint size[4]; /* width, height, planes bound, orthographic */
    float proj_info[4];
    float inv_size[4];
} second_back_block;

ob_error ob_second_back_init(ob_second_back *b)
{
    if (!b) return ob_set_error(OB_ERR_INVALID_ARGUMENT, "ob_second_back_init: NULL");
    memset(b, 0, sizeof *b);
    return ob_compute_pass_init(&b->pass, "second_back.glsl", NULL, sizeof(second_back_block));
}

ob_error ob_second_back_run(ob_second_back *b, GLuint front_depth, GLuint second_depth,
                            const ob_second_back_planes *planes)
{
    if (!b || !b->pass.program || !front_depth || !second_depth)
        return ob_set_error(OB_ERR_INVALID_ARGUMENT, "ob_second_back_run: no pass or no input");
    GLint w = 0, h = 0;
    glGetTextureLevelParameteriv(second_depth, 0, GL_TEXTURE_WIDTH, &w);
    glGetTextureLevelParameteriv(second_depth, 0, GL_TEXTURE_HEIGHT, &h);
    if (w <= 0 || h <= 0) return ob_set_error(OB_ERR_BAD_SIZE, "ob_second_back_run: second layer of %dx%d", w, h);
    if (!b->texture || b->width != w || b->height != h) {
        GLuint tex = ob_make_texture_2d(GL_R32F, w, h);
        GLenum e = ob_gl_error();
        if (e != GL_NO_ERROR) {
            glDeleteTextures(1, &tex);
            return ob_set_error(OB_ERR_GL, "OpenGL error 0x%x making the %dx%d second-layer back texture", e, w, h);
        }
        glDeleteTextures(1, &b->texture);
        b->texture = tex, b->width = w, b->height = h;
    }
    bool with_planes = planes && planes->front && planes->back;
    second_back_block block = {{w, h, with_planes, with_planes && planes->orthographic},
                               {0.0f, 0.0f, 0.0f, 0.0f},
                               {1.0f / (float)w, 1.0f / (float)h, 0.0f, 0.0f}};
    if (with_planes) memcpy(block.proj_info, planes->proj_info, sizeof block.proj_info);
    ob_compute_pass_use(&b->pass, &block, sizeof block);
    glBindTextureUnit(OB_UNIT_DEPTH, front_depth);
    glBindTextureUnit(OB_UNIT_SECOND_DEPTH, second_depth);
    /* Unbound planes read the depth itself: the shader does not read them then. */
    glBindTextureUnit(OB_UNIT_FACET_NORMAL, with_planes ? planes->front : front_depth);
    glBindTextureUnit(OB_UNIT_SECOND_PLANE, with_planes ? planes->back : front_depth);
    glBindImageTexture(OB_IMAGE_UNIT_OUT, b->texture, 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_R32F);
    ob_dispatch_2d(w, h, 8, 8);
    glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT | GL_SHADER_IMAGE_ACCESS_BARRIER_BIT);
    return OB_OK;
}

void ob_second_back_destroy(ob_second_back *b)
{
    if (!b) return;
    ob_compute_pass_destroy(&b->pass);
    glDeleteTextures(1, &b->texture);
    memset(b, 0, sizeof *b);
}

/* The shader's view_position, plane_depth and octahedral decoding, for the twin. */
typedef struct twin_camera {
    float proj_info[4], inv_size[2];
    int orthographic;
} twin_camera;

static void twin_view_position(const twin_camera *c, float px, float py, float d, float out[3])
{
    float ndc_x = px * c->inv_size[0] * 2.0f - 1.0f, ndc_y = py * c->inv_size[1] * 2.0f - 1.0f;
    float s = c->orthographic ? 1.0f : d;
    out[0] = (ndc_x + c->proj_info[2]) * s * c->proj_info[0];
    out[1] = (ndc_y + c->proj_info[3]) * s * c->proj_info[1];
    out[2] = -d;
}

static float twin_dot(const float a[3], const float b[3]) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }

static float twin_plane_depth(const twin_camera *c, float px, float py, const float q[3], const float m[3])
{
    float at_one[3], o[3] = {0.0f, 0.0f, 0.0f}, d[3], qo[3];
    twin_view_position(c, px, py, 1.0f, at_one);
    if (c->orthographic) {
        o[0] = at_one[0], o[1] = at_one[1];
        d[0] = 0.0f, d[1] = 0.0f, d[2] = -1.0f;
    } else {
        memcpy(d, at_one, sizeof d);
    }
    for (int k = 0; k < 3; ++k) qo[k] = q[k] - o[k];
    float den = twin_dot(d, m);
    return fabsf(den) > 1e-4f * sqrtf(twin_dot(d, d)) ? twin_dot(qo, m) / den : -1.0f;
}

static void twin_oct_decode(const float e[2], float n[3])
{
    n[0] = e[0], n[1] = e[1], n[2] = 1.0f - fabsf(e[0]) - fabsf(e[1]);
    if (n[2] < 0.0f) {
        float x = n[0], y = n[1];
        n[0] = (1.0f - fabsf(y)) * (x >= 0.0f ? 1.0f : -1.0f);
        n[1] = (1.0f - fabsf(x)) * (y >= 0.0f ? 1.0f : -1.0f);
    }
    float len = sqrtf(twin_dot(n, n));
    for (int k = 0; k < 3; ++k) n[k] /= len;
}

void ob_second_back_reference(const float *front, const float *second, int width, int height,
                              const ob_second_back_planes_data *planes, float *back)
{
    static const int step[4][2] = {{1, 0}, {-1, 0}, {0, 1}, {0, -1}};
    twin_camera cam = {{0}, {1.0f / (float)width, 1.0f / (float)height}, 0};
    if (planes) memcpy(cam.proj_info, planes->proj_info, sizeof cam.proj_info), cam.orthographic = planes->orthographic;
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x) {
            size_t i = (size_t)y * (size_t)width + (size_t)x;
            float z1 = front[i], z2 = second[i], deepest = z2;
            int sheet = z2 <= z1, open_behind = 0;
            if (z2 > 0.0f) {
                int with_planes = planes && !sheet;
                float cx = (float)x + 0.5f, cy = (float)y + 0.5f, f[3], b[3], n[3] = {0.0f, 0.0f, 1.0f}, m[3];
                twin_view_position(&cam, cx, cy, z1, f);
                twin_view_position(&cam, cx, cy, z2, b);
                memcpy(m, n, sizeof m);
                if (with_planes) {
                    twin_oct_decode(planes->front + 2 * i, n);
                    twin_oct_decode(planes->back + 2 * i, m);
                }
                for (int k = 0; k < 4; ++k) {
                    int qx = x + step[k][0], qy = y + step[k][1];
                    int inside = qx >= 0 && qy >= 0 && qx < width && qy < height;
                    size_t j = inside ? (size_t)qy * (size_t)width + (size_t)qx : 0;
                    float q1 = inside ? front[j] : 0.0f, q2 = inside ? second[j] : 0.0f;
                    if (q1 > 0.0f && q1 < z2) {
                        if (q2 > 0.0f) {
                            float edge = 0.5f * (z2 + q2);
                            deepest = edge > deepest ? edge : deepest;
                        } else {
                            open_behind = 1;
                        }
                    }
                    float seen = with_planes && q1 > 0.0f
                                     ? twin_plane_depth(&cam, (float)qx + 0.5f, (float)qy + 0.5f, f, n)
                                     : -1.0f;
                    int same_front = seen > 0.0f && fabsf(q1 - seen) <= 0.5f * fabsf(q1 - z1);
                    if (with_planes && !same_front) {
                        float edge = twin_plane_depth(&cam, cx + 0.5f * (float)step[k][0], cy + 0.5f * (float)step[k][1], b, m);
                        float cap = 2.0f * z2 - z1;
                        if (edge > 0.0f) {
                            edge = edge < cap ? edge : cap;
                            deepest = edge > deepest ? edge : deepest;
                        }
                    }
                }
            }
            back[i] = open_behind && !sheet ? -deepest : deepest;
        }
}
