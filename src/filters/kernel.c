/* What the Gaussian-family filters share (gaussian, bilateral, bilateral_sep, geometry): the
 * spatial kernel of Belonogov 2018 eq. 4.4, the range falloffs of eq. 4.5-4.7 / SSDO thesis §3.5, and the
 * two-dispatch driver of a separable pass (Belonogov 2018 eq. 4.6-4.7; SSDO thesis §4.3). Keeping them in
 * one place means bilateral and bilateral_sep weigh taps identically, so their RMSE difference
 * measures the separable approximation and nothing else. */
#include <math.h>
#include <stddef.h>
#include <stdlib.h>
#include <string.h>

#include "base/error.h"
#include "filters/filter.h"

void ob_filter_constants_init(ob_filter_constants *c, const ob_filter_inputs *in, int radius, float sigma_px,
                              float sigma_depth, float sigma_normal)
{
    memset(c, 0, sizeof *c);
    c->size[0] = in->width;
    c->size[1] = in->height;
    if (radius < 0) radius = 0;
    if (radius > OB_FILTER_MAX_RADIUS) radius = OB_FILTER_MAX_RADIUS;
    c->radius = radius;
    /* falloff = -1/(2 sigma^2): the shaders evaluate a range Gaussian as exp(x^2 * falloff), and
     * a product of two as one exp() of the sum. 0 turns a term into a constant 1. */
    c->depth_falloff = sigma_depth > 0.0f ? -1.0f / (2.0f * sigma_depth * sigma_depth) : 0.0f;
    c->normal_falloff = sigma_normal > 0.0f ? -1.0f / (2.0f * sigma_normal * sigma_normal) : 0.0f;
    c->sky_value = in->sky; /* read by the RGB variant only (filter_params.h) */

    /* Eq. 4.4 at x = 0..radius with mu = 0. The 1/(sigma sqrt(2 pi)) factor is replaced by the sum
     * over the taps actually used, so a kernel truncated at 2 sigma still keeps the AO's mean
     * (the plain Gaussian relies on that; the bilateral ones renormalise anyway). */
    float s = sigma_px > 1e-3f ? sigma_px : 1e-3f;
    float sum = 0.0f;
    for (int i = 0; i <= radius; ++i) {
        float w = expf(-(float)(i * i) / (2.0f * s * s));
        c->weights[i][0] = w;
        sum += i == 0 ? w : 2.0f * w;
    }
    for (int i = 0; i <= radius; ++i) c->weights[i][0] /= sum;
}

size_t ob_filter_constants_used(const ob_filter_constants *c)
{
    return offsetof(ob_filter_constants, weights) + (size_t)(c->radius + 1) * sizeof c->weights[0];
}

void ob_filter_run_separable(ob_compute_pass *pass, ob_filter_constants *c, const ob_filter_inputs *in)
{
    size_t used = ob_filter_constants_used(c);
    glBindTextureUnit(OB_UNIT_FILTER_DEPTH, in->linear_depth);
    glBindTextureUnit(OB_UNIT_FILTER_NORMAL, in->view_normal);

    /* eq. 4.6: along x, src -> scratch. */
    c->axis[0] = 1;
    c->axis[1] = 0;
    ob_compute_pass_use(pass, c, used);
    glBindTextureUnit(OB_UNIT_FILTER_IN, in->src);
    glBindImageTexture(OB_IMAGE_UNIT_OUT, in->scratch, 0, GL_FALSE, 0, GL_WRITE_ONLY, ob_filter_format(in));
    ob_dispatch_2d(in->width, in->height, OB_FILTER_GROUP_X, OB_FILTER_GROUP_Y);

    /* The y pass samples what the x pass stored with imageStore. */
    glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT | GL_SHADER_IMAGE_ACCESS_BARRIER_BIT);

    /* eq. 4.7: along y, scratch -> dst. Re-uploading the small block between the dispatches is
     * ordered by GL like any other buffer update, so the x pass still sees (1,0). */
    c->axis[0] = 0;
    c->axis[1] = 1;
    ob_compute_pass_use(pass, c, used);
    glBindTextureUnit(OB_UNIT_FILTER_IN, in->scratch);
    glBindImageTexture(OB_IMAGE_UNIT_OUT, in->dst, 0, GL_FALSE, 0, GL_WRITE_ONLY, ob_filter_format(in));
    ob_dispatch_2d(in->width, in->height, OB_FILTER_GROUP_X, OB_FILTER_GROUP_Y);
}

void ob_filter_run_single(ob_compute_pass *pass, const ob_filter_constants *c, size_t used, const ob_filter_inputs *in)
{
    ob_filter_run_blocks(pass, c, used, in, 1);
}

void ob_filter_run_blocks(ob_compute_pass *pass, const ob_filter_constants *c, size_t used, const ob_filter_inputs *in,
                          int block)
{
    ob_compute_pass_use(pass, c, used);
    glBindTextureUnit(OB_UNIT_FILTER_IN, in->src);
    glBindTextureUnit(OB_UNIT_FILTER_DEPTH, in->linear_depth);
    glBindTextureUnit(OB_UNIT_FILTER_NORMAL, in->view_normal);
    glBindImageTexture(OB_IMAGE_UNIT_OUT, in->dst, 0, GL_FALSE, 0, GL_WRITE_ONLY, ob_filter_format(in));
    ob_dispatch_2d((in->width + block - 1) / block, (in->height + block - 1) / block, OB_FILTER_GROUP_X,
                   OB_FILTER_GROUP_Y);
}

void ob_filter_destroy_pass(void *state)
{
    if (!state) return;
    ob_compute_pass_destroy(state);
    free(state);
}

void *ob_filter_make_pass(const char *shader, bool rgb)
{
    ob_compute_pass *p = calloc(1, sizeof *p);
    if (!p) {
        ob_set_error(OB_ERR_OUT_OF_MEMORY, "out of memory (%s)", shader);
        return NULL;
    }
    if (ob_compute_pass_init(p, shader, rgb ? "#define OB_FILTER_RGB 1\n" : NULL, sizeof(ob_filter_constants)) != OB_OK) {
        free(p);
        return NULL;
    }
    return p;
}
