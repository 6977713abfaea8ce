/* One value into a whole target, as a compute pass (shaders/fill.glsl says why not
 * glClearTexImage). The size is the texture's own, so a target with a guard band is filled
 * whole, as a clear would. */
#include "passes/passes.h"

ob_error ob_fill_init(ob_compute_pass *p, bool rgb)
{
    return ob_compute_pass_init(p, "fill.glsl", rgb ? "#define OB_FILL_RGB 1\n" : NULL, 4 * sizeof(float));
}

void ob_fill_run(ob_compute_pass *p, bool rgb, GLuint target, const float value[4])
{
    GLint w = 0, h = 0;
    glGetTextureLevelParameteriv(target, 0, GL_TEXTURE_WIDTH, &w);
    glGetTextureLevelParameteriv(target, 0, GL_TEXTURE_HEIGHT, &h);
    ob_compute_pass_use(p, value, 4 * sizeof(float));
    glBindImageTexture(OB_IMAGE_UNIT_OUT, target, 0, GL_FALSE, 0, GL_WRITE_ONLY, rgb ? GL_RGBA16F : GL_R32F);
    ob_dispatch_2d(w, h, 8, 8);
}
