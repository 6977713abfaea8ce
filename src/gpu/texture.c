/* Small GL helpers shared by the passes. */
#include "gpu/gpu.h"

void ob_dispatch_2d(int w, int h, int gx, int gy)
{
    glDispatchCompute((GLuint)((w + gx - 1) / gx), (GLuint)((h + gy - 1) / gy), 1);
}

GLuint ob_make_texture_2d(GLenum internal_format, int w, int h)
{
    GLuint tex = 0;
    glCreateTextures(GL_TEXTURE_2D, 1, &tex);
    glTextureStorage2D(tex, 1, internal_format, w, h);
    glTextureParameteri(tex, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    glTextureParameteri(tex, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    glTextureParameteri(tex, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    glTextureParameteri(tex, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    return tex;
}
