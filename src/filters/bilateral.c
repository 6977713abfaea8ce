/* `bilateral`: the full 2D bilateral filter of Belonogov 2018 §4.3.2 (eq. 4.5) with the range term on
 * relative depth, one dispatch over a (2r+1)^2 window. O(r^2) taps: slow on purpose, it is the
 * quality reference that `bilateral_sep` (eq. 4.6-4.7) approximates; the two share parameters,
 * defaults and weights (kernel.c) so their difference is the separable approximation alone.
 * Shader: shaders/bilateral.glsl. */
#include <stdlib.h>

#include "base/error.h"
#include "filters/filter.h"

enum { P_RADIUS, P_SIGMA, P_SIGMA_DEPTH, P_COUNT };

static const ob_param_info bilateral_params[P_COUNT] = {
    /* As `gaussian`: 4 taps = 2 sigma spans two tiles of the 4x4 rotation noise. */
    [P_RADIUS] = {"radius", OB_PARAM_INT, 1.0f, (float)OB_FILTER_MAX_RADIUS, 4.0f, "px",
                  "kernel half-width in taps ((2r+1)^2 window)", false},
    [P_SIGMA] = {"sigma", OB_PARAM_FLOAT, 0.1f, 16.0f, 2.0f, "px", "spatial standard deviation (eq. 4.4)", false},
    /* 5% of the depth: a floor seen at 80 deg from the view axis at 720p changes by ~0.8% of its
     * depth per pixel, so 4 taps away it still weighs exp(-0.5 (0.033/0.05)^2) = 0.8, while an
     * object 20% in front of what is behind it weighs exp(-8) = 3e-4: surfaces blur, silhouettes
     * stay. Relative, so it is the same in metres and millimetres. */
    [P_SIGMA_DEPTH] = {"sigma_depth", OB_PARAM_FLOAT, 0.001f, 1.0f, 0.05f, "x depth",
                       "range standard deviation on |d_q - d_p| / d_p (eq. 4.5)", false},
};

static void *bilateral_init(void) { return ob_filter_make_pass("bilateral.glsl", false); }
static void *bilateral_init_rgb(void) { return ob_filter_make_pass("bilateral.glsl", true); }

static ob_error bilateral_run(void *state, const ob_filter_inputs *in, const float *params)
{
    ob_filter_constants c;
    ob_filter_constants_init(&c, in, (int)params[P_RADIUS], params[P_SIGMA], params[P_SIGMA_DEPTH], 0.0f);
    ob_filter_run_single(state, &c, ob_filter_constants_used(&c), in);
    return OB_OK;
}

const ob_filter_impl ob_filter_bilateral = {
    .info = {.name = "bilateral",
             .description = "full 2D depth bilateral over (2r+1)^2 taps: slow, the quality reference",
             .reference = "Belonogov 2018 §4.3.2, eq. 4.5",
             .param_count = P_COUNT,
             .params = bilateral_params},
    .init = bilateral_init,
    .run = bilateral_run,
    .destroy = ob_filter_destroy_pass,
    .init_rgb = bilateral_init_rgb,
};
