/* Joint bilateral upsampling of the AO (seed 003 §3.5 eq. 3.12, §5.3). Shader:
 * shaders/upsample.glsl. */
#include "passes/passes.h"
#include "resample_params.h"

/* Depth similarity within 2% of the depth, normals within ~25 degrees (the shader's cos^8 = 0.5):
 * tight enough that no AO crosses a silhouette or a crease, loose enough that a slanted floor
 * still finds its own neighbours across a 4x subsampling step. */
#define UPSAMPLE_SIGMA_DEPTH 0.02f

ob_error ob_upsample_init(ob_compute_pass *p)
{
    return ob_compute_pass_init(p, "upsample.glsl", NULL, sizeof(ob_resample_constants));
}

ob_error ob_upsample_init_rgb(ob_compute_pass *p)
{
    return ob_compute_pass_init(p, "upsample.glsl", "#define OB_FILTER_RGB 1\n", sizeof(ob_resample_constants));
}

static void upsample(ob_compute_pass *p, const ob_ao_grid *g, GLuint full_depth, GLuint full_normal, GLuint low_depth,
                     GLuint low_normal, GLuint low_ao, GLuint ao_out, GLenum format, float sky)
{
    ob_resample_constants c;
    ob_resample_fill(&c, g);
    c.upsample_depth_sigma = UPSAMPLE_SIGMA_DEPTH;
    c.upsample_sky_value = sky;
    ob_compute_pass_use(p, &c, sizeof c);
    glBindTextureUnit(0, full_depth);
    glBindTextureUnit(1, full_normal);
    glBindTextureUnit(2, low_depth);
    glBindTextureUnit(3, low_normal);
    glBindTextureUnit(4, low_ao);
    glBindImageTexture(0, ao_out, 0, GL_FALSE, 0, GL_WRITE_ONLY, format);
    ob_dispatch_2d(g->full_width, g->full_height, OB_RESAMPLE_GROUP_X, OB_RESAMPLE_GROUP_Y);
}

void ob_upsample_run(ob_compute_pass *p, const ob_ao_grid *g, GLuint full_depth, GLuint full_normal, GLuint low_depth,
                     GLuint low_normal, GLuint low_ao, GLuint ao_out)
{
    upsample(p, g, full_depth, full_normal, low_depth, low_normal, low_ao, ao_out, GL_R32F, 1.0f);
}

void ob_upsample_run_rgb(ob_compute_pass *p, const ob_ao_grid *g, GLuint full_depth, GLuint full_normal,
                         GLuint low_depth, GLuint low_normal, GLuint low_rgb, GLuint rgb_out, float sky)
{
    upsample(p, g, full_depth, full_normal, low_depth, low_normal, low_rgb, rgb_out, GL_RGBA16F, sky);
}
