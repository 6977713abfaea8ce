/* `box4`: the classic 4x4 box blur after SSAO (Puri 2024 §3.3). Shader: shaders/box4.glsl. */
#include <stdlib.h>
#include <string.h>

#include "base/error.h"
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
    ob_filter_run_single(state, &c, offsetof(ob_filter_constants, weights), in);
    return OB_OK;
}

const ob_filter_impl ob_filter_box4 = {
    .info = {.name = "box4", .description = "the classic 4x4 box blur (one noise tile), the baseline",
             .reference = "Puri 2024 §3.3", .param_count = 0, .params = NULL},
    .init = box4_init,
    .run = box4_run,
    .destroy = ob_filter_destroy_pass,
    .init_rgb = box4_init_rgb,
};
