/* `none`: no occlusion (AO = 1 everywhere), for reference frames and the cost baseline. */
#include "methods/method.h"

static ob_error none_run(void *state, const ob_ao_inputs *in, const float *params, const ob_ao_outputs *out)
{
    (void)state;
    (void)in;
    (void)params;
    const float one = 1.0f;
    glClearTexImage(out->visibility, 0, GL_RED, GL_FLOAT, &one);
    return OB_OK;
}

const ob_method_impl ob_method_none = {
    .info = {.name = "none", .description = "no occlusion: visibility 1 everywhere (reference frame)",
             .reference = "-", .param_count = 0, .params = NULL},
    .writes = OB_WRITES_VISIBILITY,
    .run = none_run,
};
