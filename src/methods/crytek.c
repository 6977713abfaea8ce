/* `crytek`: Crytek SSAO (Mittring 2007; Puri 2024 §2.2), the first SSAO: a sphere of samples and
 * a depth-only test. Flat surfaces self-occlude to about 0.5 by design; `correction` applies
 * SSDO thesis §5.4's factor (off by default). Shader: shaders/crytek.glsl. */
#include <stdlib.h>
#include <string.h>

#include "base/error.h"
#include "crytek_params.h"
#include "methods/method.h"
#include "sampling/sampling.h"

enum {
    P_RADIUS, P_BIAS, P_INTENSITY, P_SAMPLES, P_CORRECTION, P_SAMPLING,
    P_NOISE, P_DEINTERLEAVE, P_DEPTH_MIPS, P_COUNT
};

/* The depth MIP chain only with `depth_mips` on (crytek_active_reads). */
#define CRYTEK_READS (OB_READS_DEPTH | OB_READS_DEPTH_MIPS)

static const ob_param_info crytek_params[P_COUNT] = {
    [P_RADIUS] = {"radius", OB_PARAM_FLOAT, 1e-4f, 1e4f, 0.5f, "world",
                  "sphere radius; default: the scene's suggested radius", true},
    [P_BIAS] = {"bias", OB_PARAM_FLOAT, 0.0f, 0.5f, 0.02f, "x radius",
                "depth bias, as a fraction of the radius", false},
    [P_INTENSITY] = {"intensity", OB_PARAM_FLOAT, 0.0f, 8.0f, 1.0f, "exponent",
                     "AO = visibility^intensity", false},
    [P_SAMPLES] = {"samples", OB_PARAM_INT, 1.0f, (float)OB_CRYTEK_MAX_SAMPLES, 16.0f, "count",
                   "sphere points per pixel", false},
    [P_CORRECTION] = {"correction", OB_PARAM_BOOL, 0.0f, 1.0f, 0.0f, "on/off",
                      "SSDO thesis §5.4: AO' = min(1, 2 AO), so open planes read 1 instead of ~0.5", false},
    [P_SAMPLING] = {"sampling", OB_PARAM_ENUM, 0.0f, 1.0f, 0.0f, "", "kernel numbers: seeded random or Halton 2,5,3",
                    false, ob_sampling_options},
    [P_NOISE] = {"noise", OB_PARAM_ENUM, 0.0f, 1.0f, 0.0f, "", "per-pixel rotation: 4x4 texture or interleaved gradient noise",
                 false, ob_noise_options},
    [P_DEINTERLEAVE] = OB_DEINTERLEAVE_PARAM,
    [P_DEPTH_MIPS] = OB_TAPS_DEPTH_MIPS_PARAM,
};

#define KERNEL_SEED 0xC4E7u

typedef struct crytek_state {
    ob_method_kit kit;
    int kernel_count, kernel_sampling; /* what the cached kernel was built for */
    ob_taps taps; /* `deinterleave`, `depth_mips` (methods/deinterleave.c) */
    ob_crytek_constants constants;
} crytek_state;

static ob_error crytek_init(void *p)
{
    crytek_state *s = p;
    s->kernel_count = -1;
    return OB_OK;
}

static ob_error crytek_run(void *p, const ob_ao_inputs *in, const float *params, const ob_ao_outputs *out)
{
    crytek_state *s = p;
    ob_crytek_constants *c = &s->constants;
    const ob_sample_plan plan =
        ob_method_sample_plan(in, (int)params[P_SAMPLES], (int)params[P_SAMPLING], OB_CRYTEK_MAX_SAMPLES);
    const int count = plan.count, sampling = plan.sampling;
    if (count != s->kernel_count || sampling != s->kernel_sampling) {
        ob_sphere_kernel(&c->kernel[0][0], count, (ob_sampling)sampling, KERNEL_SEED);
        s->kernel_count = count;
        s->kernel_sampling = sampling;
    }
    c->radius = params[P_RADIUS];
    c->bias = params[P_BIAS] * params[P_RADIUS];
    c->intensity = params[P_INTENSITY];
    c->correction = params[P_CORRECTION] != 0.0f ? 1 : 0;
    c->samples = count;
    c->noise = (int)params[P_NOISE];
    c->adaptive = plan.adaptive ? 1 : 0;
    c->adaptive_base = plan.base;
    const bool split = params[P_DEINTERLEAVE] != 0.0f, mips = params[P_DEPTH_MIPS] != 0.0f;
    if (ob_taps_prepare(&s->taps, "crytek", "crytek.glsl", in, split, mips) != OB_OK) return ob_peek_error(NULL);
    size_t used = offsetof(ob_crytek_constants, kernel) + (size_t)count * sizeof c->kernel[0];
    ob_method_kit_use(&s->kit, c, used, in, out, GL_R32F);
    ob_method_kit_bind_multiplier(&s->kit, in);
    ob_taps_dispatch(&s->taps, in, OB_CRYTEK_GROUP_X, OB_CRYTEK_GROUP_Y);
    return OB_OK;
}

static void crytek_destroy(void *p) { ob_taps_release(&((crytek_state *)p)->taps); }

static uint32_t crytek_active_reads(const float *params) { return ob_taps_reads(params[P_DEPTH_MIPS]); }

static int crytek_kernel(const float *params, float *xyzw, int max)
{
    int count = (int)params[P_SAMPLES] < max ? (int)params[P_SAMPLES] : max;
    ob_sphere_kernel(xyzw, count, (ob_sampling)(int)params[P_SAMPLING], KERNEL_SEED);
    return count;
}

const ob_method_impl ob_method_crytek = {
    .info = {.name = "crytek",
             .description = "Crytek SSAO: sphere samples, depth-only test (flat surfaces read ~0.5 by design)",
             .reference = "Puri 2024 §2.2; SSDO thesis §5.4 (correction); Mittring 2007",
             .param_count = P_COUNT,
             .params = crytek_params},
    .shader = "crytek.glsl",
    .constants_size = sizeof(ob_crytek_constants),
    .state_size = sizeof(crytek_state),
    .reads = CRYTEK_READS,
    .active_reads = crytek_active_reads,
    .writes = OB_WRITES_VISIBILITY,
    .init = crytek_init,
    .run = crytek_run,
    .destroy = crytek_destroy,
    .adapts = true,
    .kernel = crytek_kernel,
    .roles = {[OB_ROLE_RADIUS] = OB_ROLE_PARAM(P_RADIUS), [OB_ROLE_SAMPLES] = OB_ROLE_PARAM(P_SAMPLES),
              [OB_ROLE_INTENSITY] = OB_ROLE_PARAM(P_INTENSITY), [OB_ROLE_DEINTERLEAVE] = OB_ROLE_PARAM(P_DEINTERLEAVE)},
};
