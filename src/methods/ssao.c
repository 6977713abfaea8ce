/* `ssao`: normal-oriented hemisphere SSAO (Puri 2024 §2.3 and §3.3; Belonogov 2018 §3.2).
 * The reference the other methods are compared with. Shader: shaders/ssao.glsl. */
#include <stdlib.h>
#include <string.h>

#include "base/error.h"
#include "methods/method.h"
#include "sampling/sampling.h"
#include "ssao_params.h"

enum {
    P_RADIUS, P_BIAS, P_INTENSITY, P_SAMPLES, P_SAMPLING, P_DIRECTIONS,
    P_NOISE, P_DEINTERLEAVE, P_DEPTH_MIPS, P_COUNT
};

/* The depth MIP chain only with `depth_mips` on (ssao_active_reads). */
#define SSAO_READS (OB_READS_DEPTH | OB_READS_NORMALS | OB_READS_DEPTH_MIPS)

static const ob_param_info ssao_params[P_COUNT] = {
    [P_RADIUS] = {"radius", OB_PARAM_FLOAT, 1e-4f, 1e4f, 0.5f, "world",
                  "hemisphere radius; default: the scene's suggested radius", true},
    /* Relative to the radius so one default works in metres and millimetres alike; 0.02 removes
     * the acne of R32F depth on llvmpipe and GPUs without visibly thinning contact shadows. */
    [P_BIAS] = {"bias", OB_PARAM_FLOAT, 0.0f, 0.5f, 0.02f, "x radius",
                "depth bias against self-occlusion, as a fraction of the radius", false},
    [P_INTENSITY] = {"intensity", OB_PARAM_FLOAT, 0.0f, 8.0f, 1.0f, "exponent",
                     "AO = visibility^intensity: > 1 darkens, < 1 lightens", false},
    /* 16 taps: the 4x4 noise x 16 kernel points gives 256 distinct directions per tile. */
    [P_SAMPLES] = {"samples", OB_PARAM_INT, 1.0f, (float)OB_SSAO_MAX_SAMPLES, 16.0f, "count",
                   "kernel points per pixel", false},
    [P_SAMPLING] = {"sampling", OB_PARAM_ENUM, 0.0f, 1.0f, 0.0f, "", "kernel numbers: seeded random (seed) or Halton 2,5,3",
                    false, ob_sampling_options},
    /* Uniform in solid angle, as the seed's kernel; cosine-weighted makes each sample count as
     * much as the cosine-weighted AO integral asks (SSDO thesis eq. 5.2). */
    [P_DIRECTIONS] = {"directions", OB_PARAM_ENUM, 0.0f, 1.0f, 0.0f, "", "kernel directions: uniform (eq. 5.3) or cosine (eq. 5.2)",
                      false, ob_direction_options},
    [P_NOISE] = {"noise", OB_PARAM_ENUM, 0.0f, 1.0f, 0.0f, "", "per-pixel rotation: 4x4 texture or interleaved gradient noise",
                 false, ob_noise_options},
    [P_DEINTERLEAVE] = OB_DEINTERLEAVE_PARAM,
    [P_DEPTH_MIPS] = OB_TAPS_DEPTH_MIPS_PARAM,
};

/* Fixed seeds: the same command gives the same AO bytes. */
#define KERNEL_SEED 0x55A0u

typedef struct ssao_state {
    ob_method_kit kit;
    int kernel_count; /* the cached kernel was built for these */
    int kernel_sampling, kernel_directions;
    ob_taps taps; /* `deinterleave`, `depth_mips` (methods/deinterleave.c) */
    ob_ssao_constants constants;
} ssao_state;

static ob_error ssao_run(void *p, const ob_ao_inputs *in, const float *params, const ob_ao_outputs *out)
{
    ssao_state *s = p;
    ob_ssao_constants *c = &s->constants;
    const ob_sample_plan plan =
        ob_method_sample_plan(in, (int)params[P_SAMPLES], (int)params[P_SAMPLING], OB_SSAO_MAX_SAMPLES);
    const int count = plan.count, sampling = plan.sampling, directions = (int)params[P_DIRECTIONS];
    if (count != s->kernel_count || sampling != s->kernel_sampling || directions != s->kernel_directions) {
        ob_hemisphere_kernel(&c->kernel[0][0], count, (ob_sampling)sampling, (ob_direction_pdf)directions, KERNEL_SEED);
        s->kernel_count = count;
        s->kernel_sampling = sampling;
        s->kernel_directions = directions;
    }
    c->radius = params[P_RADIUS];
    c->bias = params[P_BIAS] * params[P_RADIUS];
    c->intensity = params[P_INTENSITY];
    c->samples = count;
    c->noise = (int)params[P_NOISE];
    c->adaptive = plan.adaptive ? 1 : 0;
    c->adaptive_base = plan.base;
    const bool split = params[P_DEINTERLEAVE] != 0.0f, mips = params[P_DEPTH_MIPS] != 0.0f;
    if (ob_taps_prepare(&s->taps, "ssao", "ssao.glsl", in, split, mips) != OB_OK) return ob_peek_error(NULL);
    /* Upload only the kernel entries in use. */
    size_t used = offsetof(ob_ssao_constants, kernel) + (size_t)count * sizeof c->kernel[0];
    ob_method_kit_use(&s->kit, c, used, in, out, GL_R32F);
    ob_method_kit_bind_multiplier(&s->kit, in);
    ob_taps_dispatch(&s->taps, in, OB_SSAO_GROUP_X, OB_SSAO_GROUP_Y);
    return OB_OK;
}

static void ssao_destroy(void *p) { ob_taps_release(&((ssao_state *)p)->taps); }

static uint32_t ssao_active_reads(const float *params) { return ob_taps_reads(params[P_DEPTH_MIPS]); }

static int ssao_kernel(const float *params, float *xyzw, int max)
{
    int count = (int)params[P_SAMPLES] < max ? (int)params[P_SAMPLES] : max;
    ob_hemisphere_kernel(xyzw, count, (ob_sampling)(int)params[P_SAMPLING], (ob_direction_pdf)(int)params[P_DIRECTIONS],
                         KERNEL_SEED);
    return count;
}

const ob_method_impl ob_method_ssao = {
    .info = {.name = "ssao",
             .description = "normal-oriented hemisphere SSAO with range check (StarCraft II)",
             .reference = "Puri 2024 §2.3, §3.3; Belonogov 2018 §3.2",
             .param_count = P_COUNT,
             .params = ssao_params},
    .shader = "ssao.glsl",
    .constants_size = sizeof(ob_ssao_constants),
    .state_size = sizeof(ssao_state),
    .reads = SSAO_READS,
    .active_reads = ssao_active_reads,
    .writes = OB_WRITES_VISIBILITY,
    .run = ssao_run,
    .destroy = ssao_destroy,
    .adapts = true,
    .kernel = ssao_kernel,
    .roles = {[OB_ROLE_RADIUS] = OB_ROLE_PARAM(P_RADIUS), [OB_ROLE_SAMPLES] = OB_ROLE_PARAM(P_SAMPLES),
              [OB_ROLE_INTENSITY] = OB_ROLE_PARAM(P_INTENSITY), [OB_ROLE_DEINTERLEAVE] = OB_ROLE_PARAM(P_DEINTERLEAVE)},
};
