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

void ob_compose_run(ob_compose_pass *c, const ob_compose_inputs *in, GLuint hdr_out)
{
    ob_compose_constants k;
    memset(&k, 0, sizeof k);
    k.ao_all_light = in->ao_all_light ? 1 : 0;
    k.directional = in->directional ? 1 : 0;
    k.add_bounce = in->bounce ? 1 : 0;
    k.multibounce = in->multibounce ? 1 : 0;
    k.bent_normal = in->bent_normal ? 1 : 0;
    k.guard = in->guard;
    ob_compute_pass_use(&c->pass, &k, sizeof k);
    glBindTextureUnit(0, in->linear_depth);
    glBindTextureUnit(1, in->normal);
    glBindTextureUnit(2, in->albedo);
    glBindTextureUnit(3, in->ao);
    glBindTextureUnit(4, in->direct);
    /* Without an environment map the sampler is never read; bind a valid texture all the same. */
    glBindTextureUnit(5, in->environment ? in->environment : in->direct);
    glBindTextureUnit(6, in->bounce ? in->bounce : in->direct);
    glBindTextureUnit(7, in->bent_normal ? in->bent_normal : in->direct);
    glBindImageTexture(0, hdr_out, 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA16F);
    ob_dispatch_2d(in->width, in->height, OB_COMPOSE_GROUP_X, OB_COMPOSE_GROUP_Y);
}

void ob_compose_destroy(ob_compose_pass *c) { ob_compute_pass_destroy(&c->pass); }
