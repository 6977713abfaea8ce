/* `hbao`: horizon-based ambient occlusion (Bavoil & Sainz 2008), Belonogov 2018 §3.3 (eq. 3.1-3.2,
 * W = max(0, 1 - r/R)) and Puri 2024 §2.4 (tangent and horizon angles) and §3.4 (an OpenGL
 * implementation: radius projected with depth and clamped, directions rotated per pixel).
 * N_d screen directions x N_s depth-buffer steps; the quality presets of Belonogov 2018 map onto them
 * (hbao_set_samples). Shader: shaders/hbao.glsl. */
#include <math.h>
#include <stdlib.h>

#include "base/error.h"
#include "hbao_params.h"
#include "methods/method.h"
#include "sampling/sampling.h"

enum {
    P_RADIUS, P_DIRECTIONS, P_STEPS, P_MAX_RADIUS_PX, P_ANGLE_BIAS, P_INTENSITY,
    P_NOISE, P_DEINTERLEAVE, P_DEPTH_MIPS, P_COUNT
};

/* The depth MIP chain only with `depth_mips` on (hbao_active_reads). */
#define HBAO_READS (OB_READS_DEPTH | OB_READS_NORMALS | OB_READS_DEPTH_MIPS)

static const ob_param_info hbao_params[P_COUNT] = {
    [P_RADIUS] = {"radius", OB_PARAM_FLOAT, 1e-4f, 1e4f, 0.5f, "world",
                  "horizon search radius R (W = 1 - r/R); default: the scene's suggested radius", true},
    /* 6 x 4 = 24 samples: Belonogov 2018's "medium" level. */
    [P_DIRECTIONS] = {"directions", OB_PARAM_INT, 1.0f, (float)OB_HBAO_MAX_DIRECTIONS, 6.0f, "count",
                      "screen directions N_d (azimuths 2πk/N_d, rotated per pixel)", false},
    [P_STEPS] = {"steps", OB_PARAM_INT, 1.0f, (float)OB_HBAO_MAX_STEPS, 4.0f, "count",
                 "depth-buffer steps N_s per direction", false},
    /* 128 px is a fifth of a 640-pixel-wide image: enough for the contact shadows the radius is
     * meant for, while a close-up cannot make every pixel march across the whole screen. */
    [P_MAX_RADIUS_PX] = {"max_radius_px", OB_PARAM_FLOAT, 1.0f, 1024.0f, 128.0f, "px",
                         "upper bound on the projected radius", false},
    /* 5 degrees, not NVIDIA's customary 10-30: the shader's tangent is exact on planes (the
     * perspective slice, and texel snapping compensated), so flat surfaces need no bias at all -
     * the open floor of `corner` reads 1.000 at 0, 5 and 10 degrees (640x480, blur off, 0.957 at 0
     * before those fixes). The bias is left to hide tessellation: the upper half of the 48x24
     * sphere of `sphere-on-plane` (front) reads 0.998 at 0, 1.000 at 5. Every degree more only
     * lightens real creases: `corner` 0-3 cm from the crease reads 0.664 / 0.685 / 0.707 at
     * 0 / 5 / 10 degrees, where AO_R (R = 0.5, cosine-weighted, one infinite wall, integrated
     * numerically) is 0.51-0.54. */
    [P_ANGLE_BIAS] = {"angle_bias", OB_PARAM_FLOAT, 0.0f, 60.0f, 5.0f, "degrees",
                      "added to the tangent angle: hides tessellation creases and self-occlusion", false},
    [P_INTENSITY] = {"intensity", OB_PARAM_FLOAT, 0.0f, 8.0f, 1.0f, "x",
                     "strength multiplier: AO = 1 - intensity * occlusion", false},
    [P_NOISE] = {"noise", OB_PARAM_ENUM, 0.0f, 1.0f, 0.0f, "",
                 "per-pixel rotation and step jitter: 4x4 texture (+ 4x4 Bayer jitter) or interleaved gradient noise",
                 false, ob_noise_options},
    [P_DEINTERLEAVE] = OB_DEINTERLEAVE_PARAM,
    [P_DEPTH_MIPS] = OB_TAPS_DEPTH_MIPS_PARAM,
};


typedef struct hbao_state {
    ob_method_kit kit;
    ob_taps taps; /* `deinterleave`, `depth_mips` (methods/deinterleave.c) */
    ob_hbao_constants constants;
} hbao_state;

static ob_error hbao_run(void *p, const ob_ao_inputs *in, const float *params, const ob_ao_outputs *out)
{
    hbao_state *s = p;
    ob_hbao_constants *c = &s->constants;
    float bias = params[P_ANGLE_BIAS] * (3.14159265358979f / 180.0f);
    c->radius = params[P_RADIUS];
    c->inv_radius = 1.0f / params[P_RADIUS];
    /* R_px = R * (height/2) * P11 / d; P11 = 1 / proj_info.y. */
    c->px_per_unit = 0.5f * (float)in->height / in->frame->ao_proj_info[1];
    c->max_radius_px = params[P_MAX_RADIUS_PX];
    c->sin_bias = sinf(bias);
    c->cos_bias = cosf(bias);
    c->intensity = params[P_INTENSITY];
    c->directions = (int)params[P_DIRECTIONS];
    c->steps = (int)params[P_STEPS];
    c->noise = (int)params[P_NOISE];
    /* Adaptive sample counts: the directions scale with the edge pass's multiplier. */
    c->adaptive = in->sample_multiplier != 0 ? 1 : 0;
    c->adaptive_base = (c->directions + 1) / 3 > 1 ? (c->directions + 1) / 3 : 1;
    const bool split = params[P_DEINTERLEAVE] != 0.0f, mips = params[P_DEPTH_MIPS] != 0.0f;
    if (ob_taps_prepare(&s->taps, "hbao", "hbao.glsl", in, split, mips) != OB_OK) return ob_peek_error(NULL);
    ob_method_kit_use(&s->kit, c, sizeof *c, in, out, GL_R32F);
    ob_method_kit_bind_multiplier(&s->kit, in);
    ob_taps_dispatch(&s->taps, in, OB_HBAO_GROUP_X, OB_HBAO_GROUP_Y);
    return OB_OK;
}

static void hbao_destroy(void *p) { ob_taps_release(&((hbao_state *)p)->taps); }

static uint32_t hbao_active_reads(const float *params) { return ob_taps_reads(params[P_DEPTH_MIPS]); }

static int clamp_int(long v, int lo, int hi) { return v < lo ? lo : v > hi ? hi : (int)v; }

/* N samples per pixel -> directions x steps. Belonogov 2018's quality levels (§3.2.3: 12/24/36/64)
 * get hand-picked splits: few directions leave star-shaped streaks that the 4x4 blur cannot
 * remove, few steps miss thin occluders, so both grow together. Other counts split near
 * sqrt(N) x sqrt(N). */
static int hbao_count_samples(const float *params) { return (int)params[P_DIRECTIONS] * (int)params[P_STEPS]; }
static int hbao_count_rays(const float *params) { return (int)params[P_DIRECTIONS]; }

static ob_error hbao_set_samples(float *params, uint32_t *params_set, int samples)
{
    if (!params) return ob_set_error(OB_ERR_INVALID_ARGUMENT, "hbao: params is NULL");
    if (samples < 1 || samples > OB_HBAO_MAX_DIRECTIONS * OB_HBAO_MAX_STEPS)
        return ob_set_error(OB_ERR_OUT_OF_RANGE, "hbao: samples must be 1..%d (directions x steps), got %d",
                            OB_HBAO_MAX_DIRECTIONS * OB_HBAO_MAX_STEPS, samples);
    static const struct { int samples, directions, steps; } presets[] = {
        {12, 4, 3}, {24, 6, 4}, {36, 6, 6}, {64, 8, 8}};
    int directions = 0, steps = 0;
    for (size_t i = 0; i < sizeof presets / sizeof presets[0]; ++i)
        if (presets[i].samples == samples) {
            directions = presets[i].directions;
            steps = presets[i].steps;
        }
    if (directions == 0) {
        directions = clamp_int(lroundf(sqrtf((float)samples)), 1, OB_HBAO_MAX_DIRECTIONS);
        steps = clamp_int(lroundf((float)samples / (float)directions), 1, OB_HBAO_MAX_STEPS);
    }
    params[P_DIRECTIONS] = (float)directions;
    params[P_STEPS] = (float)steps;
    if (params_set) *params_set |= (1u << P_DIRECTIONS) | (1u << P_STEPS);
    return OB_OK;
}

const ob_method_impl ob_method_hbao = {
    .info = {.name = "hbao",
             .description = "horizon-based AO: directions x steps through the depth buffer (NVIDIA)",
             .reference = "Belonogov 2018 §3.3 eq. 3.1-3.2; Puri 2024 §2.4, §3.4",
             .param_count = P_COUNT,
             .params = hbao_params},
    .shader = "hbao.glsl",
    .constants_size = sizeof(ob_hbao_constants),
    .state_size = sizeof(hbao_state),
    .reads = HBAO_READS,
    .active_reads = hbao_active_reads,
    .writes = OB_WRITES_VISIBILITY,
    .run = hbao_run,
    .destroy = hbao_destroy,
    .set_samples = hbao_set_samples,
    .count_samples = hbao_count_samples,
    .count_rays = hbao_count_rays,
    .adapts = true,
    /* No OB_ROLE_SAMPLES: the count is directions x steps (set_samples, count_samples). */
    .roles = {[OB_ROLE_RADIUS] = OB_ROLE_PARAM(P_RADIUS), [OB_ROLE_MAX_RADIUS_PX] = OB_ROLE_PARAM(P_MAX_RADIUS_PX),
              [OB_ROLE_INTENSITY] = OB_ROLE_PARAM(P_INTENSITY), [OB_ROLE_DEINTERLEAVE] = OB_ROLE_PARAM(P_DEINTERLEAVE)},
};
