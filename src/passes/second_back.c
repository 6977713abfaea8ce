/* The second layer over each pixel's footprint: what a method reads as its samples' backs
 * (docs/methods.md, "The back over a pixel's footprint"). Shader and reasons:
 * shaders/second_back.glsl. */
#include <string.h>

#include "base/error.h"
#include "passes/passes.h"

ob_error ob_second_back_init(ob_second_back *b)
{
    if (!b) return ob_set_error(OB_ERR_INVALID_ARGUMENT, "ob_second_back_init: NULL");
    memset(b, 0, sizeof *b);
    return ob_compute_pass_init(&b->pass, "second_back.glsl", NULL, 4 * sizeof(GLint));
}

ob_error ob_second_back_run(ob_second_back *b, GLuint front_depth, GLuint second_depth)
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
    const GLint size[4] = {w, h, 0, 0};
    ob_compute_pass_use(&b->pass, size, sizeof size);
    glBindTextureUnit(OB_UNIT_DEPTH, front_depth);
    glBindTextureUnit(OB_UNIT_SECOND_DEPTH, second_depth);
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

void ob_second_back_reference(const float *front, const float *second, int width, int height, float *back)
{
    static const int step[4][2] = {{1, 0}, {-1, 0}, {0, 1}, {0, -1}};
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x) {
            size_t i = (size_t)y * (size_t)width + (size_t)x;
            float z2 = second[i], deepest = z2;
            int sheet = z2 <= front[i], open_behind = 0;
            for (int k = 0; z2 > 0.0f && k < 4; ++k) {
                int qx = x + step[k][0], qy = y + step[k][1];
                if (qx < 0 || qy < 0 || qx >= width || qy >= height) continue;
                size_t j = (size_t)qy * (size_t)width + (size_t)qx;
                if (!(front[j] > 0.0f && front[j] < z2)) continue;
                if (second[j] > 0.0f) {
                    float edge = 0.5f * (z2 + second[j]);
                    deepest = edge > deepest ? edge : deepest;
                } else {
                    open_behind = 1;
                }
            }
            back[i] = open_behind && !sheet ? -deepest : deepest;
        }
}
