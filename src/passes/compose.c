/* Lighting + compose: one directional light (Lambert + Blinn-Phong, seed 000 §4.5) and an
 * ambient term multiplied by AO, written as sRGB. */
#include <string.h>

#include "compose_params.h"
#include "core/error.h"
#include "passes/passes.h"

/* A dielectric's specular reflectance (~4%) and a moderate lobe: scenes without material
 * specular data still show the light's direction without plastic-looking highlights. */
#define SPECULAR_KS 0.04f
#define SPECULAR_SHININESS 32.0f

ob_error ob_compose_init(ob_compose_pass *c)
{
    return ob_compute_pass_init(&c->pass, "compose.glsl", NULL, sizeof(ob_compose_constants));
}

void ob_compose_run(ob_compose_pass *c, const ob_compose_inputs *in, GLuint final_out)
{
    ob_compose_constants k;
    memset(&k, 0, sizeof k);
    k.size[0] = (float)in->width;
    k.size[1] = (float)in->height;
    k.size[2] = 1.0f / (float)in->width;
    k.size[3] = 1.0f / (float)in->height;
    memcpy(k.proj_info, in->proj_info, sizeof k.proj_info);
    memcpy(k.light_dir, in->light_dir_view, 3 * sizeof(float));
    memcpy(k.light_color, in->light_radiance, 3 * sizeof(float));
    memcpy(k.ambient, in->ambient, 3 * sizeof(float));
    memcpy(k.background, in->background, 3 * sizeof(float));
    k.specular[0] = SPECULAR_KS;
    k.specular[1] = SPECULAR_SHININESS;
    ob_compute_pass_use(&c->pass, &k, sizeof k);
    glBindTextureUnit(0, in->linear_depth);
    glBindTextureUnit(1, in->normal);
    glBindTextureUnit(2, in->albedo);
    glBindTextureUnit(3, in->ao);
    glBindImageTexture(0, final_out, 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA8);
    ob_dispatch_2d(in->width, in->height, OB_COMPOSE_GROUP_X, OB_COMPOSE_GROUP_Y);
}

void ob_compose_destroy(ob_compose_pass *c) { ob_compute_pass_destroy(&c->pass); }
