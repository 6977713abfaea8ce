/* `box4`: the classic 4x4 box blur after SSAO (seed 004 §3.3). Shader: shaders/box4.glsl. */
#include <stdlib.h>
#include <string.h>

#include "core/error.h"
#include "filter_params.h"
#include "filters/filter.h"

static void *box4_init(void) { return ob_filter_make_pass("box4.glsl", false); }
static void *box4_init_rgb(void) { return ob_filter_make_pass("box4.glsl", true); }

static ob_error box4_run(void *state, const ob_filter_inputs *in, const float *params)
{
    (void)params;
    ob_filter_constants c;
    memset(&c, 0, sizeof c);
    c.size[0] = in->width;
    c.size[1] = in->height;
    c.sky_value = in->sky; /* read by the RGB variant only (filter_params.h) */
    ob_compute_pass_use(state, &c, offsetof(ob_filter_constants, weights));
    glBindTextureUnit(0, in->src);
    glBindTextureUnit(1, in->linear_depth);
    glBindImageTexture(0, in->dst, 0, GL_FALSE, 0, GL_WRITE_ONLY, ob_filter_format(in));
    ob_dispatch_2d(in->width, in->height, OB_FILTER_GROUP_X, OB_FILTER_GROUP_Y);
    return OB_OK;
}

static void box4_destroy(void *state)
{
    if (!state) return;
    ob_compute_pass_destroy(state);
    free(state);
}

const ob_filter_impl ob_filter_box4 = {
    .info = {.name = "box4", .description = "the classic 4x4 box blur (one noise tile), the baseline",
             .reference = "seed 004 §3.3", .param_count = 0, .params = NULL},
    .init = box4_init,
    .run = box4_run,
    .destroy = box4_destroy,
    .init_rgb = box4_init_rgb,
};
