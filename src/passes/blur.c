/* The classic 4x4 box blur after SSAO (seed 004 §3.3). Better filters arrive as passes of their
 * own (issue 4); this one stays as the baseline. */
#include "blur_params.h"
#include "core/error.h"
#include "passes/passes.h"

ob_error ob_blur_init(ob_blur_pass *b)
{
    return ob_compute_pass_init(&b->pass, "blur_box4.glsl", NULL, sizeof(ob_blur_constants));
}

void ob_blur_run(ob_blur_pass *b, GLuint ao_in, GLuint linear_depth, GLuint ao_out, int width, int height)
{
    ob_blur_constants c = {{(float)width, (float)height, 1.0f / (float)width, 1.0f / (float)height}};
    ob_compute_pass_use(&b->pass, &c, sizeof c);
    glBindTextureUnit(0, ao_in);
    glBindTextureUnit(1, linear_depth);
    glBindImageTexture(0, ao_out, 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_R32F);
    ob_dispatch_2d(width, height, OB_BLUR_GROUP_X, OB_BLUR_GROUP_Y);
}

void ob_blur_destroy(ob_blur_pass *b) { ob_compute_pass_destroy(&b->pass); }
