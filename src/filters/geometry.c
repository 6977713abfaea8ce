/* `geometry`: the separable geometry-aware bilateral filter of SSDO thesis §3.5 (after Reinbothe et
 * al.): spatial Gaussian domain (Belonogov 2018 eq. 4.4) x range kernels on relative depth and on the
 * angle between normals, run as an x then a y pass as SSDO thesis §4.3 does to afford it; 11x11 by
 * default as in SSDO thesis §6.2 (fig. 6.9). The default filter: it removes the 4x4 noise while
 * keeping both silhouettes (depth) and creases (normals) crisp. Shader: shaders/geometry.glsl. */
#include <stdlib.h>

#include "base/error.h"
#include "filters/filter.h"

enum { P_RADIUS, P_SIGMA, P_SIGMA_DEPTH, P_SIGMA_NORMAL, P_COUNT };

#define OB_DEG_TO_RAD 0.017453292519943295f

static const ob_param_info geometry_params[P_COUNT] = {
    /* 5 taps each side = the 11x11 kernel of SSDO thesis §6.2. */
    [P_RADIUS] = {"radius", OB_PARAM_INT, 1.0f, (float)OB_FILTER_MAX_RADIUS, 5.0f, "px",
                  "kernel half-width in taps (2r+1 per pass; 5 = 11x11)", false},
    /* Wider than `gaussian`'s 2: the range terms guard the edges, so the spatial kernel can use
     * the whole window (the outermost tap still weighs exp(-25/18) = 0.25 of the centre). */
    [P_SIGMA] = {"sigma", OB_PARAM_FLOAT, 0.1f, 16.0f, 3.0f, "px", "spatial standard deviation (eq. 4.4)", false},
    /* As `bilateral`: grazing floors still blur, silhouettes do not. */
    [P_SIGMA_DEPTH] = {"sigma_depth", OB_PARAM_FLOAT, 0.001f, 1.0f, 0.05f, "x depth",
                       "range standard deviation on |d_q - d_p| / d_p", false},
    /* 20 deg: a 90 deg crease weighs exp(-0.5 (90/20)^2) = 4e-5 and a 45 deg bevel 0.08, so AO
     * does not leak around corners, while the few degrees between neighbours on a tessellated
     * curved surface (and the fp16 normal error) cost almost nothing (5 deg: 0.97). */
    [P_SIGMA_NORMAL] = {"sigma_normal", OB_PARAM_FLOAT, 1.0f, 90.0f, 20.0f, "degrees",
                        "range standard deviation on the angle between normals", false},
};

static void *geometry_init(void) { return ob_filter_make_pass("geometry.glsl", false); }
static void *geometry_init_rgb(void) { return ob_filter_make_pass("geometry.glsl", true); }

static ob_error geometry_run(void *state, const ob_filter_inputs *in, const float *params)
{
    ob_filter_constants c;
    ob_filter_constants_init(&c, in, (int)params[P_RADIUS], params[P_SIGMA], params[P_SIGMA_DEPTH],
                             params[P_SIGMA_NORMAL] * OB_DEG_TO_RAD);
    ob_filter_run_separable(state, &c, in);
    return OB_OK;
}

const ob_filter_impl ob_filter_geometry = {
    .info = {.name = "geometry",
             .description = "separable depth + normal bilateral (geometry-aware), 11x11 (brightens creases: see crease)",
             .reference = "SSDO thesis §3.5, §4.3, §6.2; Belonogov 2018 eq. 4.6-4.7",
             .param_count = P_COUNT,
             .params = geometry_params},
    .init = geometry_init,
    .run = geometry_run,
    .destroy = ob_filter_destroy_pass,
    .init_rgb = geometry_init_rgb,
};
