/* The classic 4x4 box blur after SSAO (seed 004 §3.3). Better filters arrive as passes of their
 * own (issue 4); this one stays as the baseline. */
#include <string.h>

#include "blur_params.h"
#include "core/error.h"
#include "passes/passes.h"

ob_error ob_blur_init(ob_blur_pass *b)
{
    memset(b, 0, sizeof *b);
    b->program = ob_make_compute_program("blur_box4.glsl", NULL);
    if (!b->program) return ob_get_error(NULL);
    glCreateBuffers(1, &b->ubo);
    glNamedBufferStorage(b->ubo, sizeof(ob_blur_constants), NULL, GL_DYNAMIC_STORAGE_BIT);
    return OB_OK;
}

void ob_blur_run(ob_blur_pass *b, GLuint ao_in, GLuint linear_depth, GLuint ao_out, int width, int height)
{
    ob_blur_constants c = {{(float)width, (float)height, 1.0f / (float)width, 1.0f / (float)height}};
    glNamedBufferSubData(b->ubo, 0, sizeof c, &c);
    glUseProgram(b->program);
    glBindBufferBase(GL_UNIFORM_BUFFER, OB_BINDING_PASS, b->ubo);
    glBindTextureUnit(0, ao_in);
    glBindTextureUnit(1, linear_depth);
    glBindImageTexture(0, ao_out, 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_R32F);
    ob_dispatch_2d(width, height, OB_BLUR_GROUP_X, OB_BLUR_GROUP_Y);
}

void ob_blur_destroy(ob_blur_pass *b)
{
    glDeleteProgram(b->program);
    glDeleteBuffers(1, &b->ubo);
    memset(b, 0, sizeof *b);
}
