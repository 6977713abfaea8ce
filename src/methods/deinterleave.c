/* Where a random-kernel method's taps read depth (shaders/taps.glsl): the plain program, the
 * deinterleaved one or the depth MIP chain's (ob_taps_prepare).
 *
 * Deinterleaved sampling (issue 18; Bavoil 2014, "Deinterleaved Texturing for Cache-Efficient
 * Interleaved Sampling"), the `deinterleave` parameter of the random-kernel methods: one pass
 * splits the AO grid's depth into the 16 classes of the 4x4 noise tile, one layer each
 * (shaders/deinterleave.glsl), and the method's OB_DEINTERLEAVED program runs class by class, its
 * taps reading the nearest pixel of their class (shaders/taps.glsl). Neighbouring
 * invocations then share one rotation and read neighbouring texels, which is what a GPU's texture
 * cache gains at large radii (NVIDIA measured 2.86x on HBAO's pass at 1080p); llvmpipe's
 * rasteriser gains nothing from it (docs/methods.md). The method writes its AO pixel where it is,
 * so no pass interleaves the result back. */
#include "base/error.h"
#include "methods/method.h"

#define SPLIT_GROUP 8 /* shaders/deinterleave.glsl's OB_DEINTERLEAVE_GROUP */

const char *const ob_deinterleave_options[] = {"off", "on"};

ob_error ob_deinterleaved_prepare(ob_deinterleaved *d, const char *shader, const ob_ao_inputs *in)
{
    if (!d->split) {
        d->split = ob_make_compute_program("deinterleave.glsl", NULL);
        if (!d->split) return ob_peek_error(NULL);
    }
    if (shader && !ob_method_variant(&d->program, shader, OB_DEINTERLEAVED_DEFINE)) return ob_peek_error(NULL);
    if (d->layers && (d->width != in->width || d->height != in->height)) {
        glDeleteTextures(1, &d->layers);
        d->layers = 0;
    }
    if (!d->layers) {
        glCreateTextures(GL_TEXTURE_2D_ARRAY, 1, &d->layers);
        glTextureStorage3D(d->layers, 1, GL_R32F, (in->width + 3) / 4, (in->height + 3) / 4, 16);
        glTextureParameteri(d->layers, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
        glTextureParameteri(d->layers, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
        glTextureParameteri(d->layers, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
        glTextureParameteri(d->layers, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
        d->width = in->width;
        d->height = in->height;
    }
    glUseProgram(d->split);
    glBindTextureUnit(OB_UNIT_DEPTH, in->linear_depth);
    /* Layered: every layer of level 0 is the one image. */
    glBindImageTexture(OB_IMAGE_UNIT_OUT, d->layers, 0, GL_TRUE, 0, GL_WRITE_ONLY, GL_R32F);
    ob_dispatch_2d((in->width + 3) / 4 * 4, (in->height + 3) / 4 * 4, SPLIT_GROUP, SPLIT_GROUP);
    glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT);
    glBindTextureUnit(OB_UNIT_DEPTH_LAYERS, d->layers);
    return OB_OK;
}

void ob_method_dispatch(GLuint program, bool deinterleaved, const ob_ao_inputs *in, int gx, int gy)
{
    if (program) glUseProgram(program);
    if (!deinterleaved) {
        ob_dispatch_2d(in->width, in->height, gx, gy);
        return;
    }
    const int w = (in->width + 3) / 4, h = (in->height + 3) / 4;
    glDispatchCompute((GLuint)((w + gx - 1) / gx), (GLuint)((h + gy - 1) / gy), 16);
}

void ob_deinterleaved_release(ob_deinterleaved *d)
{
    if (d->split) glDeleteProgram(d->split);
    if (d->program) glDeleteProgram(d->program);
    if (d->layers) glDeleteTextures(1, &d->layers);
    *d = (ob_deinterleaved){0};
}

ob_error ob_taps_exclusive(const char *method, bool deinterleave, bool depth_mips)
{
    if (deinterleave && depth_mips)
        return ob_set_error(OB_ERR_INVALID_ARGUMENT,
                            "%s: deinterleave and depth_mips cannot both be on (two ways to read a far tap)", method);
    return OB_OK;
}

void ob_taps_bind_mips(const ob_ao_inputs *in)
{
    glBindTextureUnit(OB_UNIT_TAPS_DEPTH_MIPS, in->depth_mips ? in->depth_mips : in->linear_depth);
}

ob_error ob_taps_prepare(ob_taps *t, const char *method, const char *shader, const ob_ao_inputs *in, bool deinterleave,
                         bool depth_mips)
{
    if (ob_taps_exclusive(method, deinterleave, depth_mips) != OB_OK) return ob_peek_error(NULL);
    t->program = 0;
    t->deinterleaved = deinterleave;
    if (deinterleave) {
        if (ob_deinterleaved_prepare(&t->split, shader, in) != OB_OK) return ob_peek_error(NULL);
        t->program = t->split.program;
    } else if (depth_mips) {
        if (!ob_method_variant(&t->mips, shader, "#define OB_TAPS_DEPTH_MIPS 1\n")) return ob_peek_error(NULL);
        t->program = t->mips;
        ob_taps_bind_mips(in);
    }
    return OB_OK;
}

void ob_taps_dispatch(const ob_taps *t, const ob_ao_inputs *in, int gx, int gy)
{
    ob_method_dispatch(t->program, t->deinterleaved, in, gx, gy);
}

uint32_t ob_taps_reads(float depth_mips) { return depth_mips != 0.0f ? ~0u : ~(uint32_t)OB_READS_DEPTH_MIPS; }

void ob_taps_release(ob_taps *t)
{
    ob_deinterleaved_release(&t->split);
    if (t->mips) glDeleteProgram(t->mips);
    *t = (ob_taps){0};
}
