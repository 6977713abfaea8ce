/* Compute-pass plumbing shared by every pass and method: program + constants, dispatch, textures. */
#include <string.h>

#include "base/error.h"
#include "gpu/gpu.h"
#include "ob_shared.h"
#include "sampling/sampling.h"

/* The host path saves and restores texture units 0..OB_HOST_TEXTURE_UNITS-1 and image units
 * 0..OB_HOST_IMAGE_UNITS-1 (obscura.h): a pass that bound one beyond them would change a host's
 * binding behind its back. ob_units.h counts the units the passes bind. */
_Static_assert(OB_TEXTURE_UNITS_USED <= OB_HOST_TEXTURE_UNITS,
               "a pass binds a texture unit beyond OB_HOST_TEXTURE_UNITS (shaders/ob_units.h, obscura.h)");
_Static_assert(OB_IMAGE_UNITS_USED <= OB_HOST_IMAGE_UNITS,
               "a pass binds an image unit beyond OB_HOST_IMAGE_UNITS (shaders/ob_units.h, obscura.h)");
_Static_assert(OB_IMAGE_UNIT_DEPTH_MIPS + OB_DEPTH_MIPS_LEVELS <= OB_IMAGE_UNITS_USED,
               "the depth MIP pass's images reach beyond OB_IMAGE_UNITS_USED (shaders/ob_units.h)");

ob_error ob_compute_pass_init(ob_compute_pass *p, const char *shader, const char *defines, size_t constants_size)
{
    memset(p, 0, sizeof *p);
    p->program = ob_make_compute_program(shader, defines);
    if (!p->program) return ob_peek_error(NULL);
    p->constants_size = constants_size;
    glCreateBuffers(1, &p->ubo);
    glNamedBufferStorage(p->ubo, (GLsizeiptr)constants_size, NULL, GL_DYNAMIC_STORAGE_BIT);
    return OB_OK;
}

void ob_compute_pass_use(ob_compute_pass *p, const void *constants, size_t size)
{
    glNamedBufferSubData(p->ubo, 0, (GLsizeiptr)(size < p->constants_size ? size : p->constants_size), constants);
    glUseProgram(p->program);
    glBindBufferBase(GL_UNIFORM_BUFFER, OB_BINDING_PASS, p->ubo);
}

void ob_compute_pass_destroy(ob_compute_pass *p)
{
    if (p->program) glDeleteProgram(p->program);
    if (p->ubo) glDeleteBuffers(1, &p->ubo);
    memset(p, 0, sizeof *p);
}

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

GLuint ob_make_rotation_noise_texture(void)
{
    float noise[16 * 2] = {0};
    ob_rotation_noise_4x4(noise, 0x4E01u);
    GLuint tex = ob_make_texture_2d(GL_RG32F, 4, 4);
    glTextureSubImage2D(tex, 0, 0, 0, 4, 4, GL_RG, GL_FLOAT, noise);
    return tex;
}
