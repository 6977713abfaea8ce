/* Packed samples for the methods whose samples read a sender's normal and direct radiance besides
 * the depth (ssdo, ssdo_merged, vbgi: their `packed` parameter): one pass that writes each AO
 * texel's depth, normal and radiance into one RGBA32UI texel, losslessly, so that a sample makes
 * one fetch instead of three. llvmpipe makes the senders' fetches for every sample, occluded or
 * not (a block its lanes all skip still runs, masked), and a fetch costs it about the same
 * whatever its size; a GPU skips them where a whole group is open and would read 16 bytes a
 * sample for 4, so the methods pack only on a software rasteriser by default. Shader:
 * shaders/sample_pack.glsl. */
#include "base/error.h"
#include "methods/method.h"

#define PACK_GROUP 8 /* shaders/sample_pack.glsl's OB_PACK_GROUP */

const char *const ob_packed_options[] = {"off", "on", "auto"};

bool ob_packed_samples_wanted(ob_packed_samples *p, float mode)
{
    if ((int)mode == OB_PACKED_ON) return true;
    if ((int)mode != OB_PACKED_AUTO) return false;
    if (!p->software) p->software = ob_renderer_is_software((const char *)glGetString(GL_RENDERER)) ? 1 : -1;
    return p->software > 0;
}

ob_error ob_packed_samples_run(ob_packed_samples *p, const ob_ao_inputs *in, int unit)
{
    if (!p->program) {
        p->program = ob_make_compute_program("sample_pack.glsl", NULL);
        if (!p->program) return ob_peek_error(NULL);
    }
    if (p->texture && (p->width != in->width || p->height != in->height)) {
        glDeleteTextures(1, &p->texture);
        p->texture = 0;
    }
    if (!p->texture) {
        p->texture = ob_make_texture_2d(GL_RGBA32UI, in->width, in->height);
        p->width = in->width;
        p->height = in->height;
    }
    glUseProgram(p->program);
    glBindTextureUnit(OB_UNIT_DEPTH, in->linear_depth);
    glBindTextureUnit(OB_UNIT_NORMAL, in->view_normal);
    glBindTextureUnit(OB_UNIT_RADIANCE, in->radiance);
    glBindImageTexture(OB_IMAGE_UNIT_PACKED, p->texture, 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA32UI);
    ob_dispatch_2d(in->width, in->height, PACK_GROUP, PACK_GROUP);
    glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT);
    glBindTextureUnit((GLuint)unit, p->texture);
    return OB_OK;
}

void ob_packed_samples_release(ob_packed_samples *p)
{
    if (p->program) glDeleteProgram(p->program);
    if (p->texture) glDeleteTextures(1, &p->texture);
    *p = (ob_packed_samples){.software = p->software};
}
