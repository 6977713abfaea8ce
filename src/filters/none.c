/* `none`: no filtering; the raw AO goes on as it is (a copy: shaders/copy.glsl says why it is a
 * compute pass). */
#include <string.h>

#include "filter_params.h"
#include "filters/filter.h"

static void *none_init(void) { return ob_filter_make_pass("copy.glsl", false); }
static void *none_init_rgb(void) { return ob_filter_make_pass("copy.glsl", true); }

static ob_error none_run(void *state, const ob_filter_inputs *in, const float *params)
{
    (void)params;
    ob_filter_constants c;
    memset(&c, 0, sizeof c);
    c.size[0] = in->width;
    c.size[1] = in->height;
    ob_filter_run_single(state, &c, offsetof(ob_filter_constants, weights), in);
    return OB_OK;
}

const ob_filter_impl ob_filter_none = {
    .info = {.name = "none", .description = "no filtering: the raw AO", .reference = "-", .param_count = 0},
    .init = none_init,
    .run = none_run,
    .destroy = ob_filter_destroy_pass,
    .init_rgb = none_init_rgb,
};
