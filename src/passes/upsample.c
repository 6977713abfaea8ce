/* Joint bilateral upsampling of the AO (seed 003 §3.5 eq. 3.12, §5.3). Shader:
 * shaders/upsample.glsl: the plain program and the block programs (one invocation per k x k
 * pixels), the same bits (tests/test_filters.c). */
#include <stdio.h>

#include "core/error.h"
#include "passes/passes.h"
#include "resample_params.h"

/* Depth similarity within 2% of the depth, normals within ~25 degrees (the shader's cos^8 = 0.5):
 * tight enough that no AO crosses a silhouette or a crease, loose enough that a slanted floor
 * still finds its own neighbours across a 4x subsampling step. */
#define UPSAMPLE_SIGMA_DEPTH 0.02f

ob_error ob_upsample_init(ob_upsample *u, bool rgb)
{
    *u = (ob_upsample){.rgb = rgb, .software = ob_renderer_is_software((const char *)glGetString(GL_RENDERER))};
    return ob_compute_pass_init(&u->plain, "upsample.glsl", rgb ? "#define OB_FILTER_RGB 1\n" : NULL,
                                sizeof(ob_resample_constants));
}

ob_error ob_upsample_run(ob_upsample *u, int program, const ob_ao_grid *g, GLuint full_depth, GLuint full_normal,
                         GLuint low_depth, GLuint low_normal, GLuint low_ao, GLuint ao_out, float sky)
{
    /* auto: the block program where a fetch costs as much as arithmetic, a software rasteriser
     * (on llvmpipe at 1280x720 the pass is 1.7-1.9x faster at k = 4, 1.25-1.6x at k = 2,
     * docs/filters.md); a GPU's texture cache serves the plain one's neighbouring invocations,
     * not measured there yet. */
    if (program == OB_UPSAMPLE_AUTO) program = u->software ? OB_UPSAMPLE_BLOCK : OB_UPSAMPLE_PLAIN;
    const bool block = program == OB_UPSAMPLE_BLOCK && (g->k == 2 || g->k == 4);
    ob_compute_pass *p = &u->plain;
    if (block) {
        p = &u->block[g->k == 4];
        if (!p->program) {
            char defines[80];
            snprintf(defines, sizeof defines, "%s#define OB_UPSAMPLE_BLOCK %d\n", u->rgb ? "#define OB_FILTER_RGB 1\n" : "",
                     g->k);
            if (ob_compute_pass_init(p, "upsample.glsl", defines, sizeof(ob_resample_constants)) != OB_OK)
                return ob_peek_error(NULL);
        }
    }
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
    glBindImageTexture(0, ao_out, 0, GL_FALSE, 0, GL_WRITE_ONLY, u->rgb ? GL_RGBA16F : GL_R32F);
    const int k = block ? g->k : 1; /* full pixels per invocation and axis */
    ob_dispatch_2d((g->full_width + k - 1) / k, (g->full_height + k - 1) / k, OB_RESAMPLE_GROUP_X, OB_RESAMPLE_GROUP_Y);
    return OB_OK;
}

void ob_upsample_destroy(ob_upsample *u)
{
    ob_compute_pass_destroy(&u->plain);
    ob_compute_pass_destroy(&u->block[0]);
    ob_compute_pass_destroy(&u->block[1]);
}
