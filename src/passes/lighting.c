/* Direct light over the G-buffer into RGBA16F radiance (Belonogov 2018 §4.5; SSDO thesis §5.2), with the
 * shadow maps of src/passes/shadow.c. Shader: shaders/lighting.glsl. */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "base/error.h"
#include "passes/passes.h"

/* A dielectric's specular reflectance (~4%) and a moderate lobe: scenes without material
 * specular data still show the light's direction without plastic-looking highlights. */
#define SPECULAR_KS 0.04f
#define SPECULAR_SHININESS 32.0f

/* The variant index and defines of a frame's lighting program (shaders/shadow.glsl): the shadow
 * method (2 bits) and whether a point light (cube map) and a directional or spot light (2D map)
 * has a map to read. */
static int variant_defines(int method, bool cube, bool flat, char *defines, size_t size)
{
    snprintf(defines, size, "#define OB_SHADOW_FIXED_METHOD %d\n%s%s", method,
             cube ? "" : "#define OB_SHADOW_NO_CUBE 1\n", flat ? "" : "#define OB_SHADOW_NO_2D 1\n");
    return method | (cube ? 4 : 0) | (flat ? 8 : 0);
}

ob_error ob_lighting_init(ob_lighting_pass *l)
{
    memset(l, 0, sizeof *l);
    /* The pass's own program is the common variant (PCF, directional and spot maps, no point
     * light's), so most scenes compile nothing more at their first frame. */
    char defines[160];
    const int v = variant_defines(OB_SHADOW_METHOD_PCF, false, true, defines, sizeof defines);
    ob_error err = ob_compute_pass_init(&l->pass, "lighting.glsl", defines, sizeof(ob_lighting_constants));
    if (err == OB_OK) l->variants[v] = l->pass.program;
    return err;
}

void ob_lighting_setup(ob_lighting_pass *l)
{
    l->constants.specular_ks = SPECULAR_KS;
    l->constants.specular_shininess = SPECULAR_SHININESS;
}

/* The variant for this frame, made on first use. */
static GLuint lighting_variant(ob_lighting_pass *l, const ob_frame_constants *frame)
{
    const int method = l->constants.shadow_method & 3;
    bool cube = false, flat = false;
    for (int i = 0; i < frame->light_count && i < OB_MAX_LIGHTS && method != OB_SHADOW_METHOD_NONE; ++i) {
        const int map = (int)floorf(frame->light_direction[i][3] + 0.5f);
        if (map < 0 || map >= OB_MAX_SHADOW_MAPS) continue;
        if ((int)(frame->light_color[i][3] + 0.5f) == OB_LIGHT_TYPE_POINT) cube = true;
        else flat = true;
    }
    char defines[160];
    const int v = variant_defines(method, cube, flat, defines, sizeof defines);
    if (!l->variants[v]) l->variants[v] = ob_make_compute_program("lighting.glsl", defines);
    return l->variants[v];
}

ob_error ob_lighting_run(ob_lighting_pass *l, const ob_frame_constants *frame, int width, int height, GLuint linear_depth,
                         GLuint normal, GLuint albedo, GLuint radiance_out)
{
    const GLuint program = lighting_variant(l, frame);
    if (!program) return ob_peek_error(NULL);
    const ob_lighting_constants *c = &l->constants;
    ob_compute_pass_use(&l->pass, c, sizeof *c);
    glUseProgram(program);
    glBindTextureUnit(OB_UNIT_DEPTH, linear_depth);
    glBindTextureUnit(OB_UNIT_NORMAL, normal);
    glBindTextureUnit(OB_UNIT_ALBEDO, albedo);
    glBindImageTexture(OB_IMAGE_UNIT_OUT, radiance_out, 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA16F);
    ob_dispatch_2d(width, height, OB_LIGHTING_GROUP_X, OB_LIGHTING_GROUP_Y);
    return OB_OK;
}

void ob_lighting_destroy(ob_lighting_pass *l)
{
    for (int v = 0; v < OB_LIGHTING_VARIANTS; ++v)
        if (l->variants[v] && l->variants[v] != l->pass.program) glDeleteProgram(l->variants[v]);
    ob_compute_pass_destroy(&l->pass);
}
