/* Direct light over the G-buffer into RGBA16F radiance (seed 000 §4.5; seed 003 §5.2), with the
 * shadow maps of src/passes/shadow.c. Shader: shaders/lighting.glsl. */
#include <math.h>
#include <string.h>

#include "core/error.h"
#include "passes/passes.h"

/* A dielectric's specular reflectance (~4%) and a moderate lobe: scenes without material
 * specular data still show the light's direction without plastic-looking highlights. */
#define SPECULAR_KS 0.04f
#define SPECULAR_SHININESS 32.0f

ob_error ob_lighting_init(ob_lighting_pass *l)
{
    memset(l, 0, sizeof *l);
    return ob_compute_pass_init(&l->pass, "lighting.glsl", NULL, sizeof(ob_lighting_constants));
}

void ob_lighting_setup(ob_lighting_pass *l, const ob_light *lights, int count, const float inv_view[16],
                       const float proj_info[4], int width, int height)
{
    ob_lighting_constants *c = &l->constants;
    memset(c, 0, sizeof *c);
    c->size[0] = (float)width;
    c->size[1] = (float)height;
    c->size[2] = 1.0f / (float)width;
    c->size[3] = 1.0f / (float)height;
    memcpy(c->proj_info, proj_info, sizeof c->proj_info);
    memcpy(c->inv_view, inv_view, sizeof c->inv_view);
    c->specular[0] = SPECULAR_KS;
    c->specular[1] = SPECULAR_SHININESS;
    if (count > OB_MAX_LIGHTS) count = OB_MAX_LIGHTS;
    c->counts[0] = count;
    for (int i = 0; i < count; ++i) {
        const ob_light *s = &lights[i];
        float len = sqrtf(s->direction[0] * s->direction[0] + s->direction[1] * s->direction[1] +
                          s->direction[2] * s->direction[2]);
        for (int k = 0; k < 3; ++k) {
            c->light_color[i][k] = s->color[k] * s->intensity;
            c->light_position[i][k] = s->position[k];
            c->light_direction[i][k] = len > 0.0f ? s->direction[k] / len : (k == 1 ? 1.0f : 0.0f);
        }
        c->light_color[i][3] = (float)s->type;
        c->light_position[i][3] = s->range;
        c->light_direction[i][3] = -1.0f; /* unshadowed until ob_shadows_fill says otherwise */
        c->light_spot[i][0] = cosf(s->spot_inner_deg * 0.01745329252f);
        c->light_spot[i][1] = cosf(s->spot_outer_deg * 0.01745329252f);
    }
}

void ob_lighting_run(ob_lighting_pass *l, GLuint linear_depth, GLuint normal, GLuint albedo, GLuint radiance_out)
{
    const ob_lighting_constants *c = &l->constants;
    ob_compute_pass_use(&l->pass, c, sizeof *c);
    glBindTextureUnit(0, linear_depth);
    glBindTextureUnit(1, normal);
    glBindTextureUnit(2, albedo);
    glBindImageTexture(0, radiance_out, 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA16F);
    ob_dispatch_2d((int)c->size[0], (int)c->size[1], OB_LIGHTING_GROUP_X, OB_LIGHTING_GROUP_Y);
}

void ob_lighting_destroy(ob_lighting_pass *l) { ob_compute_pass_destroy(&l->pass); }
