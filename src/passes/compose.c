/* Compose: direct light + ambient x AO (or SSDO's direct x M + bounce) into HDR radiance (docs/architecture.md "The frame"). Shader:
 * shaders/compose.glsl. */
#include <stdio.h>
#include <string.h>

#include "compose_params.h"
#include "base/error.h"
#include "passes/passes.h"

ob_error ob_compose_init(ob_compose_pass *c)
{
    memset(c, 0, sizeof *c);
    return ob_compute_pass_init(&c->variants[0], "compose.glsl", NULL, sizeof(ob_compose_constants));
}

ob_error ob_compose_run(ob_compose_pass *c, const ob_compose_inputs *in, GLuint hdr_out)
{
    /* The frame's choices are the program's (compose.glsl): llvmpipe runs every uniform branch for
     * every pixel, so a program carries only its own terms. */
    const int mode = in->ambient_mode == OB_AMBIENT_MODE_HEMISPHERE     ? 1
                     : in->ambient_mode == OB_AMBIENT_MODE_ENVIRONMENT ? 2
                                                                       : 0;
    const int bits = (in->directional ? 1 : 0) | (in->bounce ? 2 : 0) | (in->bent_normal ? 4 : 0) |
                     (in->multibounce ? 8 : 0) | (in->ao_all_light ? 16 : 0);
    ob_compute_pass *p = &c->variants[mode + 3 * bits];
    if (!p->program) {
        char defines[320];
        snprintf(defines, sizeof defines, "#define OB_COMPOSE_AMBIENT %d\n%s%s%s%s%s", mode,
                 in->directional ? "#define OB_COMPOSE_DIRECTIONAL 1\n" : "", in->bounce ? "#define OB_COMPOSE_BOUNCE 1\n" : "",
                 in->bent_normal ? "#define OB_COMPOSE_BENT 1\n" : "",
                 in->multibounce ? "#define OB_COMPOSE_MULTIBOUNCE 1\n" : "",
                 in->ao_all_light ? "#define OB_COMPOSE_ALL_LIGHT 1\n" : "");
        if (ob_compute_pass_init(p, "compose.glsl", defines, sizeof(ob_compose_constants)) != OB_OK)
            return ob_peek_error(NULL);
    }
    ob_compose_constants k;
    memset(&k, 0, sizeof k);
    k.guard = in->guard;
    ob_compute_pass_use(p, &k, sizeof k);
    glBindTextureUnit(OB_UNIT_DEPTH, in->linear_depth);
    glBindTextureUnit(OB_UNIT_NORMAL, in->normal);
    glBindTextureUnit(OB_UNIT_ALBEDO, in->albedo);
    glBindTextureUnit(OB_UNIT_COMPOSE_AO, in->ao);
    glBindTextureUnit(OB_UNIT_COMPOSE_DIRECT, in->direct);
    /* Without an environment map the sampler is never read; bind a valid texture all the same. */
    glBindTextureUnit(OB_UNIT_COMPOSE_ENVIRONMENT, in->environment ? in->environment : in->direct);
    glBindTextureUnit(OB_UNIT_COMPOSE_BOUNCE, in->bounce ? in->bounce : in->direct);
    glBindTextureUnit(OB_UNIT_COMPOSE_BENT_NORMAL, in->bent_normal ? in->bent_normal : in->direct);
    glBindImageTexture(OB_IMAGE_UNIT_OUT, hdr_out, 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA16F);
    ob_dispatch_2d(in->width, in->height, OB_COMPOSE_GROUP_X, OB_COMPOSE_GROUP_Y);
    return OB_OK;
}

void ob_compose_destroy(ob_compose_pass *c)
{
    for (int v = 0; v < OB_COMPOSE_VARIANTS; ++v) ob_compute_pass_destroy(&c->variants[v]);
}
