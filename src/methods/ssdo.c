/* `ssdo` and `ssdo_merged`: screen-space directional occlusion with one indirect bounce
 * (Ritschel, Grosch & Seidel 2009, described in SSDO thesis §3.3; SSDO thesis §4.2 and §5.3; Belonogov 2018
 * §4.1-4.2). Both write a per-channel modulation factor M (SSDO thesis eq. 4.2-4.4: the direct light
 * with visibility over the same without, 1 = open) and an RGB bounce; compose gives
 * direct x M + ambient x albedo x M + bounce x albedo.
 *   - `ssdo`: the original two passes. Pass 1 takes uniform solid-angle directions (eq. 5.3) and
 *     weighs incoming radiance by cos(theta); pass 2 revisits the same samples and turns every
 *     occluder pixel into a patch of area pi r^2 / N sending its direct radiance (eq. 3.4).
 *   - `ssdo_merged`: SSDO thesis's one-pass variant: cosine-weighted directions (eq. 5.2), M and the
 *     bounce in one loop, the bounce darkened by M.
 * Shader: shaders/ssdo.glsl (one program, the stage in a constant). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "base/error.h"
#include "methods/method.h"
#include "sampling/sampling.h"
#include "ssdo_params.h"

enum { P_RADIUS, P_BIAS, P_SAMPLES, P_BOUNCE, P_BOUNCE_STRENGTH, P_LOBE, P_LAYERS, P_EXTRA_VIEW, P_FUSED, P_PACKED, P_DEINTERLEAVE,
       P_DEPTH_MIPS, P_COUNT };


/* The lobe exponent of the default programs, which compile it in (shaders/ssdo.glsl: three
 * squarings); any other value takes the pow variant. */
#define DEFAULT_LOBE 8.0f

static const ob_param_info ssdo_params[P_COUNT] = {
    [P_RADIUS] = {"radius", OB_PARAM_FLOAT, 1e-4f, 1e4f, 0.5f, "world",
                  "sampling hemisphere radius; default: the scene's suggested radius", true},
    /* As `ssao`: relative to the radius, 0.02 removes R32F depth acne. */
    [P_BIAS] = {"bias", OB_PARAM_FLOAT, 0.0f, 0.5f, 0.02f, "x radius",
                "depth bias against self-occlusion, as a fraction of the radius", false},
    /* 16: the 4x4 noise x 16 Halton points gives 256 directions per tile; multiples of 10 (the
     * period of bases 2 x 5, SSDO thesis §4.1) split the hemisphere evenly too. */
    [P_SAMPLES] = {"samples", OB_PARAM_INT, 1.0f, (float)OB_SSDO_MAX_SAMPLES, 16.0f, "count",
                   "hemisphere samples per pixel (Halton 2,5 directions, 3 for the step)", false},
    [P_BOUNCE] = {"bounce", OB_PARAM_BOOL, 0.0f, 1.0f, 1.0f, "on/off",
                  "one indirect bounce from occluder pixels (eq. 3.4); off writes a black bounce", false},
    /* 1 = the physical patch area A_s = pi r^2 / N of eq. 3.4; SSDO thesis §5.3 leaves it to the user. */
    [P_BOUNCE_STRENGTH] = {"bounce_strength", OB_PARAM_FLOAT, 0.0f, 16.0f, 1.0f, "x A_s",
                           "multiplies the sender patch area pi r^2 / N", false},
    /* 8: a lobe of ~30 degrees half-width at half maximum, wide enough that 16 samples hit it,
     * narrow enough that M still says from which side the light comes. */
    [P_LOBE] = {"lobe", OB_PARAM_FLOAT, 1.0f, 256.0f, DEFAULT_LOBE, "exponent",
                "lights become cosine lobes max(0, w.l)^k around their direction: k", false},
    /* 2: Belonogov 2018's test around Fig. 4.6: a sample behind the first layer occludes only while it
     * is in front of the second (inside the object); behind it the sample is free. */
    [P_LAYERS] = OB_LAYERS_PARAM,
    /* Belonogov 2018 §4.4: a sample hidden in this view but seen in front of the extra view's surface
     * is free, and a bounce comes from whichever view's surface lies nearer the sample. */
    [P_EXTRA_VIEW] = {"extra_view", OB_PARAM_BOOL, 0.0f, 1.0f, 0.0f, "on/off",
                      "also a camera turned 90 degrees around the target: its G-buffer frees samples it sees and "
                      "sends bounces from surfaces this view sees at grazing angles",
                      false},
    /* On: `ssdo`'s two passes (M, then the bounce from the same samples) in one dispatch, which
     * takes, tests and projects each sample once instead of twice; the outputs are the same
     * bits (tests/test_ssdo.c). Off: the seed's two passes, the baseline. ssdo_merged has one
     * pass either way. */
    [P_FUSED] = {"fused", OB_PARAM_BOOL, 0.0f, 1.0f, 1.0f, "on/off",
                 "ssdo: M and the bounce in one dispatch (off: two passes over the same samples)", false},
    /* On: a pre-pass packs each AO texel's depth, normal and direct radiance into one RGBA32UI
     * texel (methods/packed.c) and a sample makes one fetch instead of three; the outputs
     * are the same bits (tests/test_ssdo.c). llvmpipe fetches a sender's normal and radiance for
     * every sample (the bounce's block is masked, not skipped), and a fetch costs it about the
     * same whatever its size: on fzk-haus:stair at 640x480 (five alternated rounds, the medians'
     * median, pack included) ssdo 144 -> 98 ms, ssdo_merged 141 -> 122
     * (bench/results/2026-11-23-llvmpipe-crease-block-ssdo-lobe.md). A GPU
     * skips those fetches where no lane of a group is occluded and would read 16 bytes a sample
     * for 4, so auto packs only on a software rasteriser; off is the baseline. */
    [P_PACKED] = OB_PACKED_PARAM("; not with depth_mips"),
    /* The taps' depth from the 16 noise classes' layers (methods/deinterleave.c); with `packed`
     * the packed texel is read at the same (class) pixel, so both give the same bits. */
    [P_DEINTERLEAVE] = OB_DEINTERLEAVE_PARAM,
    /* Far taps' depth from the MIP chain (shaders/taps.glsl); the sender's normal and light are
     * read at the pixel the chain picked, from their full textures. It takes the place of
     * `packed` (the chain's levels are not packed), as in vbgi. */
    [P_DEPTH_MIPS] = OB_TAPS_DEPTH_MIPS_PARAM,
};

#define KERNEL_SEED 0x55D0u

/* 2 x 2 x 3 x 2 x 2 x 2 x 2 programs, indexed by bits (the ambient mode's two bits take 3
 * values), for each number of lights 0 ... OB_MAX_LIGHTS: see ssdo_state.variants. */
#define VARIANT_BITS 256
#define VARIANTS (VARIANT_BITS * (OB_MAX_LIGHTS + 1))

typedef struct ssdo_state {
    ob_method_kit kit;
    /* The program variants with the second layer (bit 0), the extra view (bit 1), the ambient
     * mode (bits 2-3: constant, hemisphere, environment), a lobe other than DEFAULT_LOBE (bit 4:
     * pow), the packed samples (bit 5), deinterleaved taps (bit 6) and MIP taps (bit 7), plus
     * VARIANT_BITS x the number of lights, made on first use; [0] is the kit's own program (no
     * light, constant ambient, one layer, one view, the default lobe, unpacked, plain taps). */
    GLuint variants[VARIANTS];
    ob_packed_samples packed; /* `packed`: methods/packed.c, bound at OB_UNIT_PACKED_SAMPLES */
    ob_deinterleaved split;   /* `deinterleave`: methods/deinterleave.c, bound at OB_UNIT_DEPTH_LAYERS */
    int kernel_count; /* the cached kernel was built for these */
    int kernel_pdf;
    bool merged;
    ob_ssdo_constants constants;
} ssdo_state;

static ob_error ssdo_init(void *p)
{
    ssdo_state *s = p;
    s->merged = false;
    s->kernel_count = -1;
    return OB_OK;
}

static ob_error ssdo_merged_init(void *p)
{
    ssdo_state *s = p;
    s->merged = true;
    s->kernel_count = -1;
    return OB_OK;
}


/* Halton 2,5 directions and base 3 steps (SSDO thesis §5.3), as unit direction + length. */
static void build_kernel(ssdo_state *s, int count, ob_direction_pdf pdf)
{
    ob_ssdo_constants *c = &s->constants;
    ob_hemisphere_kernel(&c->kernel[0][0], count, OB_SAMPLING_HALTON, pdf, KERNEL_SEED);
    for (int i = 0; i < count; ++i) {
        float *k = c->kernel[i];
        float len = sqrtf(k[0] * k[0] + k[1] * k[1] + k[2] * k[2]);
        float inv = len > 0.0f ? 1.0f / len : 0.0f;
        k[0] *= inv;
        k[1] *= inv;
        k[2] *= inv;
        k[3] = len;
    }
    s->kernel_count = count;
    s->kernel_pdf = (int)pdf;
}

/* The second depth layer, the extra view and the MIP chain only when asked for. */
static uint32_t ssdo_active_reads(const float *params)
{
    return (OB_READS_DEPTH | OB_READS_NORMALS | OB_READS_RADIANCE | OB_READS_DEPTH_MIPS |
            (params[P_LAYERS] >= 2.0f ? OB_READS_SECOND_LAYER : 0u) |
            (params[P_EXTRA_VIEW] != 0.0f ? OB_READS_EXTRA_VIEW : 0u)) &
           ob_taps_reads(params[P_DEPTH_MIPS]);
}

/* `bounce` off: no bounce to write, filter or upsample. */
static uint32_t ssdo_active_writes(const float *params)
{
    return OB_WRITES_VISIBILITY_RGB | (params[P_BOUNCE] != 0.0f ? OB_WRITES_BOUNCE : 0u);
}

static void ssdo_destroy(void *p)
{
    ssdo_state *s = p;
    for (int v = 1; v < VARIANTS; ++v)
        if (s->variants[v]) glDeleteProgram(s->variants[v]);
    ob_packed_samples_release(&s->packed);
    ob_deinterleaved_release(&s->split);
}

static ob_error ssdo_run(void *p, const ob_ao_inputs *in, const float *params, const ob_ao_outputs *out)
{
    ssdo_state *s = p;
    ob_ssdo_constants *c = &s->constants;
    if (!in->radiance || !out->bounce)
        return ob_set_error(OB_ERR_INVALID_ARGUMENT, "ssdo needs the renderer's direct light (ob_render_frame)");
    /* Adaptive sample counts: a kernel of 3 x base Halton entries, of which a pixel takes the
     * first base x its block's multiplier (the kernel is Halton already, so fixed counts keep it). */
    ob_sample_plan plan = ob_method_sample_plan(in, (int)params[P_SAMPLES], OB_SAMPLING_MODE_HALTON, OB_SSDO_MAX_SAMPLES);
    int count = plan.count;
    ob_direction_pdf pdf = s->merged ? OB_DIRECTIONS_COSINE : OB_DIRECTIONS_UNIFORM;
    if (count != s->kernel_count || (int)pdf != s->kernel_pdf) build_kernel(s, count, pdf);
    c->adaptive = plan.adaptive ? 1 : 0;
    c->adaptive_base = plan.base;
    bool bounce = params[P_BOUNCE] != 0.0f;
    float radius = params[P_RADIUS];

    c->radius = radius;
    c->bias = params[P_BIAS] * radius;
    /* Eq. 3.4's A_s = pi r^2 / N, over pi for the radiance a white receiver reflects. */
    c->bounce_scale = params[P_BOUNCE_STRENGTH] * radius * radius / (float)count;
    c->lobe = params[P_LOBE];
    c->samples = count;
    c->noise = OB_NOISE_TEXTURE4; /* the 4x4 rotation texture: the filters' windows cancel its tile */
    c->bounce = bounce ? 1 : 0;
    c->layers = params[P_LAYERS] >= 2.0f && in->second_depth ? 1 : 0;
    c->extra_view = params[P_EXTRA_VIEW] != 0.0f && in->extra_depth ? 1 : 0;
    if (c->extra_view) {
        memcpy(c->extra_from_view, in->extra_from_view, sizeof c->extra_from_view);
        memcpy(c->extra_to_view, in->extra_to_view, sizeof c->extra_to_view);
        memcpy(c->extra_proj, in->extra_proj, sizeof c->extra_proj);
        const float *ep = in->extra_proj; /* column-major: 1/P00, 1/P11, P20, P21 as ob_view_position takes them */
        c->extra_proj_info[0] = 1.0f / ep[0];
        c->extra_proj_info[1] = 1.0f / ep[5];
        c->extra_proj_info[2] = ep[8];
        c->extra_proj_info[3] = ep[9];
    }

    /* The layer and extra-view code and the ambient mode's per-sample radiance only in their own
     * programs (shaders/ssdo.glsl): llvmpipe runs an if block whose uniform condition is false as
     * it runs any other, and the hemisphere and SH branches cost ssdo a third of its pass in the
     * default constant mode (bench/results/2026-11-23-llvmpipe-ssdo-ambient.md). */
    GLuint variant = 0;
    const int mode = in->frame->ambient_mode == OB_AMBIENT_MODE_HEMISPHERE     ? 1
                     : in->frame->ambient_mode == OB_AMBIENT_MODE_ENVIRONMENT ? 2
                                                                              : 0;
    const bool pow_lobe = c->lobe != DEFAULT_LOBE;
    const bool split = params[P_DEINTERLEAVE] != 0.0f, mips = params[P_DEPTH_MIPS] != 0.0f;
    if (ob_taps_exclusive(s->merged ? "ssdo_merged" : "ssdo", split, mips) != OB_OK) return ob_peek_error(NULL);
    const bool packed = !mips && ob_packed_samples_wanted(&s->packed, params[P_PACKED]);
    /* The number of lights too: the per-sample light loop then unrolls (shaders/ssdo.glsl). */
    const int lights = in->frame->light_count;
    const int v = ((c->layers ? 1 : 0) | (c->extra_view ? 2 : 0) | mode << 2 | (pow_lobe ? 16 : 0) | (packed ? 32 : 0) |
                   (split ? 64 : 0) | (mips ? 128 : 0)) +
                  VARIANT_BITS * lights;
    if (v) {
        static const char *const ambient[3] = {"", "#define OB_SSDO_AMBIENT_HEMISPHERE 1\n",
                                               "#define OB_SSDO_AMBIENT_ENVIRONMENT 1\n"};
        char defines[352];
        snprintf(defines, sizeof defines, "%s%s%s%s%s%s%s#define OB_SSDO_LIGHTS %d\n",
                 c->layers ? "#define OB_SSDO_LAYERS 1\n" : "", c->extra_view ? "#define OB_SSDO_EXTRA_VIEW 1\n" : "",
                 ambient[mode], pow_lobe ? "#define OB_SSDO_LOBE_POW 1\n" : "",
                 packed ? "#define OB_SSDO_PACKED 1\n" : "", split ? OB_DEINTERLEAVED_DEFINE : "",
                 mips ? "#define OB_TAPS_DEPTH_MIPS 1\n" : "", lights);
        variant = ob_method_variant(&s->variants[v], "ssdo.glsl", defines);
        if (!variant) return ob_peek_error(NULL);
    }
    if (packed) {
        ob_error err = ob_packed_samples_run(&s->packed, in, OB_UNIT_PACKED_SAMPLES); /* ssdo.glsl's packed_samples */
        if (err != OB_OK) return err;
    }
    if (split && ob_deinterleaved_prepare(&s->split, NULL, in) != OB_OK) return ob_peek_error(NULL);
    if (mips) ob_taps_bind_mips(in); /* taps.glsl's chain */
    size_t used = offsetof(ob_ssdo_constants, kernel) + (size_t)count * sizeof c->kernel[0];
    const bool fused = params[P_FUSED] != 0.0f && bounce;
    c->stage = s->merged ? OB_SSDO_STAGE_MERGED : fused ? OB_SSDO_STAGE_BOTH : OB_SSDO_STAGE_DIRECT;
    ob_method_kit_use(&s->kit, c, used, in, out, GL_RGBA16F);
    glBindTextureUnit(OB_UNIT_RADIANCE, in->radiance);
    glBindTextureUnit(OB_UNIT_SSDO_MULTIPLIER, in->sample_multiplier ? in->sample_multiplier : s->kit.noise);
    /* The depth keeps each sampler valid where its input is off. */
    glBindTextureUnit(OB_UNIT_SECOND_DEPTH, in->second_depth ? in->second_depth : in->linear_depth);
    glBindTextureUnit(OB_UNIT_EXTRA_DEPTH, in->extra_depth ? in->extra_depth : in->linear_depth);
    glBindTextureUnit(OB_UNIT_EXTRA_NORMAL, in->extra_normal ? in->extra_normal : in->view_normal);
    glBindTextureUnit(OB_UNIT_EXTRA_RADIANCE, in->extra_radiance ? in->extra_radiance : in->radiance);
    /* The renderer gives every declared output a target, so image 1 is valid with the bounce off
     * too (the merged stage then writes zeros there; nothing reads them). */
    glBindImageTexture(OB_IMAGE_UNIT_BOUNCE, out->bounce, 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA16F);
    ob_method_dispatch(variant, split, in, OB_SSDO_GROUP_X, OB_SSDO_GROUP_Y);
    if (s->merged || !bounce || fused) return OB_OK;
    /* Pass 2 reads nothing pass 1 wrote (the senders' radiance is the lighting pass's), so no
     * barrier: the same samples, the bounce of eq. 3.4. */
    c->stage = OB_SSDO_STAGE_BOUNCE;
    ob_compute_pass_use(&s->kit.pass, c, used);
    ob_method_dispatch(variant, split, in, OB_SSDO_GROUP_X, OB_SSDO_GROUP_Y);
    return OB_OK;
}

/* The Halton 2,5 / 3 kernels as points: pass 1's uniform directions and the merged variant's
 * cosine-weighted ones (build_kernel stores the same points as direction + length). */
static int kernel_points(const float *params, float *xyzw, int max, ob_direction_pdf pdf)
{
    int count = (int)params[P_SAMPLES] < max ? (int)params[P_SAMPLES] : max;
    ob_hemisphere_kernel(xyzw, count, OB_SAMPLING_HALTON, pdf, KERNEL_SEED);
    return count;
}

static int ssdo_kernel(const float *params, float *xyzw, int max)
{
    return kernel_points(params, xyzw, max, OB_DIRECTIONS_UNIFORM);
}

static int ssdo_merged_kernel(const float *params, float *xyzw, int max)
{
    return kernel_points(params, xyzw, max, OB_DIRECTIONS_COSINE);
}

/* Both entries share the table, so the roles too. */
#define SSDO_ROLES                                                                                                 \
    {[OB_ROLE_RADIUS] = OB_ROLE_PARAM(P_RADIUS), [OB_ROLE_SAMPLES] = OB_ROLE_PARAM(P_SAMPLES),                     \
     [OB_ROLE_LAYERS] = OB_ROLE_PARAM(P_LAYERS), [OB_ROLE_PACKED] = OB_ROLE_PARAM(P_PACKED),                       \
     [OB_ROLE_DEINTERLEAVE] = OB_ROLE_PARAM(P_DEINTERLEAVE)}

const ob_method_impl ob_method_ssdo = {
    .info = {.name = "ssdo",
             .description = "screen-space directional occlusion + one bounce, the original two passes",
             .reference = "SSDO thesis §3.3 eq. 3.2-3.4, §5.3 eq. 5.3; Belonogov 2018 §4.1-4.2",
             .param_count = P_COUNT,
             .params = ssdo_params},
    .shader = "ssdo.glsl",
    .constants_size = sizeof(ob_ssdo_constants),
    .state_size = sizeof(ssdo_state),
    .reads = OB_READS_DEPTH | OB_READS_NORMALS | OB_READS_RADIANCE | OB_READS_SECOND_LAYER | OB_READS_EXTRA_VIEW |
             OB_READS_DEPTH_MIPS,
    .active_reads = ssdo_active_reads,
    .destroy = ssdo_destroy,
    .writes = OB_WRITES_VISIBILITY_RGB | OB_WRITES_BOUNCE,
    .adapts = true,
    .kernel = ssdo_kernel,
    .init = ssdo_init,
    .run = ssdo_run,
    .active_writes = ssdo_active_writes,
    .roles = SSDO_ROLES,
};

const ob_method_impl ob_method_ssdo_merged = {
    .info = {.name = "ssdo_merged",
             .description = "one-pass SSDO: modulation factor M and bounce (darkened by M) in one loop",
             .reference = "SSDO thesis §4.2 eq. 4.1-4.4, §5.3 eq. 5.2",
             .param_count = P_COUNT,
             .params = ssdo_params},
    .shader = "ssdo.glsl",
    .constants_size = sizeof(ob_ssdo_constants),
    .state_size = sizeof(ssdo_state),
    .reads = OB_READS_DEPTH | OB_READS_NORMALS | OB_READS_RADIANCE | OB_READS_SECOND_LAYER | OB_READS_EXTRA_VIEW |
             OB_READS_DEPTH_MIPS,
    .active_reads = ssdo_active_reads,
    .destroy = ssdo_destroy,
    .writes = OB_WRITES_VISIBILITY_RGB | OB_WRITES_BOUNCE,
    .adapts = true,
    .kernel = ssdo_merged_kernel,
    .init = ssdo_merged_init,
    .run = ssdo_run,
    .active_writes = ssdo_active_writes,
    .roles = SSDO_ROLES,
};
