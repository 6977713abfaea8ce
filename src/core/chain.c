/* The AO chain, the one code both front doors run (docs/architecture.md "The frame"): ob_render_frame on the
 * renderer's own G-buffer and ob_host_ao on an engine's textures.
 *   [downsample to the AO grid] -> [edges] -> [depth MIPs] -> method -> [temporal accumulation,
 *   before or after the filter] -> filter -> [joint bilateral upsample]
 * It reads linear depth and view normals at the enlarged size (chain_io) and writes the visibility
 * (or M), the bounce and the bent normal at that size; each pass is timed. The method is resolved
 * once per frame into a plan; the chain knows no method by name, only what the registry entry
 * declares it reads, writes and which parameters play which role (method.h, ob_param_role). */
#include <math.h>
#include <string.h>

#include "base/error.h"
#include "core/renderer.h"

void ob_upload_frame(ob_renderer *r)
{
    glNamedBufferSubData(r->frame_ubo, 0, sizeof r->frame_constants, &r->frame_constants);
    glBindBufferBase(GL_UNIFORM_BUFFER, OB_BINDING_FRAME, r->frame_ubo);
}

int ob_scale_index(int divisor) { return divisor == 2 ? 1 : divisor == 4 ? 2 : 0; }

ob_error ob_check_settings(const ob_settings *s)
{
    if (!s || !ob_method_at(s->method) || !ob_filter_at(s->filter))
        return ob_set_error(OB_ERR_INVALID_ARGUMENT, "settings are not initialised");
    if (s->ao_divisor != 0 && s->ao_divisor != 1 && s->ao_divisor != 2 && s->ao_divisor != 4)
        return ob_set_error(OB_ERR_OUT_OF_RANGE, "ao divisor %d is not 1, 2 or 4", s->ao_divisor);
    if (s->guard < 0 || s->guard > OB_GUARD_MAX)
        return ob_set_error(OB_ERR_OUT_OF_RANGE, "guard band %d px is outside 0..%d", s->guard, OB_GUARD_MAX);
    if (s->temporal_at != OB_TEMPORAL_BEFORE_FILTER && s->temporal_at != OB_TEMPORAL_AFTER_FILTER)
        return ob_set_error(OB_ERR_OUT_OF_RANGE, "temporal_at %d is not before (0) or after (1) the filter", s->temporal_at);
    if (s->jitter < 0 || s->jitter > OB_JITTER_POSITIONS_MAX)
        return ob_set_error(OB_ERR_OUT_OF_RANGE, "jitter %d is outside 0..%d (positions)", s->jitter,
                            OB_JITTER_POSITIONS_MAX);
    if (s->temporal_frames < 0 || s->temporal_frames > OB_TEMPORAL_FRAMES_MAX)
        return ob_set_error(OB_ERR_OUT_OF_RANGE, "temporal_frames %d is outside 1..%d", s->temporal_frames,
                            OB_TEMPORAL_FRAMES_MAX);
    if (!(s->temporal_detail >= 0.0f && s->temporal_detail < 1.0f))
        return ob_set_error(OB_ERR_OUT_OF_RANGE, "temporal_detail %g is outside [0, 1)", (double)s->temporal_detail);
    return OB_OK;
}

ob_error ob_plan_method(ob_renderer *r, const ob_settings *s, float scene_radius, ob_method_plan *p)
{
    memset(p, 0, sizeof *p);
    p->index = s->method;
    p->impl = ob_method_impl_at(s->method);
    const ob_method_info *m = &p->impl->info;
    /* radius_scale (0 in a zero-filled ob_settings = 1) widens or narrows the search, not R. */
    float scale = s->radius_scale > 0.0f ? s->radius_scale : 1.0f;
    for (int i = 0; i < m->param_count; ++i) {
        p->params[i] = s->params[i];
        if (m->params[i].follows_scene_radius && !(s->params_set & (1u << i)) && scene_radius > 0.0f)
            p->params[i] = scene_radius;
        if (m->params[i].follows_scene_radius)
            p->params[i] = fminf(fmaxf(p->params[i] * scale, m->params[i].min), m->params[i].max);
    }
    /* Temporal accumulation wants noise that moves with the frame index: the method's temporal
     * switch (gtao, vbao, vbgi: R2 jitters), as its table declares it, goes on unless it was set
     * explicitly. */
    const int temporal = ob_method_role(p->impl, OB_ROLE_TEMPORAL);
    if (s->temporal && temporal >= 0 && !(s->params_set & (1u << temporal))) p->params[temporal] = 1.0f;
    p->reads = ob_method_active_reads(p->impl, p->params);
    p->writes = ob_method_active_writes(p->impl, p->params);
    p->rgb = (p->impl->writes & OB_WRITES_VISIBILITY_RGB) != 0;
    p->bounce = (p->writes & OB_WRITES_BOUNCE) != 0;
    p->bent = (p->writes & OB_WRITES_BENT_NORMAL) != 0;
    ob_error err = OB_OK;
    p->state = ob_renderer_method_state(r, s->method, &err);
    return err;
}

/* The prefiltered MIP chain of an AO grid's depth (SAO's trick; passes/depth_mips.c), one dispatch,
 * for a method that reads it (OB_READS_DEPTH_MIPS). */
static ob_error make_depth_mips(ob_renderer *r, GLuint depth, int width, int height, GLuint *mips, int *levels)
{
    if (!r->depth_mips.pass.program && ob_depth_mips_init(&r->depth_mips) != OB_OK) return ob_peek_error(NULL);
    ob_error err = ob_depth_mips_run(&r->depth_mips, depth, width, height);
    if (err != OB_OK) return err;
    *mips = r->depth_mips.texture;
    *levels = r->depth_mips.levels;
    return OB_OK;
}

/* The second layer over each pixel's footprint (passes/second_back.c) from the frame's full-resolution
 * depth and *second (the peel pass's or a host's), into *second. */
static ob_error make_second_back(ob_renderer *r, const ob_chain_io *io, bool planes_wanted, GLuint *second)
{
    if (!r->second_back.pass.program && ob_second_back_init(&r->second_back) != OB_OK) return ob_peek_error(NULL);
    ob_second_back_planes planes = {.front = planes_wanted ? io->facet : 0,
                                    .back = planes_wanted ? io->second_plane : 0,
                                    .orthographic = r->frame_constants.orthographic};
    memcpy(planes.proj_info, r->frame_constants.proj_info, sizeof planes.proj_info);
    ob_error err = ob_second_back_run(&r->second_back, io->depth, *second, &planes);
    if (err == OB_OK) *second = r->second_back.texture;
    return err;
}

/* Filter one chain (src -> dst through the scratch target) at the AO resolution, guided by the AO
 * grid's depth and normals. */
static ob_error run_filter(const ob_renderer *r, const ob_filter_impl *filter, void *fstate, const ao_targets *t,
                           const GLuint guide[2], GLuint src, GLuint dst, GLuint scratch, bool rgb, float sky,
                           const ob_settings *s)
{
    const ob_filter_inputs fin = {.src = src, .dst = dst, .scratch = scratch, .linear_depth = guide[0],
                                  .view_normal = guide[1], .width = t->grid.width, .height = t->grid.height,
                                  .rgb = rgb, .sky = sky, .orthographic = r->frame_constants.orthographic != 0};
    return filter->run(fstate, &fin, s->filter_params);
}

/* The frame's G-buffer is jittered (ob_settings.jitter, ob_host_frame.jitter): its projection is
 * not the unjittered one. */
static bool frame_jittered(const ob_renderer *r)
{
    return memcmp(r->frame_constants.ao_proj, r->ao_proj_unjittered, sizeof r->ao_proj_unjittered) != 0;
}

/* Where the accumulation runs: temporal_at, but after the filter while the G-buffer is jittered
 * (this frame or the last accumulated one). The edge-aware filter weighs each pixel by this frame's
 * sample in it, which under a jitter is another surface from frame to frame at every edge; a
 * history that already holds the footprint's mean of both surfaces, filtered with one frame's
 * weights, is pulled toward that frame's surface. On `grille` (test_temporal) a still jittered
 * camera accumulated before the filter ends 0.035 RMS from the footprint's mean AO, after it
 * 0.012 (docs/temporal.md, "Jitter"). */
static int temporal_at(const ob_renderer *r, const ob_settings *s)
{
    const bool jittered = frame_jittered(r) || (r->history_valid && r->prev_jittered);
    return jittered ? OB_TEMPORAL_AFTER_FILTER : s->temporal_at;
}

/* Temporal accumulation of the main chain (visibility or M) and the bounce: `*_in` this frame's
 * values, `*_out` where the accumulation goes (passes/temporal.c). The history is reused only when
 * the last frame accumulated under the same key; the pass also writes this frame's depth and
 * normals for the next (geometry[1 - h]). */
/* Field by field, not memcmp: the key's tail padding (after the two bools) is whatever the stack
 * held, since an initializer sets the members only, so memcmp rejected the history whenever the
 * stack under this frame's key held other bytes than under the last one's (it did every frame once
 * the timers called glFinish on llvmpipe, src/gpu/timer.c). */
static bool same_history(const ob_history_key *a, const ob_history_key *b)
{
    return a->method == b->method && a->scale == b->scale && a->at == b->at && a->width == b->width &&
           a->height == b->height && a->orthographic == b->orthographic && a->rgb == b->rgb && a->bounce == b->bounce;
}

static ob_error run_temporal(ob_renderer *r, const ob_settings *s, const ob_method_plan *plan, ao_targets *t,
                             const ob_chain_io *io, const GLuint guide[2], GLuint main_in, GLuint main_out,
                             GLuint bounce_in, GLuint bounce_out)
{
    const ob_history_key key = {.method = plan->index, .scale = r->last.scale, .at = temporal_at(r, s),
                                .width = r->inner_width, .height = r->inner_height,
                                .orthographic = r->frame_constants.orthographic, .rgb = plan->rgb,
                                .bounce = plan->bounce};
    const bool valid = r->history_valid && same_history(&key, &r->history_key);
    /* The last frame's camera with this frame's jitter: a point seen now at pixel p is looked up
     * where it lay in the last frame's unjittered raster, moved by this frame's jitter, which for
     * a still camera is p itself. So the history is never resampled between pixels by the jitter
     * alone, and a still camera's history averages each pixel's jittered samples: the AO over the
     * pixel's footprint (the reprojection of TAA, Karis 2014). Only the jitter's elements differ. */
    float prev_ao_proj[16];
    for (int i = 0; i < 16; ++i)
        prev_ao_proj[i] = r->prev_ao_proj[i] + (r->frame_constants.ao_proj[i] - r->ao_proj_unjittered[i]);
    const bool jittered = frame_jittered(r);
    ob_temporal_constants c;
    ob_temporal_fill(&c, r->prev_view, r->frame_constants.inv_view, prev_ao_proj, valid, r->last.temporal_frames,
                     s->temporal_detail);
    ob_temporal_set_motion(&c, io->motion, io->motion_scale);
    const int h = t->history_index;
    ob_temporal_chain chain = {.current = main_in, .result = main_out, .rgb = plan->rgb,
                               .history = plan->rgb ? t->history_rgb[h] : t->history[h],
                               .next_history = plan->rgb ? t->history_rgb[1 - h] : t->history[1 - h],
                               .age = plan->rgb ? 0 : t->history_age[h],
                               .next_age = plan->rgb ? 0 : t->history_age[1 - h],
                               .host_motion = io->motion,
                               .jittered = jittered || (valid && r->prev_jittered)};
    if (plan->bounce) {
        chain.bounce_current = bounce_in;
        chain.bounce_result = bounce_out;
        chain.bounce_history = t->bounce_history[h];
        chain.bounce_next_history = t->bounce_history[1 - h];
    }
    ob_error err =
        ob_temporal_run(&r->temporal, &c, &t->grid, guide[0], guide[1], &t->geometry[h], &t->geometry[1 - h], &chain);
    if (err != OB_OK) return err;
    t->history_index = 1 - h;
    r->history_key = key;
    r->history_valid = true;
    memcpy(r->prev_view, r->frame_constants.view, sizeof r->prev_view);
    memcpy(r->prev_ao_proj, r->ao_proj_unjittered, sizeof r->prev_ao_proj);
    r->prev_jittered = jittered;
    return OB_OK;
}

/* none: 1 into the raw target (what the raw-AO read-back shows) and into the chain's output, by
 * the fill pass (glClearTexImage took 0.15 ms per 1920x1080 target on an H100, more than ssao's AO
 * pass: shaders/fill.glsl). The renderer's own output is left alone while it still holds the last
 * none frame's 1 (ao_is_one). No timer of its own: the baseline has no AO pass (test_baseline). */
static ob_error run_without_ao(ob_renderer *r, const ob_method_plan *plan, ao_targets *t, const ob_chain_io *io)
{
    const ob_ao_inputs in = {.frame = &r->frame_constants, .width = t->grid.width, .height = t->grid.height};
    const ob_ao_outputs out = {.visibility = t->raw};
    r->history_valid = false;
    ob_error err = plan->impl->run(plan->state, &in, plan->params, &out); /* none's run itself writes nothing */
    if (err != OB_OK) return err;
    const float one[4] = {1.0f, 1.0f, 1.0f, 1.0f};
    ob_fill_run(&r->fill, false, t->raw, one);
    if (io->ao != r->ao || !r->ao_is_one) ob_fill_run(&r->fill, false, io->ao, one);
    r->ao_is_one = io->ao == r->ao;
    return OB_OK;
}

/* Each compute pass reads what the previous one wrote with image stores. */
static const GLbitfield BARRIER = GL_TEXTURE_FETCH_BARRIER_BIT | GL_SHADER_IMAGE_ACCESS_BARRIER_BIT;

/* One frame's way through the chain: the AO grid's guides and where each stage reads and writes. */
typedef struct chain_run {
    ob_renderer *r;
    const ob_settings *s;
    const ob_method_plan *plan;
    ao_targets *t;
    const ob_chain_io *io;
    GLuint guide[2];             /* the AO grid's depth and normals */
    GLuint main_in, main_out;    /* the visibility or M into and out of the filter */
    GLuint bounce_in, bounce_out;
} chain_run;

/* The AO grid's inputs (downsample, edges, depth MIPs) and the method into the raw targets. */
static ob_error run_method_stage(chain_run *c)
{
    ob_renderer *r = c->r;
    ao_targets *t = c->t;
    const ob_method_plan *plan = c->plan;
    const ob_ao_grid *g = &t->grid;
    const uint32_t reads = plan->reads;
    /* The AO grid's depth and normals: the inputs themselves at full resolution, else one pixel of
     * each k x k block (downsample.glsl). */
    c->guide[0] = c->io->depth;
    c->guide[1] = c->io->normal;
    if (g->k > 1) {
        ob_timer_begin(&r->timers, "downsample");
        ob_downsample_run(&r->downsample, g, c->io->depth, c->io->normal, t->depth, t->normal);
        glMemoryBarrier(BARRIER);
        c->guide[0] = t->depth;
        c->guide[1] = t->normal;
    }
    /* Per-pixel sample counts only for a method that takes them: for the others the edge pass
     * would cost time and change nothing. */
    const bool adaptive = c->s->adaptive && plan->impl->adapts;
    r->last.adaptive = adaptive;
    if (adaptive) {
        ob_timer_begin(&r->timers, "edges");
        ob_edges_run(&r->edges, g, c->guide[0], c->guide[1], t->multiplier);
        glMemoryBarrier(BARRIER);
    }
    GLuint mips = 0;
    int mip_levels = 0;
    ob_error err = OB_OK;
    if (reads & OB_READS_DEPTH_MIPS) {
        ob_timer_begin(&r->timers, "depth_mips");
        err = make_depth_mips(r, c->guide[0], g->width, g->height, &mips, &mip_levels);
        if (err != OB_OK) return err;
    }
    if (plan->rgb || (plan->impl->writes & OB_WRITES_BOUNCE) || plan->bent) {
        err = ob_renderer_rgb_targets(r, t, plan->rgb || (plan->impl->writes & OB_WRITES_BOUNCE), plan->bent);
        if (err != OB_OK) return err;
    }
    const ob_chain_io *io = c->io;
    GLuint second = reads & OB_READS_SECOND_LAYER ? io->second_depth : 0;
    if (second && (reads & OB_READS_SECOND_BACK)) {
        ob_timer_begin(&r->timers, "second_back");
        err = make_second_back(r, io, (reads & OB_READS_SECOND_PLANES) != 0, &second);
        if (err != OB_OK) return err;
    }
    const ob_ao_inputs in = {.frame = &r->frame_constants,
                             .linear_depth = c->guide[0],
                             .view_normal = c->guide[1],
                             .width = g->width,
                             .height = g->height,
                             .sample_multiplier = adaptive ? t->multiplier : 0,
                             .radiance = reads & OB_READS_RADIANCE ? io->radiance : 0,
                             .albedo = reads & OB_READS_ALBEDO ? io->albedo : 0,
                             .depth_mips = mips,
                             .depth_mip_levels = mip_levels,
                             .second_depth = second,
                             .facet_normal = io->facet,
                             .extra_depth = r->last.extra_view ? r->extra_gbuffer.linear_depth : 0,
                             .extra_normal = r->last.extra_view ? r->extra_gbuffer.normal : 0,
                             .extra_radiance = r->last.extra_view ? r->extra_direct : 0,
                             .extra_from_view = r->extra_from_view,
                             .extra_to_view = r->extra_to_view,
                             .extra_proj = r->extra_proj};
    /* Every declared output gets a target, also one that these params leave unwritten. */
    const ob_ao_outputs out = {.visibility = plan->rgb ? t->raw_rgb : t->raw,
                               .bounce = plan->impl->writes & OB_WRITES_BOUNCE ? t->bounce_raw : 0,
                               .bent_normal = plan->bent ? t->bent_raw : 0};
    ob_timer_begin(&r->timers, "ao");
    err = plan->impl->run(plan->state, &in, plan->params, &out);
    if (err != OB_OK) return err;
    glMemoryBarrier(BARRIER);
    return OB_OK;
}

/* Temporal accumulation (issue 17) before the filter, the filter then reading the accumulation, or
 * after it, the filter writing into its input; then the filter itself on every chain. */
static ob_error run_filter_stage(chain_run *c)
{
    ob_renderer *r = c->r;
    ao_targets *t = c->t;
    const ob_method_plan *plan = c->plan;
    const ob_settings *s = c->s;
    const ob_ao_grid *g = &t->grid;
    c->main_in = plan->rgb ? t->raw_rgb : t->raw;
    c->bounce_in = t->bounce_raw;
    c->main_out = plan->rgb ? (g->k > 1 ? t->filtered_rgb : r->ao_rgb) : (g->k > 1 ? t->filtered : c->io->ao);
    c->bounce_out = g->k > 1 ? t->bounce_filtered : r->bounce;
    const GLuint filtered_main = c->main_out, filtered_bounce = c->bounce_out;
    ob_error err = OB_OK;
    r->last.temporal = s->temporal;
    const int at = temporal_at(r, s); /* before the accumulation changes what it reads */
    if (s->temporal) {
        err = ob_renderer_temporal_targets(r, t);
        if (err != OB_OK) return err;
        r->last.temporal_frames = s->temporal_frames > 0 ? s->temporal_frames : OB_TEMPORAL_FRAMES_DEFAULT;
        const GLuint main_accum = plan->rgb ? t->accum_rgb : t->accum;
        if (at == OB_TEMPORAL_BEFORE_FILTER) {
            ob_timer_begin(&r->timers, "temporal");
            /* Visibility: the filter reads the new history's value itself, no copy. */
            err = run_temporal(r, s, plan, t, c->io, c->guide, c->main_in, plan->rgb ? main_accum : 0, c->bounce_in,
                               t->bounce_accum);
            if (err != OB_OK) return err;
            glMemoryBarrier(BARRIER);
            c->main_in = plan->rgb ? main_accum : t->history[t->history_index];
            c->bounce_in = t->bounce_accum;
        } else {
            c->main_out = main_accum;
            c->bounce_out = t->bounce_accum;
        }
    } else {
        r->history_valid = false;
    }

    ob_timer_begin(&r->timers, "filter");
    void *fstate = ob_renderer_filter_state(r, s->filter, plan->rgb, &err);
    if (err != OB_OK) return err;
    const ob_filter_impl *filter = ob_filter_impl_at(s->filter);
    /* M and the bounce through the same filter (SSDO thesis §5.3 smooths them separately); the sky is
     * 1 in M and 0 in the bounce. The barriers order the shared scratch targets. */
    err = run_filter(r, filter, fstate, t, c->guide, c->main_in, c->main_out, plan->rgb ? t->scratch_rgb : t->scratch,
                     plan->rgb, 1.0f, s);
    if (err == OB_OK && plan->bounce) {
        /* A bounce beside a scalar visibility (vbgi) takes the filter's RGB variant. */
        void *bstate = plan->rgb ? fstate : ob_renderer_filter_state(r, s->filter, true, &err);
        glMemoryBarrier(BARRIER);
        if (err == OB_OK)
            err = run_filter(r, filter, bstate, t, c->guide, c->bounce_in, c->bounce_out, t->scratch_rgb, true, 0.0f, s);
    }
    if (err == OB_OK && plan->bent) {
        /* The bent normal through the same filter's RGB variant (sky 0, no direction); compose and
         * the host's output pass renormalise what the weights average. */
        void *bstate = ob_renderer_filter_state(r, s->filter, true, &err);
        glMemoryBarrier(BARRIER);
        if (err == OB_OK)
            err = run_filter(r, filter, bstate, t, c->guide, t->bent_raw, g->k > 1 ? t->bent_filtered : r->bent,
                             t->scratch_rgb, true, 0.0f, s);
    }
    if (err != OB_OK) return err;
    glMemoryBarrier(BARRIER);
    if (s->temporal && at == OB_TEMPORAL_AFTER_FILTER) {
        ob_timer_begin(&r->timers, "temporal");
        err = run_temporal(r, s, plan, t, c->io, c->guide, c->main_out, filtered_main, c->bounce_out, filtered_bounce);
        if (err != OB_OK) return err;
        glMemoryBarrier(BARRIER);
    }
    return OB_OK;
}

/* Joint bilateral upsampling of every chain from the AO grid to the enlarged size. */
static ob_error run_upsample_stage(chain_run *c)
{
    ob_renderer *r = c->r;
    ao_targets *t = c->t;
    const ob_method_plan *plan = c->plan;
    const ob_chain_io *io = c->io;
    const ob_ao_grid *g = &t->grid;
    ob_timer_begin(&r->timers, "upsample");
    const int up = c->s->upsample;
    /* The bounce, else the bent normals, rides in the main value's dispatch: the weights depend on
     * the geometry alone, so one pass computes them once for both (the same bits as two,
     * tests/test_filters.c). With both, the bent normals have a pass of their own. */
    GLuint second_low = 0, second_out = 0;
    if (plan->bounce) {
        second_low = t->bounce_filtered;
        second_out = r->bounce;
    } else if (plan->bent) {
        second_low = t->bent_filtered;
        second_out = r->bent;
    }
    ob_error err = OB_OK;
    if (plan->bent && plan->bounce)
        err = ob_upsample_run(&r->upsample_rgb, up, g, io->depth, io->normal, t->depth, t->normal, t->bent_filtered,
                              r->bent, 0.0f, 0, 0);
    if (err == OB_OK)
        err = plan->rgb ? ob_upsample_run(&r->upsample_rgb, up, g, io->depth, io->normal, t->depth, t->normal,
                                          t->filtered_rgb, r->ao_rgb, 1.0f, second_low, second_out)
                        : ob_upsample_run(&r->upsample, up, g, io->depth, io->normal, t->depth, t->normal, t->filtered,
                                          io->ao, 1.0f, second_low, second_out);
    if (err != OB_OK) return err;
    glMemoryBarrier(BARRIER);
    return OB_OK;
}

ob_error ob_run_ao_chain(ob_renderer *r, const ob_settings *s, const ob_method_plan *plan, ao_targets *t,
                         const ob_chain_io *io)
{
    const uint32_t reads = plan->reads;
    r->last = (ob_frame_record){.scale = r->last.scale,
                                .method = plan->index,
                                .rgb = plan->rgb && plan->impl->shader,
                                .bounce = plan->bounce && plan->impl->shader,
                                .bent = plan->bent && plan->impl->shader,
                                .second_layer = (reads & OB_READS_SECOND_LAYER) && io->second_depth,
                                .extra_view = (reads & OB_READS_EXTRA_VIEW) && io->extra_view,
                                .far = r->last.far};
    memcpy(r->last.params, plan->params, sizeof r->last.params);
    /* A method that dispatches nothing (none) is the cost baseline: AO 1 straight into the output,
     * with no AO-grid pass, filter, accumulation or upsample (a filter over a constant changes
     * nothing and would only count as overhead of no AO). */
    if (!plan->impl->shader) return run_without_ao(r, plan, t, io);
    if (io->ao == r->ao) r->ao_is_one = false;
    chain_run c = {.r = r, .s = s, .plan = plan, .t = t, .io = io};
    ob_error err = run_method_stage(&c);
    if (err == OB_OK) err = run_filter_stage(&c);
    if (err == OB_OK && t->grid.k > 1) err = run_upsample_stage(&c);
    if (err != OB_OK) return err;
    if (plan->rgb && !plan->bounce) {
        /* Bounce off: nothing to filter or upsample; the bounce view reads zeros. */
        const float zero[4] = {0.0f, 0.0f, 0.0f, 0.0f};
        ob_fill_run(&r->fill_rgb, true, r->bounce, zero);
    }
    return OB_OK;
}
