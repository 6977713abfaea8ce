/* Temporal accumulation (issue 17): the reprojection cache of Nehab et al. 2007 with Karis 2014's
 * neighbourhood clamp, at the AO resolution. Shader: shaders/temporal.glsl (it says what each step
 * does and what moving objects would need); the frame's use of it: src/core/frame.c. */
#include <cglm/cglm.h>
#include <stdio.h>
#include <string.h>

#include "base/error.h"
#include "passes/passes.h"

/* A history tap is this point's surface when it lies within 1 % of the depth from this point's
 * tangent plane: on a plane the distance is 0 at any angle, so the only error it must absorb is
 * depth's (R32F, exact here) and a curved surface's bulge over a pixel; a step of an object in
 * front (the disocclusion to catch) is far more than 1 % of the depth at any of the test scenes'
 * scales. */
#define PLANE_TOLERANCE 0.01f
/* ... and its normal within 25 degrees (cos 25 = 0.906), the edge pass's turn (edges.c): more
 * than the normals of a tessellated curve turn in one pixel, less than any crease. */
#define NORMAL_COS 0.906f
/* The history's trust halves, per frame, when the point's pixel footprint changes by 1/6: the
 * screen-space methods march or scatter their samples over R's projection, and gtao's and vbao's
 * default 6 steps per side move by a whole step's spacing at the far end of the march when R's
 * projection changes by 1/6 of itself, so from there the samples land on other texels and the
 * estimate is another one. 1 / log2(1 + 1/6) = 4.50 (docs/temporal.md, "Footprint"). */
#define FOOTPRINT_FALLOFF 4.50f

void ob_temporal_fill(ob_temporal_constants *c, const float prev_view[16], const float inv_view[16],
                      const float prev_ao_proj[16], bool history_valid, int history_frames, float detail)
{
    memset(c, 0, sizeof *c);
    /* One matrix from this view to the previous one instead of two through world space: on
     * llvmpipe the two matrices and their products were a tenth of the shader's instructions
     * (bench/results/2026-11-23-llvmpipe-instructions.md), and the product skips world
     * coordinates, which lose bits far from the origin. */
    mat4 prev, inv, to_prev;
    memcpy(prev, prev_view, sizeof prev);
    memcpy(inv, inv_view, sizeof inv);
    glm_mat4_mul(prev, inv, to_prev);
    memcpy(c->to_prev_view, to_prev, sizeof c->to_prev_view);
    memcpy(c->prev_ao_proj, prev_ao_proj, sizeof c->prev_ao_proj);
    /* 1/P00, 1/P11, P20, P21 (column-major; -P30, -P31 orthographic), as common.glsl's
     * ob_view_position takes them. */
    ob_proj_info(prev_ao_proj, c->prev_ao_proj_info);
    c->history_valid = history_valid ? 1 : 0;
    c->history_frames = (float)(history_frames > 0 ? history_frames : 1);
    c->plane_tolerance = PLANE_TOLERANCE;
    c->normal_cos = NORMAL_COS;
    c->footprint_falloff = FOOTPRINT_FALLOFF;
    c->detail = detail;
}

void ob_temporal_set_motion(ob_temporal_constants *c, GLuint motion, const float scale[2])
{
    c->has_motion = motion != 0;
    c->motion_scale[0] = scale && scale[0] != 0.0f ? scale[0] : 1.0f;
    c->motion_scale[1] = scale && scale[1] != 0.0f ? scale[1] : 1.0f;
}

ob_error ob_temporal_init(ob_temporal_pass *p)
{
    memset(p, 0, sizeof *p);
    return OB_OK;
}

ob_error ob_temporal_run(ob_temporal_pass *p, const ob_temporal_constants *c, const ob_ao_grid *g, GLuint depth,
                         GLuint normal, const ob_temporal_geometry *prev, const ob_temporal_geometry *next,
                         const ob_temporal_chain *chain)
{
    /* Compile-time shapes, not uniform tests: llvmpipe runs a uniformly false branch masked, so a
     * store behind one still costs its store. Without a result image, the program that has none;
     * a method's bounce rides in the same dispatch (its own second dispatch redid the
     * reprojection, the tap tests and the geometry store). */
    static const char *const shapes[3] = {"", "#define OB_TEMPORAL_NO_RESULT 1\n", "#define OB_TEMPORAL_RGB 1\n"};
    const int shape = chain->rgb ? 2 : chain->result ? 0 : 1;
    const bool bounce = chain->bounce_current != 0;
    const bool motion = chain->host_motion != 0;
    const int k = shape + (bounce ? 3 : 0) + (motion ? 6 : 0) + (chain->jittered ? 12 : 0);
    if (!p->programs[k].program) {
        char defines[256];
        snprintf(defines, sizeof defines, "%s%s%s%s", shapes[shape], bounce ? "#define OB_TEMPORAL_BOUNCE 1\n" : "",
                 motion ? "#define OB_TEMPORAL_HOST_MOTION 1\n" : "",
                 chain->jittered ? "#define OB_TEMPORAL_JITTER 1\n" : "");
        if (ob_compute_pass_init(&p->programs[k], "temporal.glsl", defines, sizeof(ob_temporal_constants)) != OB_OK)
            return ob_peek_error(NULL);
    }
    ob_compute_pass_use(&p->programs[k], c, sizeof *c);
    p->last = *c;
    const struct {
        GLuint unit, texture;
    } units[] = {{OB_UNIT_TEMPORAL_CURRENT, chain->current},
                 {OB_UNIT_TEMPORAL_HISTORY, chain->history},
                 {OB_UNIT_TEMPORAL_DEPTH, depth},
                 {OB_UNIT_TEMPORAL_NORMAL, normal},
                 {OB_UNIT_TEMPORAL_PREV_DEPTH, prev->depth},
                 {OB_UNIT_TEMPORAL_BOUNCE_CURRENT, chain->bounce_current},
                 {OB_UNIT_TEMPORAL_BOUNCE_HISTORY, chain->bounce_history},
                 {OB_UNIT_TEMPORAL_HISTORY_AGE, chain->age},
                 {OB_UNIT_TEMPORAL_PREV_NORMAL, prev->normal},
                 {OB_UNIT_TEMPORAL_HOST_MOTION, chain->host_motion}};
    for (size_t i = 0; i < sizeof units / sizeof units[0]; ++i)
        if (units[i].texture) glBindTextureUnit(units[i].unit, units[i].texture);
    glBindImageTexture(OB_IMAGE_UNIT_TEMPORAL_NEXT_DEPTH, next->depth, 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_R32F);
    glBindImageTexture(OB_IMAGE_UNIT_TEMPORAL_NEXT_NORMAL, next->normal, 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_R32UI);
    if (chain->result)
        glBindImageTexture(OB_IMAGE_UNIT_TEMPORAL_RESULT, chain->result, 0, GL_FALSE, 0, GL_WRITE_ONLY,
                           chain->rgb ? GL_RGBA16F : GL_R32F);
    glBindImageTexture(OB_IMAGE_UNIT_TEMPORAL_NEXT_HISTORY, chain->next_history, 0, GL_FALSE, 0, GL_WRITE_ONLY,
                       chain->rgb ? GL_RGBA16F : GL_R32F);
    if (!chain->rgb)
        glBindImageTexture(OB_IMAGE_UNIT_TEMPORAL_NEXT_AGE, chain->next_age, 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_R16F);
    if (bounce) {
        glBindImageTexture(OB_IMAGE_UNIT_TEMPORAL_BOUNCE_RESULT, chain->bounce_result, 0, GL_FALSE, 0, GL_WRITE_ONLY,
                           GL_RGBA16F);
        glBindImageTexture(OB_IMAGE_UNIT_TEMPORAL_BOUNCE_NEXT_HISTORY, chain->bounce_next_history, 0, GL_FALSE, 0,
                           GL_WRITE_ONLY, GL_RGBA16F);
    }
    ob_dispatch_2d(g->width, g->height, OB_TEMPORAL_GROUP_X, OB_TEMPORAL_GROUP_Y);
    return OB_OK;
}

ob_error ob_temporal_motion(ob_temporal_pass *p, const ob_ao_grid *g, GLuint depth, GLuint motion)
{
    if (!p->motion_program.program &&
        ob_compute_pass_init(&p->motion_program, "temporal.glsl", "#define OB_TEMPORAL_MOTION 1\n",
                             sizeof(ob_temporal_constants)) != OB_OK)
        return ob_peek_error(NULL);
    /* The camera's reprojection alone: the read-back shows what the frame's own depth says. */
    ob_compute_pass_use(&p->motion_program, &p->last, sizeof p->last);
    glBindTextureUnit(OB_UNIT_TEMPORAL_DEPTH, depth);
    glBindImageTexture(OB_IMAGE_UNIT_TEMPORAL_MOTION, motion, 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RG16F);
    ob_dispatch_2d(g->width, g->height, OB_TEMPORAL_GROUP_X, OB_TEMPORAL_GROUP_Y);
    return OB_OK;
}

void ob_temporal_destroy(ob_temporal_pass *p)
{
    for (int k = 0; k < OB_TEMPORAL_PROGRAMS; ++k) ob_compute_pass_destroy(&p->programs[k]);
    ob_compute_pass_destroy(&p->motion_program);
}
