/* `none`: no occlusion (AO = 1 everywhere), for reference frames and the cost baseline. */
#include "methods/method.h"

static ob_error none_run(void *state, const ob_ao_inputs *in, const float *params, const ob_ao_outputs *out)
{
    (void)state;
    (void)in;
    (void)params;
    (void)out;
    /* The renderer writes the 1 with its fill pass, into this target and the full-size one
     * together (frame.c run_without_ao): a method has no compute pass without a shader, and
     * the one without a shader is what marks the no-AO baseline. */
    return OB_OK;
}

const ob_method_impl ob_method_none = {
    .info = {.name = "none", .description = "no occlusion: visibility 1 everywhere (reference frame)",
             .reference = "-", .param_count = 0, .params = NULL},
    .writes = OB_WRITES_VISIBILITY,
    .run = none_run,
    /* No parameters, so no roles (all 0). */
};
