/* Depth and normals at the AO resolution (Belonogov 2018 §4.7.1, SSDO thesis §4.4, §6.3). Shader:
 * shaders/downsample.glsl. */
#include <string.h>

#include "passes/passes.h"
#include "resample_params.h"

ob_ao_grid ob_ao_grid_make(int full_width, int full_height, int k)
{
    ob_ao_grid g = {full_width, full_height, (full_width + k - 1) / k, (full_height + k - 1) / k, k, 0};
    /* A sub-pixel next to the block's centre: k = 2 -> 0, k = 4 -> 1. */
    g.o = k > 1 ? k / 2 - 1 : 0;
    return g;
}

void ob_resample_fill(ob_resample_constants *c, const ob_ao_grid *g)
{
    memset(c, 0, sizeof *c);
    c->full_size[0] = g->full_width;
    c->full_size[1] = g->full_height;
    c->ao_size[0] = g->width;
    c->ao_size[1] = g->height;
    c->ao_k = g->k;
    c->ao_o = g->o;
}

ob_error ob_downsample_init(ob_compute_pass *p)
{
    return ob_compute_pass_init(p, "downsample.glsl", NULL, sizeof(ob_resample_constants));
}

void ob_downsample_run(ob_compute_pass *p, const ob_ao_grid *g, GLuint full_depth, GLuint full_normal, GLuint low_depth,
                       GLuint low_normal)
{
    ob_resample_constants c;
    ob_resample_fill(&c, g);
    ob_compute_pass_use(p, &c, sizeof c);
    glBindTextureUnit(OB_UNIT_DEPTH, full_depth);
    glBindTextureUnit(OB_UNIT_NORMAL, full_normal);
    glBindImageTexture(OB_IMAGE_UNIT_OUT, low_depth, 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_R32F);
    glBindImageTexture(OB_IMAGE_UNIT_DOWNSAMPLE_NORMAL, low_normal, 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA16F);
    ob_dispatch_2d(g->width, g->height, OB_RESAMPLE_GROUP_X, OB_RESAMPLE_GROUP_Y);
}
