/* Joint bilateral upsampling of the AO (SSDO thesis §3.5 eq. 3.12, §5.3). Shader:
 * shaders/upsample.glsl: the plain program and the block programs (one invocation per k x k
 * pixels), the same bits (tests/test_filters.c). */
#include <stdio.h>
#include <string.h>

#include "base/error.h"
#include "passes/passes.h"
#include "resample_params.h"

/* Depth similarity within 2% of the depth, normals within ~25 degrees (the shader's cos^8 = 0.5):
 * tight enough that no AO crosses a silhouette or a crease, loose enough that a slanted floor
 * still finds its own neighbours across a 4x subsampling step. */
#define UPSAMPLE_SIGMA_DEPTH 0.02f

ob_error ob_upsample_init(ob_upsample *u, bool rgb)
{
    *u = (ob_upsample){.rgb = rgb, .software = ob_renderer_is_software((const char *)glGetString(GL_RENDERER))};
    return ob_compute_pass_init(&u->programs[0][0], "upsample.glsl", rgb ? "#define OB_FILTER_RGB 1\n" : NULL,
                                sizeof(ob_resample_constants));
}

ob_error ob_upsample_run(ob_upsample *u, int program, const ob_ao_grid *g, GLuint full_depth, GLuint full_normal,
                         GLuint low_depth, GLuint low_normal, GLuint low_ao, GLuint ao_out, float sky, GLuint low_second,
                         GLuint second_out)
{
    /* auto: the block program where a fetch costs as much as arithmetic, a software rasteriser
     * (on llvmpipe at 1280x720 the pass is 1.6-1.9x faster, docs/filters.md), but for two RGBA
     * values at k = 2, where one plain dispatch beats two block ones (below; 1.3x); a GPU's
     * texture cache serves the plain one's neighbouring invocations, not measured there yet. */
    const bool pair = low_second != 0;
    if (program == OB_UPSAMPLE_AUTO)
        program = u->software && !(pair && u->rgb && g->k == 2) ? OB_UPSAMPLE_BLOCK : OB_UPSAMPLE_PLAIN;
    const bool block = program == OB_UPSAMPLE_BLOCK && (g->k == 2 || g->k == 4);
    if (pair && block && u->rgb) {
        /* Two RGBA values in one block program (ssdo's M and bounce) hold two 4x4 patches and
         * their row copies, ~40 vec4 per lane, and spilled on llvmpipe: 1.9-2.3x slower than two
         * block passes at 1280x720 (docs/filters.md). So they take a pass each here. */
        ob_error err = ob_upsample_run(u, program, g, full_depth, full_normal, low_depth, low_normal, low_ao, ao_out, sky, 0, 0);
        if (err != OB_OK) return err;
        return ob_upsample_run(u, program, g, full_depth, full_normal, low_depth, low_normal, low_second, second_out, 0.0f,
                               0, 0);
    }
    ob_compute_pass *p = &u->programs[pair][block ? (g->k == 4 ? 2 : 1) : 0];
    if (!p->program) {
        char defines[128];
        snprintf(defines, sizeof defines, "%s%s", u->rgb ? "#define OB_FILTER_RGB 1\n" : "",
                 pair ? "#define OB_UPSAMPLE_PAIR 1\n" : "");
        if (block) snprintf(defines + strlen(defines), sizeof defines - strlen(defines), "#define OB_UPSAMPLE_BLOCK %d\n", g->k);
        if (ob_compute_pass_init(p, "upsample.glsl", defines, sizeof(ob_resample_constants)) != OB_OK)
            return ob_peek_error(NULL);
    }
    ob_resample_constants c;
    ob_resample_fill(&c, g);
    c.upsample_depth_sigma = UPSAMPLE_SIGMA_DEPTH;
    c.upsample_sky_value = sky;
    ob_compute_pass_use(p, &c, sizeof c);
    glBindTextureUnit(OB_UNIT_DEPTH, full_depth);
    glBindTextureUnit(OB_UNIT_NORMAL, full_normal);
    glBindTextureUnit(OB_UNIT_UPSAMPLE_LOW_DEPTH, low_depth);
    glBindTextureUnit(OB_UNIT_UPSAMPLE_LOW_NORMAL, low_normal);
    glBindTextureUnit(OB_UNIT_UPSAMPLE_LOW_AO, low_ao);
    glBindImageTexture(OB_IMAGE_UNIT_OUT, ao_out, 0, GL_FALSE, 0, GL_WRITE_ONLY, u->rgb ? GL_RGBA16F : GL_R32F);
    if (pair) {
        glBindTextureUnit(OB_UNIT_UPSAMPLE_LOW_SECOND, low_second);
        glBindImageTexture(OB_IMAGE_UNIT_UPSAMPLE_SECOND, second_out, 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA16F);
    }
    const int k = block ? g->k : 1; /* full pixels per invocation and axis */
    ob_dispatch_2d((g->full_width + k - 1) / k, (g->full_height + k - 1) / k, OB_RESAMPLE_GROUP_X, OB_RESAMPLE_GROUP_Y);
    return OB_OK;
}

const char *ob_upsample_program_name(ob_upsample_program program)
{
    static const char *const names[OB_UPSAMPLE_PROGRAM_COUNT] = {"auto", "plain", "block"};
    return (int)program >= 0 && program < OB_UPSAMPLE_PROGRAM_COUNT ? names[program] : "";
}

void ob_upsample_destroy(ob_upsample *u)
{
    for (int pair = 0; pair < 2; ++pair)
        for (int i = 0; i < 3; ++i) ob_compute_pass_destroy(&u->programs[pair][i]);
}
