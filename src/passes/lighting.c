/* Direct light over the G-buffer into RGBA16F radiance (seed 000 §4.5; seed 003 §5.2), with the
 * shadow maps of src/passes/shadow.c. Shader: shaders/lighting.glsl. */
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

void ob_lighting_setup(ob_lighting_pass *l)
{
    l->constants.specular_ks = SPECULAR_KS;
    l->constants.specular_shininess = SPECULAR_SHININESS;
}

void ob_lighting_run(ob_lighting_pass *l, int width, int height, GLuint linear_depth, GLuint normal, GLuint albedo,
                     GLuint radiance_out)
{
    const ob_lighting_constants *c = &l->constants;
    ob_compute_pass_use(&l->pass, c, sizeof *c);
    glBindTextureUnit(0, linear_depth);
    glBindTextureUnit(1, normal);
    glBindTextureUnit(2, albedo);
    glBindImageTexture(0, radiance_out, 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA16F);
    ob_dispatch_2d(width, height, OB_LIGHTING_GROUP_X, OB_LIGHTING_GROUP_Y);
}

void ob_lighting_destroy(ob_lighting_pass *l) { ob_compute_pass_destroy(&l->pass); }
