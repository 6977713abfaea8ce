/* The host path's input and output passes (passes.h; shaders/host_input.glsl, host_output.glsl):
 * what stands between an engine's own textures and the AO chain, which reads R32F linear depth and
 * RGBA16F view normals and writes R32F / RGBA16F at the enlarged size. */
#include <stdio.h>
#include <string.h>

#include "base/error.h"
#include "passes/passes.h"

static const struct {
    GLenum format;
    const char *qualifier;
} output_formats[OB_HOST_OUTPUT_FORMATS] = {
    {GL_R8, "r8"},           {GL_R16F, "r16f"},       {GL_R32F, "r32f"},
    {GL_RGBA8, "rgba8"},     {GL_RGBA16F, "rgba16f"}, {GL_RGBA32F, "rgba32f"},
    {GL_R11F_G11F_B10F, "r11f_g11f_b10f"},
};

int ob_host_output_format_index(GLenum internal_format)
{
    for (int i = 0; i < OB_HOST_OUTPUT_FORMATS; ++i)
        if (output_formats[i].format == internal_format) return i;
    return -1;
}

static ob_error make_sampler(ob_host_passes *h)
{
    if (h->sampler) return OB_OK;
    glCreateSamplers(1, &h->sampler);
    glSamplerParameteri(h->sampler, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    glSamplerParameteri(h->sampler, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    glSamplerParameteri(h->sampler, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    glSamplerParameteri(h->sampler, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    glSamplerParameteri(h->sampler, GL_TEXTURE_COMPARE_MODE, GL_NONE);
    return h->sampler ? OB_OK : ob_set_error(OB_ERR_OUT_OF_MEMORY, "the GL made no sampler object");
}

static ob_compute_pass *input_pass(ob_host_passes *h, const ob_host_input_variant *v)
{
    return &h->input[v->depth_kind != 0][v->normal_encoding][v->second];
}

ob_error ob_host_input_prepare(ob_host_passes *h, const ob_host_input_variant *v)
{
    if (make_sampler(h) != OB_OK) return ob_peek_error(NULL);
    ob_compute_pass *p = input_pass(h, v);
    if (p->program) return OB_OK;
    char defines[160];
    snprintf(defines, sizeof defines,
             "#define OB_HOST_DEPTH_KIND %d\n#define OB_HOST_NORMAL_ENCODING %d\n#define OB_HOST_SECOND %d\n",
             v->depth_kind, v->normal_encoding, v->second ? 1 : 0);
    return ob_compute_pass_init(p, "host_input.glsl", defines, sizeof(ob_host_input_constants));
}

ob_error ob_host_output_prepare(ob_host_passes *h, GLenum format)
{
    int i = ob_host_output_format_index(format);
    if (i < 0) return ob_set_error(OB_ERR_INVALID_ARGUMENT, "the output pass writes no format 0x%x", format);
    if (make_sampler(h) != OB_OK) return ob_peek_error(NULL);
    if (h->output[i].program) return OB_OK;
    char defines[64];
    snprintf(defines, sizeof defines, "#define OB_HOST_OUT_FORMAT %s\n", output_formats[i].qualifier);
    return ob_compute_pass_init(&h->output[i], "host_output.glsl", defines, sizeof(ob_host_output_constants));
}

GLuint ob_host_second_target(ob_host_passes *h, int width, int height)
{
    if (h->second && (h->second_width != width || h->second_height != height)) {
        glDeleteTextures(1, &h->second);
        h->second = 0;
    }
    if (!h->second) {
        h->second = ob_make_texture_2d(GL_R32F, width, height);
        h->second_width = width;
        h->second_height = height;
    }
    return h->second;
}

ob_error ob_host_input_run(ob_host_passes *h, const ob_host_input_variant *v, const ob_host_input_constants *c,
                           GLuint depth, GLuint normal, GLuint second, GLuint out_depth, GLuint out_normal,
                           GLuint out_second)
{
    if (ob_host_input_prepare(h, v) != OB_OK) return ob_peek_error(NULL);
    ob_compute_pass_use(input_pass(h, v), c, sizeof *c);
    /* Units without a host texture get the output depth (bound, never read): a unit bound to 0
     * would unbind the host's textures of every target there. */
    const GLuint units[3] = {OB_UNIT_HOST_DEPTH, OB_UNIT_HOST_NORMAL, OB_UNIT_HOST_SECOND_DEPTH};
    const GLuint textures[3] = {depth, normal ? normal : depth, second ? second : depth};
    for (int i = 0; i < 3; ++i) {
        glBindTextureUnit(units[i], textures[i]);
        glBindSampler(units[i], h->sampler);
    }
    glBindImageTexture(OB_IMAGE_UNIT_HOST_DEPTH, out_depth, 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_R32F);
    glBindImageTexture(OB_IMAGE_UNIT_HOST_NORMAL, out_normal, 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA16F);
    glBindImageTexture(OB_IMAGE_UNIT_HOST_SECOND_DEPTH, out_second ? out_second : out_depth, 0, GL_FALSE, 0,
                       GL_WRITE_ONLY, GL_R32F);
    ob_dispatch_2d(c->size[0], c->size[1], OB_HOST_GROUP_X, OB_HOST_GROUP_Y);
    for (int i = 0; i < 3; ++i) glBindSampler(units[i], 0);
    return OB_OK;
}

ob_error ob_host_output_run(ob_host_passes *h, const ob_host_output_constants *c, GLuint source, GLuint target,
                            GLenum format)
{
    if (ob_host_output_prepare(h, format) != OB_OK) return ob_peek_error(NULL);
    ob_compute_pass *p = &h->output[ob_host_output_format_index(format)];
    ob_compute_pass_use(p, c, sizeof *c);
    glBindTextureUnit(OB_UNIT_SOURCE, source);
    glBindImageTexture(OB_IMAGE_UNIT_OUT, target, 0, GL_FALSE, 0, GL_WRITE_ONLY, format);
    ob_dispatch_2d(c->size[0], c->size[1], OB_HOST_GROUP_X, OB_HOST_GROUP_Y);
    return OB_OK;
}

void ob_host_passes_destroy(ob_host_passes *h)
{
    for (int k = 0; k < 2; ++k)
        for (int e = 0; e < OB_HOST_NORMAL_ENCODINGS; ++e)
            for (int s = 0; s < 2; ++s) ob_compute_pass_destroy(&h->input[k][e][s]);
    for (int i = 0; i < OB_HOST_OUTPUT_FORMATS; ++i) ob_compute_pass_destroy(&h->output[i]);
    if (h->sampler) glDeleteSamplers(1, &h->sampler);
    if (h->second) glDeleteTextures(1, &h->second);
    memset(h, 0, sizeof *h);
}
