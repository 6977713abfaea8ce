/* `gtao`: ground-truth ambient occlusion (Jimenez, Wu, Pesce & Jarabo 2016, "Practical Realtime
 * Strategies for Accurate Indirect Occlusion"): per pixel N_slices screen directions; in each the
 * horizon is searched on both sides and the cosine-weighted visibility with the projected normal
 * integrated in closed form (eq. 10). It estimates AO_R itself: its radius is exactly the R of
 * the definition and nothing rescales it. Shader: shaders/gtao.glsl. */
#include <math.h>
#include <stdlib.h>

#include "base/error.h"
#include "gtao_params.h"
#include "methods/method.h"

enum {
    P_RADIUS, P_FALLOFF, P_THIN, P_THICKNESS, P_SLICES, P_STEPS, P_NOISE, P_TEMPORAL, P_DEPTH_MIPS, P_BENT_NORMALS,
    P_LAYERS, P_FACETS, P_COUNT
};

static const ob_param_info gtao_params[P_COUNT] = {
    [P_RADIUS] = {"radius", OB_PARAM_FLOAT, 1e-4f, 1e4f, 0.5f, "world",
                  "R of AO_R: occluders count within it; default: the scene's suggested radius", true},
    /* 0: the definition's hard cut at R. A fade trades a little bias for less noise where an
     * occluder sits right at R; see docs/methods.md for what it does to the error. */
    [P_FALLOFF] = {"falloff", OB_PARAM_FLOAT, 0.0f, 1.0f, 0.0f, "x radius",
                   "occluders fade out over the last falloff x R before R (0 = AO_R's hard cut-off)", false},
    /* 0: the definition (every occluder infinitely thick behind its surface). */
    [P_THIN] = {"thin", OB_PARAM_FLOAT, 0.0f, 8.0f, 0.0f, "x",
                "thin-occluder compensation: a sample's depth offset counts (1 + thin) times in its distance", false},
    /* How far behind its surface a sample beyond R is solid, x R (slice_march.glsl
     * ob_column_entry): the horizon's height field taken literally is infinitely thick and puts a
     * halo behind every silhouette, the definition's cut at the sample's own distance makes it
     * infinitely thin beyond R and misses the occluders the depth buffer hides (a fin's far face,
     * the riser behind a step). 0.1 had the lowest RMSE summed over the training views
     * (cornell:front, fzk-haus:stair at 320x240: 0.0964 at 0, 0.0953 at 0.1, 0.0968 at 0.25, 0.1022
     * at 0.5); docs/methods.md has the table and the views that checked it. */
    [P_THICKNESS] = {"thickness", OB_PARAM_FLOAT, 0.0f, 100.0f, 0.1f, "x radius",
                     "how far behind its surface a sample beyond R is solid: the part of it inside R occludes "
                     "(0 = only samples within R count)",
                     false},
    /* 3 slices x 6 steps x 2 sides = 36 taps, Belonogov 2018's "high": on the training views
     * (cornell:front, fzk-haus:stair at 320x240) the fewest steps whose bias stays within 0.015
     * (the horizon's maximum over sparse steps only errs toward open: 4 steps +0.019 and +0.012,
     * 6 steps +0.013 and +0.010 there); slices add noise, not bias, and the filter removes
     * noise. docs/methods.md has the table. */
    [P_SLICES] = {"slices", OB_PARAM_INT, 1.0f, (float)OB_GTAO_MAX_SLICES, 3.0f, "count",
                  "screen directions N_slices over [0, π), each searched on both sides", false},
    [P_STEPS] = {"steps", OB_PARAM_INT, 1.0f, (float)OB_GTAO_MAX_STEPS, 6.0f, "count",
                 "horizon-search steps on each side of a slice", false},
    [P_NOISE] = {"noise", OB_PARAM_ENUM, 0.0f, 1.0f, 0.0f, "",
                 "per-pixel slice and step jitter: 4x4 tile (a 4x4 filter averages it) or interleaved gradient noise",
                 false, ob_noise_options},
    /* Off: the same frame gives the same bytes (the tests and the report need that). */
    [P_TEMPORAL] = {"temporal", OB_PARAM_BOOL, 0.0f, 1.0f, 0.0f, "on/off",
                    "move the jitters along an R2 sequence with the frame index (for temporal accumulation)", false},
    [P_DEPTH_MIPS] = {"depth_mips", OB_PARAM_BOOL, 0.0f, 1.0f, 0.0f, "on/off",
                      "far steps read the prefiltered depth MIP chain (SAO's trick) instead of full resolution", false},
    /* Off: the constant ambient does not depend on direction, so the default frame needs none. */
    [P_BENT_NORMALS] = {"bent_normals", OB_PARAM_BOOL, 0.0f, 1.0f, 0.0f, "on/off",
                        "also write the bent normal (the visible cone's mean direction) for compose's ambient lookup",
                        false},
    /* 1: the definition's height field. 2: a sample raises the horizon only where the current
     * horizon ray passes through the object under it, not behind its second layer (gtao.glsl);
     * measured worse than 1 on every view tried (docs/methods.md), so 1 stays the default. */
    [P_LAYERS] = OB_LAYERS_PARAM,
    /* As vbao's (methods/vbao.c, off by default for the same reason): each side's horizon starts at
     * the plane of P's own triangle where that rises above the tangent; a host's frame has no facet
     * normals, and there it is off. */
    [P_FACETS] = {"facets", OB_PARAM_BOOL, 0.0f, 1.0f, 0.0f, "on/off",
                  "each side's horizon starts at the pixel's own triangle where it rises above the interpolated "
                  "normal's tangent plane (needs the G-buffer's facet normals; off in a host's frame)",
                  false},
};

typedef struct gtao_state {
    ob_method_kit kit;                    /* the default program (shaders/gtao.glsl as it is) */
    GLuint variants[OB_SLICE_VARIANTS];   /* depth MIPs, second layer, bent normal: made on first use */
} gtao_state;

/* Settings -> constants, a pure function: the falloff as weight = clamp(r mul + add, 0, 1), 1
 * up to (1 - f) R and 0 from R on; f = 0 is the step at R. */
static void fill_constants(ob_gtao_constants *c, const float *params, const ob_slice_frame *sf)
{
    const float r = params[P_RADIUS], f = params[P_FALLOFF];
    c->radius = r;
    if (f > 0.0f) {
        c->falloff_mul = -1.0f / (f * r);
        c->falloff_add = 1.0f / f; /* (R - dist) / (f R) */
    } else {
        /* A step at R: (R - dist) x 1e20 clamps to 1 below R and to 0 from R on, without
         * dividing by zero (R <= 1e4, so nothing overflows). */
        c->falloff_mul = -1e20f;
        c->falloff_add = 1e20f * r;
    }
    c->thin = params[P_THIN];
    c->column = params[P_THICKNESS] * r;
    c->full_reach = (1.0f - f) * r;
    c->column_shell2 = (c->full_reach + c->column) * (c->full_reach + c->column);
    c->slices = (int)params[P_SLICES];
    c->steps = (int)params[P_STEPS];
    c->noise = (int)params[P_NOISE];
    c->depth_mips = params[P_DEPTH_MIPS] != 0.0f && sf->max_mip > 0 ? 1 : 0;
    c->slice_offset = params[P_TEMPORAL] != 0.0f ? sf->slice_offset : 0.0f;
    c->step_offset = params[P_TEMPORAL] != 0.0f ? sf->step_offset : 0.0f;
    c->mip_scale = sf->mip_scale;
    c->max_mip = c->depth_mips ? sf->max_mip : 0; /* level 0 only: the unit holds the depth itself */
    c->bent_normals = params[P_BENT_NORMALS] != 0.0f ? 1 : 0;
    c->layers = params[P_LAYERS] >= 2.0f ? 1 : 0;
}

/* The depth MIP chain only when asked for: the full-resolution path stays the baseline. */
static uint32_t gtao_active_reads(const float *params)
{
    return OB_READS_DEPTH | OB_READS_NORMALS | (params[P_DEPTH_MIPS] != 0.0f ? OB_READS_DEPTH_MIPS : 0u) |
           (params[P_LAYERS] >= 2.0f ? OB_READS_SECOND_LAYER : 0u);
}

/* The bent normal only when asked for. */
static uint32_t gtao_active_writes(const float *params)
{
    return OB_WRITES_VISIBILITY | (params[P_BENT_NORMALS] != 0.0f ? OB_WRITES_BENT_NORMAL : 0u);
}

static ob_error gtao_run(void *p, const ob_ao_inputs *in, const float *params, const ob_ao_outputs *out)
{
    gtao_state *s = p;
    ob_gtao_constants c = {0};
    const ob_slice_frame sf = ob_slice_frame_make(in);
    fill_constants(&c, params, &sf);
    c.layers = c.layers && in->second_depth ? 1 : 0; /* ob_compute_ao has no second layer */
    const bool facets = params[P_FACETS] != 0.0f && in->facet_normal; /* a host's frame has none */
    c.bent_normals = c.bent_normals && out->bent_normal ? 1 : 0;
    /* Adaptive sample counts: the slices scale with the edge pass's multiplier. */
    ob_slice_adaptive(in, c.slices, &c.adaptive, &c.adaptive_base);
    const unsigned features = (c.depth_mips ? OB_SLICE_MIPS : 0u) | (c.layers ? OB_SLICE_LAYERS : 0u) |
                              (c.bent_normals ? OB_SLICE_BENT : 0u) | (facets ? OB_SLICE_FACETS : 0u);
    ob_error err = ob_slice_use(&s->kit, s->variants, "gtao.glsl", features, &c, sizeof c, in, out);
    if (err != OB_OK) return err;
    if (c.bent_normals)
        glBindImageTexture(OB_IMAGE_UNIT_BENT_NORMAL, out->bent_normal, 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA16F);
    ob_dispatch_2d(in->width, in->height, OB_GTAO_GROUP_X, OB_GTAO_GROUP_Y);
    return OB_OK;
}

static void gtao_destroy(void *p)
{
    gtao_state *s = p;
    ob_slice_release(s->variants);
}

static int gtao_count_samples(const float *params) { return 2 * (int)params[P_SLICES] * (int)params[P_STEPS]; }
static int gtao_count_rays(const float *params) { return 2 * (int)params[P_SLICES]; }

/* Belonogov 2018's quality levels as slices x steps: ob_slice_set_samples. */
static ob_error gtao_set_samples(float *params, uint32_t *params_set, int samples)
{
    return ob_slice_set_samples("gtao", params, params_set, samples, P_SLICES, P_STEPS, OB_GTAO_MAX_SLICES,
                                OB_GTAO_MAX_STEPS, 0);
}

const ob_method_impl ob_method_gtao = {
    .info = {.name = "gtao",
             .description = "ground-truth AO: slices x horizon search, cosine-weighted visibility in closed form",
             .reference = "Jimenez et al. 2016 eq. 3-10; XeGTAO",
             .param_count = P_COUNT,
             .params = gtao_params},
    .shader = "gtao.glsl",
    .constants_size = sizeof(ob_gtao_constants),
    .state_size = sizeof(gtao_state),
    .reads = OB_READS_DEPTH | OB_READS_NORMALS | OB_READS_DEPTH_MIPS | OB_READS_SECOND_LAYER,
    .writes = OB_WRITES_VISIBILITY | OB_WRITES_BENT_NORMAL,
    .run = gtao_run,
    .destroy = gtao_destroy,
    .active_reads = gtao_active_reads,
    .active_writes = gtao_active_writes,
    .set_samples = gtao_set_samples,
    .count_samples = gtao_count_samples,
    .count_rays = gtao_count_rays,
    .adapts = true,
    /* No OB_ROLE_SAMPLES: the count is 2 x slices x steps (set_samples, count_samples). */
    .roles = {[OB_ROLE_RADIUS] = OB_ROLE_PARAM(P_RADIUS), [OB_ROLE_FALLOFF] = OB_ROLE_PARAM(P_FALLOFF),
              [OB_ROLE_THICKNESS] = OB_ROLE_PARAM(P_THICKNESS), [OB_ROLE_TEMPORAL] = OB_ROLE_PARAM(P_TEMPORAL),
              [OB_ROLE_BENT_NORMALS] = OB_ROLE_PARAM(P_BENT_NORMALS), [OB_ROLE_LAYERS] = OB_ROLE_PARAM(P_LAYERS)},
};
