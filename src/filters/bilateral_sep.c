/* `bilateral_sep`: the separable approximation of the depth bilateral (Belonogov 2018 §4.3.2,
 * eq. 4.6 along x into scratch, eq. 4.7 along y into dst): O(r) taps per pass instead of
 * O(r^2). Parameters, defaults and weights are those of `bilateral` (kernel.c), so the RMSE
 * between the two measures the approximation alone. Shader: shaders/bilateral_sep.glsl. */
#include <stdlib.h>

#include "base/error.h"
#include "filters/filter.h"

enum { P_RADIUS, P_SIGMA, P_SIGMA_DEPTH, P_COUNT };

/* Same table as `bilateral` (see the reasons there). */
static const ob_param_info bilateral_sep_params[P_COUNT] = {
    [P_RADIUS] = {"radius", OB_PARAM_INT, 1.0f, (float)OB_FILTER_MAX_RADIUS, 4.0f, "px",
                  "kernel half-width in taps (2r+1 per pass)", false},
    [P_SIGMA] = {"sigma", OB_PARAM_FLOAT, 0.1f, 16.0f, 2.0f, "px", "spatial standard deviation (eq. 4.4)", false},
    [P_SIGMA_DEPTH] = {"sigma_depth", OB_PARAM_FLOAT, 0.001f, 1.0f, 0.05f, "x depth",
                       "range standard deviation on |d_q - d_p| / d_p (eq. 4.6-4.7)", false},
};

static void *bilateral_sep_init(void) { return ob_filter_make_pass("bilateral_sep.glsl", false); }
static void *bilateral_sep_init_rgb(void) { return ob_filter_make_pass("bilateral_sep.glsl", true); }

static ob_error bilateral_sep_run(void *state, const ob_filter_inputs *in, const float *params)
{
    ob_filter_constants c;
    ob_filter_constants_init(&c, in, (int)params[P_RADIUS], params[P_SIGMA], params[P_SIGMA_DEPTH], 0.0f);
    ob_filter_run_separable(state, &c, in);
    return OB_OK;
}

const ob_filter_impl ob_filter_bilateral_sep = {
    .info = {.name = "bilateral_sep",
             .description = "separable depth bilateral (x then y): the fast approximation of `bilateral`",
             .reference = "Belonogov 2018 §4.3.2, eq. 4.6-4.7",
             .param_count = P_COUNT,
             .params = bilateral_sep_params},
    .init = bilateral_sep_init,
    .run = bilateral_sep_run,
    .destroy = ob_filter_destroy_pass,
    .init_rgb = bilateral_sep_init_rgb,
};
