/* `crease`: the crease-preserving denoiser (issue 13). A centred (2r+1)^2 window with the
 * half-weight rim that covers the 4x4 rotation tile exactly (shaders/crease.glsl eq. 1), weighted
 * by the distance from the receiver's tangent plane relative to depth (eq. 2) and the angle between
 * normals (eq. 3), each offset paired with its mirror (eq. 4) so that a window cut off by a wall
 * or a silhouette stays centred on the pixel. It removes the methods' per-pixel noise where
 * `geometry`'s 11x11 Gaussian along the floor also averaged the crease with the brighter floor
 * beside it (issue 13: ssao 0.68 -> 0.92 at the corner crease, hbao's RMSE up on every view).
 * The pairing is what keeps the crease: on corner:diagonal at 320x240 the floor pixels within
 * 0.05 R of a wall change by -0.004 (ssao), +0.001 (hbao), -0.001 (alchemy) against the raw AO;
 * the same window without it brightens them by +0.19 / +0.10 / +0.10, as much as box4.
 * Shader: shaders/crease.glsl. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "base/error.h"
#include "filters/filter.h"

enum { P_RADIUS, P_SIGMA_PLANE, P_SIGMA_NORMAL, P_TILED, P_COUNT };

#define OB_DEG_TO_RAD 0.017453292519943295f

static const char *const tiled_options[] = {"off", "on", "auto", "block"};
enum { TILED_OFF, TILED_ON, TILED_AUTO, TILED_BLOCK }; /* tiled_options' indices */

static const ob_param_info crease_params[P_COUNT] = {
    /* 2: the window [1/2 1 1 1 1/2]^2 gives every pixel of a 4x4 noise tile the same total
     * weight (eq. 1), so the seeds' rotation noise cancels as under box4; an even r covers whole
     * tiles too (4: two per side), an odd one does not. Measured (compare, 320x240, docs/filters.md):
     * r = 4 lowers ssao/hbao's RMSE a little more on cornell:front and fzk-haus:stair (-0.001 to
     * -0.005) but raises alchemy's (+0.001 to +0.003) and the curved models' (spider, Wuson) and
     * costs 80 taps instead of 24; what is left after the tile cancels is signal, not noise. */
    [P_RADIUS] = {"radius", OB_PARAM_INT, 1.0f, (float)OB_FILTER_MAX_RADIUS, 2.0f, "px",
                  "window half-width; the rim taps weigh 1/2, so 2r px are covered per axis (2 = one 4x4 noise tile)",
                  false},
    /* 0.005 of depth: 5 mm at 1 m, about one pixel's footprint at 320x240 and 60 deg (2 tan 30 /
     * 240 = 0.0048), so a stair tread, a door frame or a box face parallel to the one behind it is
     * off the plane, while p's own plane, which gives x = 0 at any distance and viewing angle, is
     * not cut up. Relative to depth, it works in metres and millimetres. On fzk-haus:stair RMSE is
     * flat from 0.001 to 0.005 and grows from 0.0075 (ssao 0.0975 at 0.005, 0.0986 at 0.01, hbao
     * 0.1022 / 0.1030); cornell:front does not move (its planes meet at right angles: eq. 3 does
     * the work there). */
    [P_SIGMA_PLANE] = {"sigma_plane", OB_PARAM_FLOAT, 0.0001f, 1.0f, 0.005f, "x depth",
                       "standard deviation on the distance from the receiver's tangent plane, |n_p . (P_q - P_p)| / d_p",
                       false},
    /* 20 deg, as `geometry`: a 90 deg crease weighs exp(-0.5 (90/20)^2) = 4e-5 and a 45 deg bevel
     * 0.08, while the few degrees between neighbours on a tessellated curved surface cost almost
     * nothing. 5-20 measure the same on cornell and fzk-haus; 30 and more only help alchemy, by
     * letting its (too dark) creases brighten from the other face, and cost hbao on the bunny. */
    [P_SIGMA_NORMAL] = {"sigma_normal", OB_PARAM_FLOAT, 1.0f, 90.0f, 20.0f, "degrees",
                        "standard deviation on the angle between normals", false},
    /* on: the work group's window in shared memory, each texel rebuilt once (crease.glsl's tiled
     * program); off: the plain program, the baseline the others are measured against; block: each
     * invocation filters 4x4 pixels from one 8x8 window in registers (radius 2, the default). Radii
     * above OB_CREASE_TILE_RADIUS take the plain program, other radii than 2 take `on` for block.
     * auto: block on a software rasteriser, plain on a GPU, as measured in one bench run each
     * (1280x720 on llvmpipe, 2 cores, after gtao: block 25 ms, tiled 98-102, plain 144-151, gaussian 28;
     * 1920x1080 on an H100: plain 0.089 ms, tiled 0.140, block not measured yet; docs/filters.md).
     * The values keep their old indices. */
    [P_TILED] = {"tiled", OB_PARAM_ENUM, 0.0f, 3.0f, 2.0f, "",
                 "how the window is read: on (shared-memory tiles), off (the plain program, every tap fetched "
                 "and rebuilt per pixel), block (4x4 pixels per invocation, radius 2), or auto (block on a "
                 "software rasteriser, off on a GPU)",
                 false, tiled_options},
};

/* The three programs, each compiled at its first use (a GPU's auto never compiles the block
 * program, llvmpipe's never the tiled one), so a frame can switch between them. The block program
 * has an orthographic twin (crease.glsl OB_ORTHOGRAPHIC: its plane distance is unrolled from the
 * perspective reconstruction); the other two rebuild view positions with the frame's own camera. */
typedef struct crease_state {
    ob_compute_pass plain, tiled, block, block_ortho;
    bool rgb;      /* the RGBA16F variant (SSDO's M and bounce) */
    bool software; /* the context is a software rasteriser: what `tiled` auto follows */
} crease_state;

void ob_crease_constants_init(ob_filter_constants *c, const ob_filter_inputs *in, int radius, float sigma_plane,
                              float sigma_normal)
{
    /* The range falloffs as the Gaussian family's (-1/(2 sigma^2)); depth_falloff carries the plane
     * term: a relative depth difference measured along n_p instead of along the view ray. The
     * spatial weights are then replaced by eq. 1's. */
    ob_filter_constants_init(c, in, radius, 1.0f, sigma_plane, sigma_normal);
    for (int i = 0; i <= OB_FILTER_MAX_RADIUS; ++i) c->weights[i][0] = 0.0f;
    for (int i = 0; i < c->radius; ++i) c->weights[i][0] = 1.0f;
    c->weights[c->radius][0] = c->radius > 0 ? 0.5f : 1.0f;
}

static void crease_destroy(void *state)
{
    crease_state *s = state;
    if (!s) return;
    ob_compute_pass_destroy(&s->plain);
    ob_compute_pass_destroy(&s->tiled);
    ob_compute_pass_destroy(&s->block);
    ob_compute_pass_destroy(&s->block_ortho);
    free(s);
}

static void *make_state(bool rgb)
{
    crease_state *s = calloc(1, sizeof *s);
    if (!s) {
        ob_set_error(OB_ERR_OUT_OF_MEMORY, "out of memory (crease.glsl)");
        return NULL;
    }
    s->rgb = rgb;
    s->software = ob_renderer_is_software((const char *)glGetString(GL_RENDERER));
    return s;
}

/* The program for `mode` (TILED_OFF, TILED_ON or TILED_BLOCK; `ortho`: the frame's camera is
 * orthographic), compiled now if this is its first use; NULL + ob_set_error when it does not
 * compile. */
static ob_compute_pass *program_for(crease_state *s, int mode, bool ortho)
{
    const bool block_ortho = mode == TILED_BLOCK && ortho;
    ob_compute_pass *p = block_ortho           ? &s->block_ortho
                         : mode == TILED_BLOCK ? &s->block
                         : mode == TILED_ON    ? &s->tiled
                                               : &s->plain;
    if (p->program) return p;
    char defines[128];
    snprintf(defines, sizeof defines, "%s%s%s", s->rgb ? "#define OB_FILTER_RGB 1\n" : "",
             mode == TILED_BLOCK ? "#define OB_CREASE_BLOCK 1\n" : mode == TILED_ON ? "#define OB_CREASE_TILED 1\n" : "",
             block_ortho ? "#define OB_ORTHOGRAPHIC 1\n" : "");
    return ob_compute_pass_init(p, "crease.glsl", defines, sizeof(ob_filter_constants)) == OB_OK ? p : NULL;
}

static void *crease_init(void) { return make_state(false); }
static void *crease_init_rgb(void) { return make_state(true); }

static ob_error crease_run(void *state, const ob_filter_inputs *in, const float *params)
{
    crease_state *s = state;
    ob_filter_constants c;
    ob_crease_constants_init(&c, in, (int)params[P_RADIUS], params[P_SIGMA_PLANE],
                             params[P_SIGMA_NORMAL] * OB_DEG_TO_RAD);
    int mode = (int)params[P_TILED];
    if (mode == TILED_AUTO) mode = s->software ? TILED_BLOCK : TILED_OFF;
    if (mode == TILED_BLOCK && c.radius != 2) mode = TILED_ON; /* the block program is unrolled for r = 2 */
    if (mode == TILED_ON && c.radius > OB_CREASE_TILE_RADIUS) mode = TILED_OFF;
    if (mode != TILED_OFF) {
        /* The tiled and block programs take exp2: the same exponents times log2(e). */
        c.depth_falloff *= 1.4426950408889634f;
        c.normal_falloff *= 1.4426950408889634f;
    }
    /* One pass: the view positions come from the frame's block at OB_BINDING_FRAME, which the
     * renderer binds for every pass of the frame (and ob_compute_ao_filtered for its own). */
    ob_compute_pass *p = program_for(s, mode, in->orthographic);
    if (!p) return ob_peek_error(NULL);
    if (mode == TILED_BLOCK)
        ob_filter_run_blocks(p, &c, ob_filter_constants_used(&c), in, 4); /* crease.glsl's BLOCK */
    else
        ob_filter_run_single(p, &c, ob_filter_constants_used(&c), in);
    return OB_OK;
}

const ob_filter_impl ob_filter_crease = {
    .info = {.name = "crease",
             .description = "5x5 plane + normal weighted, mirror-paired: removes the 4x4 noise, keeps creases",
             .reference = "issue 13; Puri 2024 §3.3 (the 4x4 tile); SSDO thesis §3.5 (range weights)",
             .param_count = P_COUNT,
             .params = crease_params},
    .init = crease_init,
    .run = crease_run,
    .destroy = crease_destroy,
    .init_rgb = crease_init_rgb,
};
