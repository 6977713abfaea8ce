/* Compose: direct light + ambient x AO (or SSDO's direct x M + bounce) into HDR radiance (DESIGN.md "The frame"). Shader:
 * shaders/compose.glsl. */
#include <string.h>

#include "compose_params.h"
#include "core/error.h"
#include "passes/passes.h"

ob_error ob_compose_init(ob_compose_pass *c)
{
    return ob_compute_pass_init(&c->pass, "compose.glsl", NULL, sizeof(ob_compose_constants));
}

static void put3(float *dst, const float *src, float w)
{
    dst[0] = src[0];
    dst[1] = src[1];
    dst[2] = src[2];
    dst[3] = w;
}

void ob_compose_run(ob_compose_pass *c, const ob_compose_inputs *in, GLuint hdr_out)
{
    ob_compose_constants k;
    memset(&k, 0, sizeof k);
    k.size[0] = (float)in->width;
    k.size[1] = (float)in->height;
    k.size[2] = 1.0f / (float)in->width;
    k.size[3] = 1.0f / (float)in->height;
    memcpy(k.proj_info, in->proj_info, sizeof k.proj_info);
    memcpy(k.inv_view, in->inv_view, sizeof k.inv_view);
    put3(k.ambient, in->ambient, (float)in->ambient_mode);
    put3(k.sky, in->sky, 0.0f);
    put3(k.ground, in->ground, 0.0f);
    put3(k.background, in->background, 0.0f);
    for (int i = 0; i < 9; ++i) put3(k.sh[i], in->sh[i], 0.0f);
    k.flags[0] = in->ao_all_light ? 1 : 0;
    k.flags[1] = in->directional ? 1 : 0;
    k.flags[2] = in->directional && in->bounce ? 1 : 0;
    ob_compute_pass_use(&c->pass, &k, sizeof k);
    glBindTextureUnit(0, in->linear_depth);
    glBindTextureUnit(1, in->normal);
    glBindTextureUnit(2, in->albedo);
    glBindTextureUnit(3, in->ao);
    glBindTextureUnit(4, in->direct);
    /* Without an environment map the sampler is never read; bind a valid texture all the same. */
    glBindTextureUnit(5, in->environment ? in->environment : in->direct);
    glBindTextureUnit(6, in->bounce ? in->bounce : in->direct);
    glBindImageTexture(0, hdr_out, 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA16F);
    ob_dispatch_2d(in->width, in->height, OB_COMPOSE_GROUP_X, OB_COMPOSE_GROUP_Y);
}

void ob_compose_destroy(ob_compose_pass *c) { ob_compute_pass_destroy(&c->pass); }
