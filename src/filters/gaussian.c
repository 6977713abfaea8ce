/* `gaussian`: the separable Gaussian blur of Belonogov 2018 §4.3.1 (eq. 4.4): x then y with the same
 * 1D weights. It ignores geometry on purpose, so AO bleeds across silhouettes and onto the sky:
 * the baseline the edge-aware filters (Belonogov 2018 §4.3.2; SSDO thesis §3.5) are measured against.
 * Shader: shaders/gaussian.glsl; kernel and dispatches: kernel.c. */
#include <stdlib.h>

#include "base/error.h"
#include "filters/filter.h"

enum { P_RADIUS, P_SIGMA, P_COUNT };

static const ob_param_info gaussian_params[P_COUNT] = {
    /* 4 taps each side = 2 sigma: the 9-tap window spans two tiles of the 4x4 rotation noise
     * (Puri 2024 §3.3), so the tile pattern averages out in both directions. */
    [P_RADIUS] = {"radius", OB_PARAM_INT, 1.0f, (float)OB_FILTER_MAX_RADIUS, 4.0f, "px",
                  "kernel half-width in taps (2r+1 per direction)", false},
    /* radius = 2 sigma keeps 95% of the Gaussian's mass inside the window; the weights are
     * renormalised over the taps, so the truncation does not change the mean. */
    [P_SIGMA] = {"sigma", OB_PARAM_FLOAT, 0.1f, 16.0f, 2.0f, "px", "spatial standard deviation (eq. 4.4)", false},
};

static void *gaussian_init(void) { return ob_filter_make_pass("gaussian.glsl", false); }
static void *gaussian_init_rgb(void) { return ob_filter_make_pass("gaussian.glsl", true); }

static ob_error gaussian_run(void *state, const ob_filter_inputs *in, const float *params)
{
    ob_filter_constants c;
    ob_filter_constants_init(&c, in, (int)params[P_RADIUS], params[P_SIGMA], 0.0f, 0.0f);
    ob_filter_run_separable(state, &c, in);
    return OB_OK;
}

const ob_filter_impl ob_filter_gaussian = {
    .info = {.name = "gaussian",
             .description = "separable Gaussian blur that ignores geometry (bleeds across edges), the baseline",
             .reference = "Belonogov 2018 §4.3.1, eq. 4.4",
             .param_count = P_COUNT,
             .params = gaussian_params},
    .init = gaussian_init,
    .run = gaussian_run,
    .destroy = ob_filter_destroy_pass,
    .init_rgb = gaussian_init_rgb,
};
