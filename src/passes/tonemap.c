/* Tone mapping, SSDO thesis §5.5 steps 6-8: radiance scaled by exposure alpha / L_avg (eq. 2.2, the
 * factor the luminance pass left on the GPU) plus the bloom, Reinhard on the luminance (eq. 2.4,
 * or 2.3 without L_white), sRGB into RGBA8. With HDR off, exposure x radiance clamped to [0,1].
 * Shader: shaders/tonemap.glsl. */
#include <string.h>

#include "bloom_params.h"
#include "base/error.h"
#include "passes/passes.h"
#include "tonemap_params.h"

ob_error ob_tonemap_init(ob_tonemap_pass *t)
{
    return ob_compute_pass_init(&t->pass, "tonemap.glsl", NULL, sizeof(ob_tonemap_constants));
}

void ob_tonemap_run(ob_tonemap_pass *t, const ob_tonemap_inputs *in, const ob_hdr_settings *s, GLuint final_out)
{
    ob_tonemap_constants k;
    memset(&k, 0, sizeof k);
    k.size[0] = in->width;
    k.size[1] = in->height;
    if (in->bloom_width > 0 && in->bloom_height > 0) {
        k.bloom_uv_scale[0] = 1.0f / (float)(OB_BLOOM_FACTOR * in->bloom_width);
        k.bloom_uv_scale[1] = 1.0f / (float)(OB_BLOOM_FACTOR * in->bloom_height);
    }
    k.hdr_enabled = s->enabled ? 1 : 0;
    k.exposure = s->exposure;
    k.l_white = s->l_white;
    k.bloom_strength = s->enabled && in->bloom && s->bloom_strength > 0.0f ? s->bloom_strength : 0.0f;
    ob_compute_pass_use(&t->pass, &k, sizeof k);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, OB_BINDING_HDR_RESULT, in->result);
    glBindTextureUnit(OB_UNIT_TONEMAP_RADIANCE, in->radiance);
    glBindTextureUnit(OB_UNIT_TONEMAP_BLOOM, in->bloom);
    glBindImageTexture(OB_IMAGE_UNIT_OUT, final_out, 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA8);
    ob_dispatch_2d(in->width, in->height, OB_TONEMAP_GROUP_X, OB_TONEMAP_GROUP_Y);
}

void ob_tonemap_destroy(ob_tonemap_pass *t) { ob_compute_pass_destroy(&t->pass); }
