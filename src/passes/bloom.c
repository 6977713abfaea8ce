/* Bloom, SSDO thesis §5.5 steps 2-4: the bright pass keeps each pixel's excess over a threshold in
 * scaled luminance (eq. 2.2 units, the units of L_white) at 1/OB_BLOOM_FACTOR resolution, then a
 * separable Gaussian (Belonogov 2018 eq. 4.4, x then y) spreads it. The tone-map pass adds it back.
 * Shader: shaders/bloom.glsl (two programs: the bright pass and one blur direction). */
#include <math.h>
#include <string.h>

#include "bloom_params.h"
#include "base/error.h"
#include "passes/passes.h"

static void fill_weights(ob_bloom_constants *k)
{
    /* Eq. 4.4 truncated at 2 sigma and renormalised over the taps used, so the blur keeps the
     * bright pass's energy: bloom_strength alone decides how much light is added. */
    const float sigma = 0.5f * (float)OB_BLOOM_RADIUS;
    float sum = 0.0f;
    for (int i = 0; i <= OB_BLOOM_RADIUS; ++i) {
        float w = expf(-(float)(i * i) / (2.0f * sigma * sigma));
        k->weights[i][0] = w;
        sum += i == 0 ? w : 2.0f * w;
    }
    for (int i = 0; i <= OB_BLOOM_RADIUS; ++i) k->weights[i][0] /= sum;
}

static void make_targets(int bloom_width, int bloom_height, GLuint *bloom, GLuint *scratch)
{
    *bloom = ob_make_texture_2d(GL_RGBA16F, bloom_width, bloom_height);
    *scratch = ob_make_texture_2d(GL_RGBA16F, bloom_width, bloom_height);
    /* The tone-map pass upsamples `bloom` with one bilinear fetch (§5.5 step 6). */
    glTextureParameteri(*bloom, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
    glTextureParameteri(*bloom, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
}

ob_error ob_bloom_init(ob_bloom_pass *b, int width, int height)
{
    memset(b, 0, sizeof *b);
    b->width = width;
    b->height = height;
    b->bloom_width = (width + OB_BLOOM_FACTOR - 1) / OB_BLOOM_FACTOR;
    b->bloom_height = (height + OB_BLOOM_FACTOR - 1) / OB_BLOOM_FACTOR;
    if (ob_compute_pass_init(&b->bright, "bloom.glsl", "#define OB_BLOOM_BRIGHT 1\n", sizeof(ob_bloom_constants)) !=
            OB_OK ||
        ob_compute_pass_init(&b->blur, "bloom.glsl", NULL, sizeof(ob_bloom_constants)) != OB_OK) {
        ob_error err = ob_peek_error(NULL);
        ob_bloom_destroy(b);
        return err;
    }
    make_targets(b->bloom_width, b->bloom_height, &b->bloom, &b->scratch);
    return OB_OK;
}

ob_error ob_bloom_resize(ob_bloom_pass *b, int width, int height)
{
    int bw = (width + OB_BLOOM_FACTOR - 1) / OB_BLOOM_FACTOR, bh = (height + OB_BLOOM_FACTOR - 1) / OB_BLOOM_FACTOR;
    GLuint made[2] = {0, 0};
    make_targets(bw, bh, &made[0], &made[1]);
    GLenum e = glGetError();
    if (e != GL_NO_ERROR) {
        glDeleteTextures(2, made);
        return ob_set_error(OB_ERR_GL, "OpenGL error 0x%x making the %dx%d bloom targets", e, bw, bh);
    }
    GLuint old[2] = {b->bloom, b->scratch};
    glDeleteTextures(2, old);
    b->bloom = made[0];
    b->scratch = made[1];
    b->width = width;
    b->height = height;
    b->bloom_width = bw;
    b->bloom_height = bh;
    return OB_OK;
}

void ob_bloom_run(ob_bloom_pass *b, GLuint radiance, GLuint result, float threshold)
{
    ob_bloom_constants k;
    memset(&k, 0, sizeof k);
    k.full_size[0] = b->width;
    k.full_size[1] = b->height;
    k.bloom_size[0] = b->bloom_width;
    k.bloom_size[1] = b->bloom_height;
    k.radius = OB_BLOOM_RADIUS;
    k.threshold = threshold > 0.0f ? threshold : 0.0f;
    fill_weights(&k);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, OB_BINDING_HDR_RESULT, result);

    /* Steps 2-3: radiance -> bloom (the scale comes from the luminance pass's buffer). */
    ob_compute_pass_use(&b->bright, &k, sizeof k);
    glBindTextureUnit(OB_UNIT_SOURCE, radiance);
    glBindImageTexture(OB_IMAGE_UNIT_OUT, b->bloom, 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA16F);
    ob_dispatch_2d(b->bloom_width, b->bloom_height, OB_BLOOM_GROUP_X, OB_BLOOM_GROUP_Y);
    glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT | GL_SHADER_IMAGE_ACCESS_BARRIER_BIT);

    /* Step 4 along x: bloom -> scratch. */
    k.axis_x = 1;
    k.axis_y = 0;
    ob_compute_pass_use(&b->blur, &k, sizeof k);
    glBindTextureUnit(OB_UNIT_SOURCE, b->bloom);
    glBindImageTexture(OB_IMAGE_UNIT_OUT, b->scratch, 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA16F);
    ob_dispatch_2d(b->bloom_width, b->bloom_height, OB_BLOOM_GROUP_X, OB_BLOOM_GROUP_Y);
    glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT | GL_SHADER_IMAGE_ACCESS_BARRIER_BIT);

    /* Along y: scratch -> bloom. Re-uploading the block between dispatches is ordered by GL, so
     * the x pass still sees (1,0). */
    k.axis_x = 0;
    k.axis_y = 1;
    ob_compute_pass_use(&b->blur, &k, sizeof k);
    glBindTextureUnit(OB_UNIT_SOURCE, b->scratch);
    glBindImageTexture(OB_IMAGE_UNIT_OUT, b->bloom, 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA16F);
    ob_dispatch_2d(b->bloom_width, b->bloom_height, OB_BLOOM_GROUP_X, OB_BLOOM_GROUP_Y);
}

void ob_bloom_destroy(ob_bloom_pass *b)
{
    ob_compute_pass_destroy(&b->bright);
    ob_compute_pass_destroy(&b->blur);
    GLuint tex[2] = {b->bloom, b->scratch};
    glDeleteTextures(2, tex);
    memset(b, 0, sizeof *b);
}
