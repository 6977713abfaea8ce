/* `alchemy`: Alchemy AO (McGuire et al. 2011; Puri 2024 §2.5, §3.4): spiral disk samples and an
 * obscurance estimator with artist controls sigma (intensity), k (contrast), beta (depth-scaled
 * bias) and epsilon. Shader: shaders/alchemy.glsl. */
#include <stdlib.h>
#include <string.h>

#include "alchemy_params.h"
#include "base/error.h"
#include "methods/method.h"
#include "sampling/sampling.h"

enum { P_RADIUS, P_SAMPLES, P_SIGMA, P_K, P_BETA, P_EPSILON, P_TURNS, P_NOISE, P_DEINTERLEAVE, P_DEPTH_MIPS, P_COUNT };

/* The depth MIP chain only with `depth_mips` on (alchemy_active_reads). */
#define ALCHEMY_READS (OB_READS_DEPTH | OB_READS_NORMALS | OB_READS_DEPTH_MIPS)

static const ob_param_info alchemy_params[P_COUNT] = {
    [P_RADIUS] = {"radius", OB_PARAM_FLOAT, 1e-4f, 1e4f, 0.5f, "world",
                  "world-space disk radius; default: the scene's suggested radius", true},
    [P_SAMPLES] = {"samples", OB_PARAM_INT, 1.0f, 256.0f, 16.0f, "count", "spiral samples per pixel (Puri 2024: 16)", false},
    [P_SIGMA] = {"sigma", OB_PARAM_FLOAT, 0.0f, 10.0f, 1.7f, "", "intensity scale sigma (Puri 2024: 1.7)", false},
    [P_K] = {"k", OB_PARAM_FLOAT, 0.1f, 8.0f, 1.0f, "exponent", "contrast k (Puri 2024: 1)", false},
    /* Puri 2024's 0.5 belongs to its code, which adds beta*z to the normal; in the paper's
     * equation it would subtract half the depth from v.n and erase all occlusion (measured: see
     * docs/methods.md). 0.005 frees the bunny's smooth-normal self-occlusion (open pixels 46% -> 74%)
     * and keeps the corner crease black (1st percentile 0.07); measured in docs/methods.md. */
    [P_BETA] = {"beta", OB_PARAM_FLOAT, 0.0f, 1.0f, 0.005f, "x depth/radius",
                "bias distance beta, scaled by the depth z_C", false},
    [P_EPSILON] = {"epsilon", OB_PARAM_FLOAT, 1e-6f, 1.0f, 0.001f, "radius^2",
                   "keeps the division finite; McGuire et al. saw no change within 100x of 1e-4", false},
    [P_TURNS] = {"turns", OB_PARAM_FLOAT, 1.0f, 64.0f, 10.0f, "turns", "spiral turns over the samples (Puri 2024: 10)", false},
    [P_NOISE] = {"noise", OB_PARAM_ENUM, 0.0f, 1.0f, 0.0f, "", "per-pixel spiral rotation: 4x4 texture or interleaved gradient noise",
                 false, ob_noise_options},
    [P_DEINTERLEAVE] = OB_DEINTERLEAVE_PARAM,
    [P_DEPTH_MIPS] = OB_TAPS_DEPTH_MIPS_PARAM,
};


typedef struct alchemy_state {
    ob_method_kit kit;
    ob_taps taps; /* `deinterleave`, `depth_mips` (methods/deinterleave.c) */
} alchemy_state;

static ob_error alchemy_run(void *p, const ob_ao_inputs *in, const float *params, const ob_ao_outputs *out)
{
    alchemy_state *s = p;
    ob_alchemy_constants c;
    memset(&c, 0, sizeof c);
    c.radius = params[P_RADIUS];
    c.sigma = params[P_SIGMA];
    c.k = params[P_K];
    c.beta = params[P_BETA];
    c.epsilon = params[P_EPSILON];
    c.turns = params[P_TURNS];
    /* Pixels per world unit at depth 1: (height / 2) * P11. */
    c.px_per_unit = 0.5f * (float)in->height / in->frame->ao_proj_info[1];
    c.samples = (int)params[P_SAMPLES];
    c.noise = (int)params[P_NOISE];
    /* Adaptive sample counts: the spiral's samples scale with the edge pass's multiplier. */
    c.adaptive = in->sample_multiplier != 0 ? 1 : 0;
    c.adaptive_base = ob_adaptive_base(c.samples);
    const bool split = params[P_DEINTERLEAVE] != 0.0f, mips = params[P_DEPTH_MIPS] != 0.0f;
    if (ob_taps_prepare(&s->taps, "alchemy", "alchemy.glsl", in, split, mips) != OB_OK) return ob_peek_error(NULL);
    ob_method_kit_use(&s->kit, &c, sizeof c, in, out, GL_R32F);
    ob_method_kit_bind_multiplier(&s->kit, in);
    ob_taps_dispatch(&s->taps, in, OB_ALCHEMY_GROUP_X, OB_ALCHEMY_GROUP_Y);
    return OB_OK;
}

static void alchemy_destroy(void *p) { ob_taps_release(&((alchemy_state *)p)->taps); }

static uint32_t alchemy_active_reads(const float *params) { return ob_taps_reads(params[P_DEPTH_MIPS]); }

const ob_method_impl ob_method_alchemy = {
    .info = {.name = "alchemy",
             .description = "Alchemy AO: spiral disk samples, obscurance with sigma, k, beta, epsilon",
             .reference = "Puri 2024 §2.5, §3.4; McGuire et al. 2011",
             .param_count = P_COUNT,
             .params = alchemy_params},
    .shader = "alchemy.glsl",
    .constants_size = sizeof(ob_alchemy_constants),
    .state_size = sizeof(alchemy_state),
    .reads = ALCHEMY_READS,
    .active_reads = alchemy_active_reads,
    .writes = OB_WRITES_VISIBILITY,
    .run = alchemy_run,
    .destroy = alchemy_destroy,
    .adapts = true,
    /* sigma, the paper's intensity scale, is its intensity (k, the contrast exponent, shapes it). */
    .roles = {[OB_ROLE_RADIUS] = OB_ROLE_PARAM(P_RADIUS), [OB_ROLE_SAMPLES] = OB_ROLE_PARAM(P_SAMPLES),
              [OB_ROLE_INTENSITY] = OB_ROLE_PARAM(P_SIGMA), [OB_ROLE_DEINTERLEAVE] = OB_ROLE_PARAM(P_DEINTERLEAVE)},
};
