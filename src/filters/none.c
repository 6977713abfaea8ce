/* `none`: no filtering; the raw AO goes on as it is. */
#include "filters/filter.h"

static ob_error none_run(void *state, const ob_filter_inputs *in, const float *params)
{
    (void)state;
    (void)params;
    glCopyImageSubData(in->src, GL_TEXTURE_2D, 0, 0, 0, 0, in->dst, GL_TEXTURE_2D, 0, 0, 0, 0, in->width,
                       in->height, 1);
    return OB_OK;
}

const ob_filter_impl ob_filter_none = {
    .info = {.name = "none", .description = "no filtering: the raw AO", .reference = "-", .param_count = 0},
    .init = NULL,
    .run = none_run,
    .destroy = NULL,
};
