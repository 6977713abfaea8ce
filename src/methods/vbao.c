/* `vbao` and `vbgi`: visibility-bitmask ambient occlusion and one indirect bounce (Therrien,
 * Levesque & Gilet 2023, "Screen Space Indirect Lighting with Visibility Bitmask", §3). gtao's
 * slices (shaders/slice_march.glsl), with a 32-sector bitmask per slice in place of two horizon
 * angles and a thickness per sample, so light passes behind thin occluders. vbgi gathers the
 * direct radiance of the samples through the sectors each is the first to occlude, and is
 * composed like SSDO: (direct + ambient x albedo) x visibility + bounce x albedo. One shader body
 * (shaders/visibility_bitmask.glsl), entered through shaders/vbao.glsl and shaders/vbgi.glsl. */
#include <math.h>
#include <stdlib.h>

#include "base/error.h"
#include "methods/method.h"
#include "vbao_params.h"

enum {
    P_RADIUS,
    P_THICKNESS,
    P_THICKNESS_SLOPE,
    P_WEIGHTING,
    P_COVERAGE,
    P_SLICES,
    P_STEPS,
    P_NOISE,
    P_TEMPORAL,
    P_DEPTH_MIPS,
    P_LAYERS,
    P_CONNECT,
    P_FACETS,
    P_PLANES,
    P_EMITTER_COSINE, /* vbgi only from here on: the last entries, so vbao's table is the prefix */
    P_PACKED,
    P_COUNT
};

static const char *const coverage_options[] = {"touch", "half", "all"};
static const char *const connect_options[] = {"off", "chord", "ends", "curve"};

/* The defaults and the views that chose them: docs/methods.md, "vbao". */
static const ob_param_info vb_params[P_COUNT] = {
    [P_RADIUS] = {"radius", OB_PARAM_FLOAT, 1e-4f, 1e4f, 0.5f, "world",
                  "R of AO_R: a sample counts where it lies within R (its front, or where its thickness enters the "
                  "sphere); default: the scene's suggested radius",
                  true},
    [P_THICKNESS] = {"thickness", OB_PARAM_FLOAT, 0.0f, 100.0f, 0.75f, "x radius",
                     "every sample's thickness behind its front surface, as a multiple of R (constant in world units)",
                     false},
    [P_THICKNESS_SLOPE] = {"thickness_slope", OB_PARAM_FLOAT, 0.0f, 10.0f, 0.0f, "x depth",
                           "thickness added per unit of the sample's linear depth (0 = constant thickness)", false},
    [P_WEIGHTING] = {"weighting", OB_PARAM_ENUM, 0.0f, 1.0f, 1.0f, "",
                     "sectors weighted uniformly in angle (the paper's) or by the cosine (AO_R's)", false,
                     ob_direction_options},
    [P_COVERAGE] = {"coverage", OB_PARAM_ENUM, 0.0f, 2.0f, 0.0f, "",
                    "which sectors a sample's angle interval sets: every one it touches, those whose centre it "
                    "covers, or those it covers whole",
                    false, coverage_options},
    /* 3 slices x 6 steps x 2 sides = 36 taps, the high preset; every preset keeps these 6 steps
     * (VB_PRESET_STEPS below) and changes the slices. */
    [P_SLICES] = {"slices", OB_PARAM_INT, 1.0f, (float)OB_VB_MAX_SLICES, 3.0f, "count",
                  "screen directions N_slices over [0, π), each marched on both sides", false},
    [P_STEPS] = {"steps", OB_PARAM_INT, 1.0f, (float)OB_VB_MAX_STEPS, 6.0f, "count", "steps on each side of a slice",
                 false},
    [P_NOISE] = {"noise", OB_PARAM_ENUM, 0.0f, 1.0f, 0.0f, "",
                 "per-pixel slice and step jitter: 4x4 tile (a 4x4 filter averages it) or interleaved gradient noise",
                 false, ob_noise_options},
    [P_TEMPORAL] = {"temporal", OB_PARAM_BOOL, 0.0f, 1.0f, 0.0f, "on/off",
                    "move the jitters along an R2 sequence with the frame index (for temporal accumulation)", false},
    [P_DEPTH_MIPS] = {"depth_mips", OB_PARAM_BOOL, 0.0f, 1.0f, 0.0f, "on/off",
                      "far steps read the prefiltered depth MIP chain instead of full resolution", false},
    /* 2 (the default): a sample's back is the second layer behind it, the back of its own solid
     * (shaders/peel.frag.glsl), never thinner than the steps' spacing; where the layer is not that
     * solid's back (a single sheet, the front of another object) or there is none, and in a host's
     * frame without one, the constant thickness above. Chosen by docs/methods.md "Which surface is
     * the back", for one more raster of the scene and 16-19 % of the AO pass on llvmpipe. */
    [P_LAYERS] = {"layers", OB_PARAM_INT, 1.0f, 2.0f, 2.0f, "count",
                  "depth layers: 2 = a sample's back is the second depth layer (depth peeling) where that is "
                  "the back of its own solid, else the constant thickness; 1 = the constant thickness alone",
                  false},
    /* chord: the sectors between two consecutive steps on one continuous surface are set too
     * (shaders/visibility_bitmask.glsl): the directions a sparse march leaves open between the
     * steps of a wall, most at a crease's foot (docs/methods.md, "Steps joined along a surface").
     * ends (the default): a run's first and last steps also stand for their strata's outer halves,
     * laid along the samples' tangents, so that the presets' mean AO agrees; curve: that, with
     * the cubic through both fronts along their normals' tangents in place of the chord
     * (docs/methods.md, "Steps joined along a curve"; on an H200 the curve cost 1.4x the AO pass
     * of `ends` for 0.0004 of RMSE on the check views, and lost as much on the choose views). The
     * mode is the program's (OB_VB_CONNECT), not a uniform: with the curve's code in the program,
     * `chord` ran slower there than a program doing more than it (docs/methods.md, "What the curve
     * costs on a GPU"). */
    [P_CONNECT] = {"connect", OB_PARAM_ENUM, 0.0f, 3.0f, 2.0f, "",
                   "join consecutive steps on one continuous surface: off (each step's own interval, the "
                   "paper's), chord (the sectors between their fronts), ends (chord, and each run extended "
                   "over its end steps' strata along their surfaces) or curve (ends, with the curve through "
                   "both fronts along their normals' tangents in place of the chord)",
                   false, connect_options},
    /* on: the sectors between P's tangent plane (its interpolated normal's) and its own triangle's
     * plane are set, where the triangle rises above the tangent in the slice: AO_R's rays leave P
     * around the interpolated normal, and those below the triangle enter the surface at once
     * (docs/methods.md, "Facets of a smooth-shaded mesh"). Needs the G-buffer's facet normals: a
     * host's frame has none, and there it is off. Off by default: the reference's ray offset opens
     * part of the wedge on small triangles, and against it the choose views and five models that
     * chose nothing read better without (against a reference without that offset, with). */
    [P_FACETS] = {"facets", OB_PARAM_BOOL, 0.0f, 1.0f, 0.0f, "on/off",
                  "set the directions between the interpolated normal's tangent plane and the pixel's own "
                  "triangle, which a smooth-shaded mesh hides from its normals (needs the G-buffer's facet "
                  "normals; off in a host's frame)",
                  false},
    /* On: the back over a pixel's footprint follows the second layer's own plane across an edge
     * where the front steps to another surface (a stair of one-pixel risers: shaders/second_back.glsl,
     * docs/methods.md "Where part of the footprint has no known back"). Needs the peel pass's planes:
     * a host's frame has none, and there it is off. */
    [P_PLANES] = {"planes", OB_PARAM_BOOL, 0.0f, 1.0f, 1.0f, "on/off",
                  "with layers=2, the back over a pixel's footprint follows the second layer's own plane "
                  "across an edge where the front steps to another surface (needs the peel pass's planes; "
                  "off in a host's frame)",
                  false},
    [P_EMITTER_COSINE] = {"emitter_cosine", OB_PARAM_BOOL, 0.0f, 1.0f, 0.0f, "on/off",
                          "a sender's radiance times its cosine toward P (the paper's); off: its radiance where it "
                          "faces P (the solid-angle form of the one-bounce integral)",
                          false},
    /* On: each AO texel's depth, normal and direct radiance packed into one texel by a pre-pass
     * (methods/packed.c), so a sample makes one fetch instead of three; the same bits
     * (tests/test_vbao.c). llvmpipe fetches a sender's normal and radiance for every sample (the
     * fresh-sector block is masked, not skipped): without those two fetches vbgi's pass at
     * 640x480 took 111-115 ms against 168-198. A GPU skips them where no lane of a group has a
     * fresh sector, so auto packs only on a software rasteriser; off is the baseline. Not with
     * depth_mips (the chain's levels are not packed). */
    [P_PACKED] = OB_PACKED_PARAM("; not with depth_mips"),
};

typedef struct vb_state {
    ob_method_kit kit;   /* the full-resolution program */
    GLuint variants[OB_SLICE_VARIANTS]; /* depth MIPs, second layer, packed: made on first use (ob_slice_use) */
    const char *shader;
    bool gi;
    ob_packed_samples packed; /* vbgi's `packed`: methods/packed.c, bound at OB_UNIT_PACKED_SAMPLES */
} vb_state;

/* Settings -> constants, a pure function. */
static void fill_constants(ob_vb_constants *c, const float *params, bool gi, const ob_slice_frame *sf)
{
    const float r = params[P_RADIUS];
    c->radius = r;
    c->thickness = params[P_THICKNESS] * r;
    c->thickness_slope = params[P_THICKNESS_SLOPE];
    c->layers = params[P_LAYERS] >= 2.0f ? 1 : 0;
    c->weighting = (int)params[P_WEIGHTING];
    c->slices = (int)params[P_SLICES];
    c->steps = (int)params[P_STEPS];
    c->noise = (int)params[P_NOISE];
    c->slice_offset = params[P_TEMPORAL] != 0.0f ? sf->slice_offset : 0.0f;
    c->step_offset = params[P_TEMPORAL] != 0.0f ? sf->step_offset : 0.0f;
    c->mip_scale = sf->mip_scale;
    c->max_mip = params[P_DEPTH_MIPS] != 0.0f ? sf->max_mip : 0;
    c->emitter_cosine = gi && params[P_EMITTER_COSINE] != 0.0f ? 1 : 0;
}

static ob_error vbao_init(void *p)
{
    vb_state *s = p;
    s->shader = "vbao.glsl";
    return OB_OK;
}

static ob_error vbgi_init(void *p)
{
    vb_state *s = p;
    s->shader = "vbgi.glsl";
    s->gi = true;
    return OB_OK;
}

static void vb_destroy(void *p)
{
    vb_state *s = p;
    ob_slice_release(s->variants);
    ob_packed_samples_release(&s->packed);
}

static uint32_t vb_active_reads(const float *params, uint32_t reads)
{
    if (params[P_DEPTH_MIPS] == 0.0f) reads &= ~(uint32_t)OB_READS_DEPTH_MIPS;
    if (params[P_LAYERS] < 2.0f)
        reads &= ~(uint32_t)(OB_READS_SECOND_LAYER | OB_READS_SECOND_BACK | OB_READS_SECOND_PLANES);
    if (params[P_PLANES] == 0.0f) reads &= ~(uint32_t)OB_READS_SECOND_PLANES;
    return reads;
}

static uint32_t vbao_active_reads(const float *params)
{
    return vb_active_reads(params, OB_READS_DEPTH | OB_READS_NORMALS | OB_READS_DEPTH_MIPS | OB_READS_SECOND_LAYER |
                                       OB_READS_SECOND_BACK | OB_READS_SECOND_PLANES);
}

static uint32_t vbgi_active_reads(const float *params)
{
    return vb_active_reads(params, OB_READS_DEPTH | OB_READS_NORMALS | OB_READS_RADIANCE | OB_READS_DEPTH_MIPS |
                                       OB_READS_SECOND_LAYER | OB_READS_SECOND_BACK | OB_READS_SECOND_PLANES);
}

static ob_error vb_run(void *p, const ob_ao_inputs *in, const float *params, const ob_ao_outputs *out)
{
    vb_state *s = p;
    if (s->gi && (!in->radiance || !out->bounce))
        return ob_set_error(OB_ERR_INVALID_ARGUMENT, "vbgi needs the renderer's direct light (ob_render_frame)");
    ob_vb_constants c = {0};
    const ob_slice_frame sf = ob_slice_frame_make(in);
    fill_constants(&c, params, s->gi, &sf);
    c.layers = c.layers && in->second_depth ? 1 : 0; /* ob_compute_ao has no second layer */
    const bool facets = params[P_FACETS] != 0.0f && in->facet_normal; /* a host's frame has none */
    /* Adaptive sample counts: the slices scale with the edge pass's multiplier. */
    ob_slice_adaptive(in, c.slices, &c.adaptive, &c.adaptive_base);
    const bool packed = s->gi && c.max_mip == 0 && ob_packed_samples_wanted(&s->packed, params[P_PACKED]);
    const unsigned features = (c.max_mip > 0 ? OB_SLICE_MIPS : 0u) | (c.layers ? OB_SLICE_LAYERS : 0u) |
                              (packed ? OB_SLICE_PACKED : 0u) | (facets ? OB_SLICE_FACETS : 0u) |
                              (unsigned)params[P_COVERAGE] << OB_SLICE_COVERAGE_SHIFT |
                              (unsigned)params[P_CONNECT] << OB_SLICE_CONNECT_SHIFT;
    if (packed) {
        ob_error err = ob_packed_samples_run(&s->packed, in, OB_UNIT_PACKED_SAMPLES);
        if (err != OB_OK) return err;
    }
    ob_error err = ob_slice_use(&s->kit, s->variants, s->shader, features, &c, sizeof c, in, out);
    if (err != OB_OK) return err;
    if (s->gi) {
        glBindTextureUnit(OB_UNIT_SLICE_RADIANCE, in->radiance);
        glBindImageTexture(OB_IMAGE_UNIT_BOUNCE, out->bounce, 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA16F);
    }
    ob_dispatch_2d(in->width, in->height, OB_VB_GROUP_X, OB_VB_GROUP_Y);
    return OB_OK;
}

static int vb_count_samples(const float *params) { return 2 * (int)params[P_SLICES] * (int)params[P_STEPS]; }
static int vb_count_rays(const float *params) { return 2 * (int)params[P_SLICES]; }

/* Every sample count marches the default's steps (6) and changes only its slices (12 = 1 x 6 ...
 * 64 -> 5 x 6): fewer steps read more open, fewer slices only noisier (docs/methods.md, "Presets
 * that keep their mean"). */
#define VB_PRESET_STEPS ((int)vb_params[P_STEPS].def)

static ob_error vbao_set_samples(float *params, uint32_t *params_set, int samples)
{
    return ob_slice_set_samples("vbao", params, params_set, samples, P_SLICES, P_STEPS, OB_VB_MAX_SLICES,
                                OB_VB_MAX_STEPS, VB_PRESET_STEPS);
}

static ob_error vbgi_set_samples(float *params, uint32_t *params_set, int samples)
{
    return ob_slice_set_samples("vbgi", params, params_set, samples, P_SLICES, P_STEPS, OB_VB_MAX_SLICES,
                                OB_VB_MAX_STEPS, VB_PRESET_STEPS);
}

/* The roles of vbao's table, which is vbgi's prefix; vbgi adds `packed`. No OB_ROLE_SAMPLES: the
 * count is 2 x slices x steps (set_samples, count_samples). */
#define VB_ROLE_ENTRIES                                                                                            \
    [OB_ROLE_RADIUS] = OB_ROLE_PARAM(P_RADIUS), [OB_ROLE_THICKNESS] = OB_ROLE_PARAM(P_THICKNESS),                  \
    [OB_ROLE_TEMPORAL] = OB_ROLE_PARAM(P_TEMPORAL), [OB_ROLE_LAYERS] = OB_ROLE_PARAM(P_LAYERS)

const ob_method_impl ob_method_vbao = {
    .info = {.name = "vbao",
             .description = "visibility-bitmask AO: gtao's slices with 32 sectors and a thickness per sample",
             .reference = "Therrien et al. 2023 §3.1-3.2",
             .param_count = P_EMITTER_COSINE,
             .params = vb_params},
    .shader = "vbao.glsl",
    .constants_size = sizeof(ob_vb_constants),
    .state_size = sizeof(vb_state),
    .reads = OB_READS_DEPTH | OB_READS_NORMALS | OB_READS_DEPTH_MIPS | OB_READS_SECOND_LAYER | OB_READS_SECOND_BACK |
             OB_READS_SECOND_PLANES,
    .writes = OB_WRITES_VISIBILITY,
    .init = vbao_init,
    .run = vb_run,
    .destroy = vb_destroy,
    .active_reads = vbao_active_reads,
    .set_samples = vbao_set_samples,
    .count_samples = vb_count_samples,
    .count_rays = vb_count_rays,
    .adapts = true,
    .roles = {VB_ROLE_ENTRIES},
};

const ob_method_impl ob_method_vbgi = {
    .info = {.name = "vbgi",
             .description = "visibility-bitmask AO + one indirect bounce gathered in the same march",
             .reference = "Therrien et al. 2023 §3.1-3.3",
             .param_count = P_COUNT,
             .params = vb_params},
    .shader = "vbgi.glsl",
    .constants_size = sizeof(ob_vb_constants),
    .state_size = sizeof(vb_state),
    .reads = OB_READS_DEPTH | OB_READS_NORMALS | OB_READS_RADIANCE | OB_READS_DEPTH_MIPS | OB_READS_SECOND_LAYER |
             OB_READS_SECOND_BACK | OB_READS_SECOND_PLANES,
    .writes = OB_WRITES_VISIBILITY | OB_WRITES_BOUNCE,
    .init = vbgi_init,
    .run = vb_run,
    .destroy = vb_destroy,
    .active_reads = vbgi_active_reads,
    .set_samples = vbgi_set_samples,
    .count_samples = vb_count_samples,
    .count_rays = vb_count_rays,
    .adapts = true,
    .roles = {VB_ROLE_ENTRIES, [OB_ROLE_PACKED] = OB_ROLE_PARAM(P_PACKED)},
};
