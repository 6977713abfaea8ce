/* The frame (DESIGN.md "The frame"), each pass timed:
 *   [shadow maps] -> gbuffer -> lighting (direct light, shadowed) -> [downsample to the AO
 *   resolution] -> [edges, for adaptive sample counts] -> method -> filter (at the AO
 *   resolution) -> [joint bilateral upsample] -> compose (HDR radiance) -> luminance, bloom,
 *   tonemap.
 * The method is resolved once per frame into a plan (its state, its resolved parameters and the
 * outputs they produce); the renderer knows no method by name, only what the registry entry
 * declares it reads and writes. The camera, the AO grid, the lights and the ambient light go into
 * the per-frame block (frame_params.h) that every pass reads. The CLI, the viewer and the tests
 * all render through here. */
#include <cglm/cglm.h>
#include <math.h>
#include <string.h>

#include "core/error.h"
#include "core/renderer.h"

void ob_proj_info(const float *proj, float out[4])
{
    /* Column-major: P00 = proj[0], P11 = proj[5], P20 = proj[8], P21 = proj[9]. */
    out[0] = 1.0f / proj[0];
    out[1] = 1.0f / proj[5];
    out[2] = proj[8];
    out[3] = proj[9];
}

void ob_guard_projection(float *proj, int width, int height, int guard)
{
    /* Seed 000 §3.2.2: the enlarged image must hold the visible one at its centre, pixel for pixel.
     * ndc' = 2 (x + g + 1/2) / (W + 2g) - 1 = (2 (x + 1/2) / W - 1) W / (W + 2g), so ndc scales
     * about the centre by W / (W + 2g); ndc = (P00 X + P20 Z) / -Z scales with P00 and P20. */
    if (guard <= 0) return;
    float sx = (float)width / (float)(width + 2 * guard);
    float sy = (float)height / (float)(height + 2 * guard);
    proj[0] *= sx;
    proj[8] *= sx;
    proj[5] *= sy;
    proj[9] *= sy;
}

/* The projection as seen from the AO grid. AO pixel i sits at full pixel k i + o, so along x
 * ndc_grid = a ndc_full + b with a = W / (k w) and b = a - 1 + (1 - (2o + 1)/k) / w (from
 * ndc_full = 2 (k i + o + 1/2) / W - 1 and ndc_grid = 2 (i + 1/2) / w - 1). Folding that into
 * P00, P20 (and P11, P21) keeps every method's reconstruction and projection exact. */
static void grid_projection(const ob_ao_grid *g, const float *proj, float *out)
{
    memcpy(out, proj, 16 * sizeof(float));
    if (g->k == 1) return;
    float ax = (float)g->full_width / (float)(g->k * g->width);
    float ay = (float)g->full_height / (float)(g->k * g->height);
    float bx = ax - 1.0f + (1.0f - (2.0f * (float)g->o + 1.0f) / (float)g->k) / (float)g->width;
    float by = ay - 1.0f + (1.0f - (2.0f * (float)g->o + 1.0f) / (float)g->k) / (float)g->height;
    /* ndc = (P00 X + P20 Z) / -Z  ->  a ndc + b = (a P00 X + (a P20 - b) Z) / -Z */
    out[0] = ax * proj[0];
    out[8] = ax * proj[8] - bx;
    out[5] = ay * proj[5];
    out[9] = ay * proj[9] - by;
}

static void put3(float *dst, const float *src)
{
    dst[0] = src[0];
    dst[1] = src[1];
    dst[2] = src[2];
    dst[3] = 0.0f;
}

void ob_frame_constants_fill(ob_frame_constants *f, const ob_frame_desc *d)
{
    memset(f, 0, sizeof *f);
    const ob_ao_grid *g = d->grid;
    memcpy(f->view, d->view, sizeof f->view);
    /* Through aligned cglm matrices: its SIMD paths assume them. */
    mat4 view, inv_view;
    memcpy(view, d->view, sizeof view);
    glm_mat4_inv(view, inv_view);
    memcpy(f->inv_view, inv_view, sizeof f->inv_view);
    memcpy(f->proj, d->proj, sizeof f->proj);
    grid_projection(g, d->proj, f->ao_proj);
    ob_proj_info(f->proj, f->proj_info);
    ob_proj_info(f->ao_proj, f->ao_proj_info);
    f->size[0] = (float)g->full_width;
    f->size[1] = (float)g->full_height;
    f->inv_size[0] = 1.0f / (float)g->full_width;
    f->inv_size[1] = 1.0f / (float)g->full_height;
    f->ao_size[0] = (float)g->width;
    f->ao_size[1] = (float)g->height;
    f->ao_inv_size[0] = 1.0f / (float)g->width;
    f->ao_inv_size[1] = 1.0f / (float)g->height;
    f->ao_k = g->k;
    f->ao_o = g->o;
    f->frame_index = d->frame_index;
    f->near_z = d->near_z;
    f->far_z = d->far_z;
    const ob_settings *s = d->settings;
    if (s) {
        f->ambient_mode = (int)s->ambient_mode;
        put3(f->ambient, s->ambient);
        put3(f->sky, s->sky);
        put3(f->ground, s->ground);
        put3(f->background, s->background);
        /* Temporal accumulation: the random-kernel methods' rotation noise turns by the golden
         * ratio's fraction per frame (noise.glsl says why that sequence); in double, as 0.618 i
         * loses the fraction in float after a few thousand frames. */
        if (s->temporal) f->noise_turn = (float)fmod((double)d->frame_index * 0.6180339887498949, 1.0);
    }
    for (int i = 0; i < 9 && d->sh; ++i) put3(f->sh[i], d->sh[i]);
    int count = d->light_count < OB_MAX_LIGHTS ? d->light_count : OB_MAX_LIGHTS;
    f->light_count = count > 0 ? count : 0;
    for (int i = 0; i < f->light_count; ++i) {
        const ob_light *l = &d->lights[i];
        float len = sqrtf(l->direction[0] * l->direction[0] + l->direction[1] * l->direction[1] +
                          l->direction[2] * l->direction[2]);
        for (int k = 0; k < 3; ++k) {
            f->light_color[i][k] = l->color[k] * l->intensity;
            f->light_position[i][k] = l->position[k];
            /* A zero direction points up, as the shadow maps assume (shadow.c). */
            f->light_direction[i][k] = len > 0.0f ? l->direction[k] / len : (k == 1 ? 1.0f : 0.0f);
        }
        f->light_color[i][3] = (float)l->type;
        f->light_position[i][3] = l->range;
        f->light_direction[i][3] = -1.0f; /* unshadowed until ob_shadows_fill says otherwise */
        f->light_spot[i][0] = cosf(l->spot_inner_deg * 0.01745329252f);
        f->light_spot[i][1] = cosf(l->spot_outer_deg * 0.01745329252f);
    }
}

void ob_extra_view_camera(const ob_camera *c, ob_camera *out)
{
    *out = *c;
    float k[3] = {c->up[0], c->up[1], c->up[2]};
    float len = sqrtf(k[0] * k[0] + k[1] * k[1] + k[2] * k[2]);
    if (len <= 0.0f) {
        k[0] = k[2] = 0.0f;
        k[1] = len = 1.0f;
    }
    for (int i = 0; i < 3; ++i) k[i] /= len;
    /* Rodrigues at 90 degrees: v' = k x v + k (k . v), v = eye - target. */
    float v[3] = {c->eye[0] - c->target[0], c->eye[1] - c->target[1], c->eye[2] - c->target[2]};
    float kv = k[0] * v[0] + k[1] * v[1] + k[2] * v[2];
    float x[3] = {k[1] * v[2] - k[2] * v[1], k[2] * v[0] - k[0] * v[2], k[0] * v[1] - k[1] * v[0]};
    for (int i = 0; i < 3; ++i) out->eye[i] = c->target[i] + x[i] + k[i] * kv;
    out->shift[0] = out->shift[1] = 0.0f;
}

static void upload_frame(ob_renderer *r)
{
    glNamedBufferSubData(r->frame_ubo, 0, sizeof r->frame_constants, &r->frame_constants);
    glBindBufferBase(GL_UNIFORM_BUFFER, OB_BINDING_FRAME, r->frame_ubo);
}

static ob_error check_settings(const ob_settings *s)
{
    if (!s || !ob_method_at(s->method) || !ob_filter_at(s->filter))
        return ob_set_error(OB_ERR_INVALID_ARGUMENT, "settings are not initialised");
    if (s->ao_divisor != 0 && s->ao_divisor != 1 && s->ao_divisor != 2 && s->ao_divisor != 4)
        return ob_set_error(OB_ERR_OUT_OF_RANGE, "ao divisor %d is not 1, 2 or 4", s->ao_divisor);
    if (s->guard < 0 || s->guard > OB_GUARD_MAX)
        return ob_set_error(OB_ERR_OUT_OF_RANGE, "guard band %d px is outside 0..%d", s->guard, OB_GUARD_MAX);
    if (s->temporal_at != OB_TEMPORAL_BEFORE_FILTER && s->temporal_at != OB_TEMPORAL_AFTER_FILTER)
        return ob_set_error(OB_ERR_OUT_OF_RANGE, "temporal_at %d is not before (0) or after (1) the filter", s->temporal_at);
    if (s->temporal_frames < 0 || s->temporal_frames > OB_TEMPORAL_FRAMES_MAX)
        return ob_set_error(OB_ERR_OUT_OF_RANGE, "temporal_frames %d is outside 1..%d", s->temporal_frames,
                            OB_TEMPORAL_FRAMES_MAX);
    if (!(s->temporal_detail >= 0.0f && s->temporal_detail < 1.0f))
        return ob_set_error(OB_ERR_OUT_OF_RANGE, "temporal_detail %g is outside [0, 1)", (double)s->temporal_detail);
    return OB_OK;
}

/* The method of a frame, resolved once: its entry, state, parameters as it sees them (explicit
 * values, else defaults, with radii that were not set following the scene) and what it writes. */
typedef struct method_plan {
    int index;
    const ob_method_impl *impl;
    void *state;
    float params[OB_MAX_PARAMS];
    uint32_t reads;   /* ob_method_active_reads */
    uint32_t writes;  /* ob_method_active_writes */
    bool rgb;         /* OB_WRITES_VISIBILITY_RGB: M instead of visibility */
    bool bounce;      /* OB_WRITES_BOUNCE among the active outputs */
    bool bent;        /* OB_WRITES_BENT_NORMAL among the active outputs */
} method_plan;

static ob_error plan_method(ob_renderer *r, const ob_settings *s, method_plan *p)
{
    memset(p, 0, sizeof *p);
    p->index = s->method;
    p->impl = ob_method_impl_at(s->method);
    const ob_method_info *m = &p->impl->info;
    /* radius_scale (0 in a zero-filled ob_settings = 1) widens or narrows the search, not R. */
    float scale = s->radius_scale > 0.0f ? s->radius_scale : 1.0f;
    for (int i = 0; i < m->param_count; ++i) {
        p->params[i] = s->params[i];
        if (m->params[i].follows_scene_radius && !(s->params_set & (1u << i)) && r->scene_radius > 0.0f)
            p->params[i] = r->scene_radius;
        if (m->params[i].follows_scene_radius)
            p->params[i] = fminf(fmaxf(p->params[i] * scale, m->params[i].min), m->params[i].max);
    }
    /* Temporal accumulation wants noise that moves with the frame index: a method's own "temporal"
     * switch (gtao, vbao, vbgi: R2 jitters) goes on unless it was set explicitly. */
    for (int i = 0; i < m->param_count && s->temporal; ++i)
        if (m->params[i].type == OB_PARAM_BOOL && !strcmp(m->params[i].name, "temporal") && !(s->params_set & (1u << i)))
            p->params[i] = 1.0f;
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
 * for a method that reads it (OB_READS_DEPTH_MIPS): the frame's own depth or an engine's. */
static ob_error make_depth_mips(ob_renderer *r, GLuint depth, int width, int height, GLuint *mips, int *levels)
{
    if (!r->depth_mips_ready) {
        if (ob_depth_mips_init(&r->depth_mips) != OB_OK) return ob_peek_error(NULL);
        r->depth_mips_ready = true;
    }
    ob_error err = ob_depth_mips_run(&r->depth_mips, depth, width, height);
    if (err != OB_OK) return err;
    *mips = r->depth_mips.texture;
    *levels = r->depth_mips.levels;
    return OB_OK;
}

static ob_error run_method(ob_renderer *r, const method_plan *p, const ob_ao_inputs *in, const ob_ao_outputs *out)
{
    r->last_method = p->index;
    memcpy(r->last_params, p->params, sizeof r->last_params);
    r->last_adaptive = in->sample_multiplier != 0;
    return p->impl->run(p->state, in, p->params, out);
}

/* Filter one chain (src -> dst through the scratch target) at the AO resolution. */
static ob_error run_filter(const ob_filter_impl *filter, void *fstate, const ao_targets *t, GLuint src, GLuint dst,
                           GLuint scratch, bool rgb, float sky, const ob_settings *s)
{
    const ob_filter_inputs fin = {.src = src, .dst = dst, .scratch = scratch, .linear_depth = t->depth,
                                  .view_normal = t->normal, .width = t->grid.width, .height = t->grid.height,
                                  .rgb = rgb, .sky = sky};
    return filter->run(fstate, &fin, s->filter_params);
}

/* The extra view's targets at the G-buffer's size, made on first use and remade with it. */
static ob_error extra_targets(ob_renderer *r)
{
    int w = r->gbuffer.width, h = r->gbuffer.height;
    if (!r->extra_ready) {
        if (ob_gbuffer_init(&r->extra_gbuffer, w, h) != OB_OK) {
            ob_error err = ob_peek_error(NULL);
            ob_gbuffer_destroy(&r->extra_gbuffer);
            return err;
        }
        glCreateBuffers(1, &r->extra_ubo);
        glNamedBufferStorage(r->extra_ubo, sizeof(ob_frame_constants), NULL, GL_DYNAMIC_STORAGE_BIT);
        r->extra_direct = ob_make_texture_2d(GL_RGBA16F, w, h);
        r->extra_ready = true;
    } else if (r->extra_gbuffer.width != w || r->extra_gbuffer.height != h) {
        ob_error err = ob_gbuffer_resize(&r->extra_gbuffer, w, h);
        if (err != OB_OK) return err;
        glDeleteTextures(1, &r->extra_direct);
        r->extra_direct = ob_make_texture_2d(GL_RGBA16F, w, h);
    }
    GLenum e = glGetError();
    if (e != GL_NO_ERROR) return ob_set_error(OB_ERR_GL, "OpenGL error 0x%x making the extra view's targets", e);
    return OB_OK;
}

static ob_error run_extra_view(ob_renderer *r, const ob_settings *s, const ob_light *lights, int light_count)
{
    ob_error err = extra_targets(r);
    if (err != OB_OK) return err;
    const GLbitfield barrier = GL_TEXTURE_FETCH_BARRIER_BIT | GL_SHADER_IMAGE_ACCESS_BARRIER_BIT;
    ob_gbuffer_run_from(&r->extra_gbuffer, &r->gbuffer, r->extra_view, r->extra_proj, !s->textures_off);
    glMemoryBarrier(barrier | GL_FRAMEBUFFER_BARRIER_BIT);
    const ob_ao_grid grid = ob_ao_grid_make(r->gbuffer.width, r->gbuffer.height, 1);
    ob_frame_constants_fill(&r->extra_constants,
                            &(ob_frame_desc){.view = r->extra_view, .proj = r->extra_proj, .grid = &grid,
                                             .near_z = r->frame_constants.near_z, .far_z = r->frame_constants.far_z,
                                             .frame_index = r->frame_constants.frame_index, .lights = lights,
                                             .light_count = light_count, .settings = s,
                                             .sh = (const float(*)[3])r->environment.sh});
    ob_lighting_constants keep = r->lighting.constants;
    ob_shadows_fill(&r->shadows, &r->lighting.constants, &r->extra_constants);
    glNamedBufferSubData(r->extra_ubo, 0, sizeof r->extra_constants, &r->extra_constants);
    glBindBufferBase(GL_UNIFORM_BUFFER, OB_BINDING_FRAME, r->extra_ubo);
    err = ob_lighting_run(&r->lighting, &r->extra_constants, r->gbuffer.width, r->gbuffer.height,
                          r->extra_gbuffer.linear_depth, r->extra_gbuffer.normal, r->extra_gbuffer.albedo,
                          r->extra_direct);
    glMemoryBarrier(barrier);
    r->lighting.constants = keep;
    glBindBufferBase(GL_UNIFORM_BUFFER, OB_BINDING_FRAME, r->frame_ubo);
    return err;
}

/* Temporal accumulation of the main chain (visibility or M) and the bounce: `*_in` this frame's
 * values, `*_out` where the accumulation goes (passes/temporal.c). The history is reused only when
 * the last frame accumulated under the same key; the pass also writes this frame's depth and
 * normals for the next (geometry[1 - h]). */
static ob_error run_temporal(ob_renderer *r, const ob_settings *s, const method_plan *plan, ao_targets *t,
                             GLuint main_in, GLuint main_out, GLuint bounce_in, GLuint bounce_out)
{
    const ob_history_key key = {.method = plan->index, .scale = r->last_scale, .at = s->temporal_at,
                                .width = r->inner_width, .height = r->inner_height, .rgb = plan->rgb,
                                .bounce = plan->bounce};
    const bool valid = r->history_valid && !memcmp(&key, &r->history_key, sizeof key);
    ob_temporal_constants c;
    /* The history length: run_passes resolved it (0 = the default) for this frame. */
    ob_temporal_fill(&c, r->prev_view, r->frame_constants.inv_view, r->prev_ao_proj, valid, r->last_temporal_frames,
                     s->temporal_detail);
    const int h = t->history_index;
    ob_temporal_chain chain = {.current = main_in, .result = main_out, .rgb = plan->rgb,
                               .history = plan->rgb ? t->history_rgb[h] : t->history[h],
                               .next_history = plan->rgb ? t->history_rgb[1 - h] : t->history[1 - h],
                               .age = plan->rgb ? 0 : t->history_age[h],
                               .next_age = plan->rgb ? 0 : t->history_age[1 - h]};
    if (plan->bounce) {
        chain.bounce_current = bounce_in;
        chain.bounce_result = bounce_out;
        chain.bounce_history = t->bounce_history[h];
        chain.bounce_next_history = t->bounce_history[1 - h];
    }
    ob_error err = ob_temporal_run(&r->temporal, &c, &t->grid, t->depth, t->normal, &t->geometry[h], &t->geometry[1 - h],
                                   &chain);
    if (err != OB_OK) return err;
    t->history_index = 1 - h;
    r->history_key = key;
    r->history_valid = true;
    memcpy(r->prev_view, r->frame_constants.view, sizeof r->prev_view);
    memcpy(r->prev_ao_proj, r->frame_constants.ao_proj, sizeof r->prev_ao_proj);
    return OB_OK;
}

/* none: 1 into the raw target (what the raw-AO read-back shows) and into the full-size one that
 * compose reads, by the fill pass (glClearTexImage took 0.15 ms per 1920x1080 target on an H100,
 * more than ssao's AO pass: shaders/fill.glsl). The full-size target is left alone while it
 * still holds the last none frame's 1 (ao_is_one); the raw one, of whichever AO scale, is filled
 * every time. No timer of their own: the baseline has no AO pass (test_baseline). */
static ob_error run_without_ao(ob_renderer *r, const method_plan *plan, ao_targets *t)
{
    const ob_ao_inputs in = {.frame = &r->frame_constants, .width = t->grid.width, .height = t->grid.height};
    const ob_ao_outputs out = {.visibility = t->raw};
    r->last_rgb = r->last_bounce = r->last_bent = false;
    r->last_second_layer = r->last_extra_view = false;
    r->last_temporal = false;
    r->history_valid = false;
    ob_error err = run_method(r, plan, &in, &out); /* none's run itself writes nothing */
    if (err != OB_OK) return err;
    const float one[4] = {1.0f, 1.0f, 1.0f, 1.0f};
    ob_fill_run(&r->fill, false, t->raw, one);
    if (!r->ao_is_one) ob_fill_run(&r->fill, false, r->ao, one);
    r->ao_is_one = true;
    return OB_OK;
}

/* Every pass of the frame, stopping at the first failure; the caller closes the timers. */
static ob_error run_passes(ob_renderer *r, const ob_settings *s, const method_plan *plan, ao_targets *t,
                           const ob_light *lights, int light_count)
{
    const ob_ao_grid *g = &t->grid;
    /* Each compute pass reads what the previous one wrote with image stores or as attachments. */
    const GLbitfield barrier = GL_TEXTURE_FETCH_BARRIER_BIT | GL_SHADER_IMAGE_ACCESS_BARRIER_BIT;
    const ob_frame_constants *f = &r->frame_constants;
    ob_error err = ob_shadows_render(&r->shadows, &r->gbuffer, lights, light_count, r->bounds_min, r->bounds_max,
                                     &s->shadow, &r->timers);
    if (err != OB_OK) return err;
    ob_timer_begin(&r->timers, "gbuffer");
    ob_gbuffer_run(&r->gbuffer, f->view, f->proj, !s->textures_off);
    glMemoryBarrier(barrier | GL_FRAMEBUFFER_BARRIER_BIT);
    ob_timer_begin(&r->timers, "lighting");
    ob_lighting_setup(&r->lighting);
    ob_shadows_fill(&r->shadows, &r->lighting.constants, &r->frame_constants);
    upload_frame(r); /* after ob_shadows_fill: each light's shadow map index */
    err = ob_lighting_run(&r->lighting, &r->frame_constants, r->inner_width, r->inner_height, r->gbuffer.linear_depth,
                          r->gbuffer.normal, r->gbuffer.albedo, r->direct);
    if (err != OB_OK) return err;
    glMemoryBarrier(barrier);
    /* A method that dispatches nothing (none) is the cost baseline: AO 1 straight into the
     * full-size target that compose reads, with no AO-grid pass, filter, accumulation or upsample
     * (a filter over a constant changes nothing and would only count as overhead of no AO). The
     * jump skips only the AO chain's locals; compose reads none of them. */
    if (!plan->impl->shader) {
        err = run_without_ao(r, plan, t);
        if (err != OB_OK) return err;
        goto compose;
    }
    r->ao_is_one = false; /* the chain below writes r->ao (or what compose reads instead) */
    if (g->k > 1) {
        ob_timer_begin(&r->timers, "downsample");
        ob_downsample_run(&r->downsample, g, r->gbuffer.linear_depth, r->gbuffer.normal, t->depth, t->normal);
        glMemoryBarrier(barrier);
    }
    /* Per-pixel sample counts only for a method that takes them: for the others the edge pass
     * would cost time and change nothing. */
    const bool adaptive = s->adaptive && plan->impl->adapts;
    if (adaptive) {
        ob_timer_begin(&r->timers, "edges");
        ob_edges_run(&r->edges, g, t->depth, t->normal, t->multiplier);
        glMemoryBarrier(barrier);
    }
    if (plan->reads & OB_READS_EXTRA_VIEW) {
        /* Seed 000 §4.4: the extra camera's G-buffer and direct light, with its own per-frame
         * block (the same lights and shadow maps), then the main block bound again. */
        ob_timer_begin(&r->timers, "extra_view");
        err = run_extra_view(r, s, lights, light_count);
        if (err != OB_OK) return err;
    }
    if (plan->reads & OB_READS_SECOND_LAYER) {
        /* Depth peeling after the G-buffer, whose linear depth it peels behind. */
        ob_timer_begin(&r->timers, "second_layer");
        if (!r->peel_ready) {
            if (ob_peel_init(&r->peel) != OB_OK) return ob_peek_error(NULL);
            r->peel_ready = true;
        }
        err = ob_peel_run(&r->peel, &r->gbuffer, f->view, f->proj);
        if (err != OB_OK) return err;
        glMemoryBarrier(barrier);
    }
    GLuint mips = 0;
    int mip_levels = 0;
    if (plan->reads & OB_READS_DEPTH_MIPS) {
        ob_timer_begin(&r->timers, "depth_mips");
        err = make_depth_mips(r, t->depth, g->width, g->height, &mips, &mip_levels);
        if (err != OB_OK) return err;
    }
    if (plan->rgb || (plan->impl->writes & OB_WRITES_BOUNCE) || plan->bent) {
        err = ob_renderer_rgb_targets(r, t, plan->rgb || (plan->impl->writes & OB_WRITES_BOUNCE), plan->bent);
        if (err != OB_OK) return err;
    }
    const uint32_t reads = plan->reads;
    const ob_ao_inputs in = {.frame = f,
                             .linear_depth = t->depth,
                             .view_normal = t->normal,
                             .width = g->width,
                             .height = g->height,
                             .sample_multiplier = adaptive ? t->multiplier : 0,
                             .radiance = reads & OB_READS_RADIANCE ? r->direct : 0,
                             .albedo = reads & OB_READS_ALBEDO ? r->gbuffer.albedo : 0,
                             .depth_mips = mips,
                             .depth_mip_levels = mip_levels,
                             .second_depth = reads & OB_READS_SECOND_LAYER ? r->peel.linear_depth : 0,
                             .extra_depth = reads & OB_READS_EXTRA_VIEW ? r->extra_gbuffer.linear_depth : 0,
                             .extra_normal = reads & OB_READS_EXTRA_VIEW ? r->extra_gbuffer.normal : 0,
                             .extra_radiance = reads & OB_READS_EXTRA_VIEW ? r->extra_direct : 0,
                             .extra_from_view = r->extra_from_view,
                             .extra_to_view = r->extra_to_view,
                             .extra_proj = r->extra_proj};
    /* Every declared output gets a target, also one that these params leave unwritten. */
    const ob_ao_outputs out = {.visibility = plan->rgb ? t->raw_rgb : t->raw,
                               .bounce = plan->impl->writes & OB_WRITES_BOUNCE ? t->bounce_raw : 0,
                               .bent_normal = plan->bent ? t->bent_raw : 0};
    r->last_rgb = plan->rgb;
    r->last_bounce = plan->bounce;
    r->last_bent = plan->bent;
    r->last_second_layer = (reads & OB_READS_SECOND_LAYER) != 0;
    r->last_extra_view = (reads & OB_READS_EXTRA_VIEW) != 0;
    ob_timer_begin(&r->timers, "ao");
    err = run_method(r, plan, &in, &out);
    if (err != OB_OK) return err;
    glMemoryBarrier(barrier);

    /* The chains into and out of the filter; temporal accumulation (issue 17) sits before it, the
     * filter then reading the accumulation, or after it, the filter writing into its input. */
    GLuint main_in = plan->rgb ? t->raw_rgb : t->raw, bounce_in = t->bounce_raw;
    GLuint main_out = plan->rgb ? (g->k > 1 ? t->filtered_rgb : r->ao_rgb) : (g->k > 1 ? t->filtered : r->ao);
    GLuint bounce_out = g->k > 1 ? t->bounce_filtered : r->bounce;
    /* A method that dispatches nothing (none) writes a constant: nothing to accumulate. */
    const bool temporal = s->temporal && plan->impl->shader != NULL;
    r->last_temporal = temporal;
    if (temporal) {
        err = ob_renderer_temporal_targets(r, t);
        if (err != OB_OK) return err;
        r->last_temporal_frames = s->temporal_frames > 0 ? s->temporal_frames : OB_TEMPORAL_FRAMES_DEFAULT;
        const GLuint main_accum = plan->rgb ? t->accum_rgb : t->accum;
        if (s->temporal_at == OB_TEMPORAL_BEFORE_FILTER) {
            ob_timer_begin(&r->timers, "temporal");
            /* Visibility: the filter reads the new history's value itself, no copy. */
            err = run_temporal(r, s, plan, t, main_in, plan->rgb ? main_accum : 0, bounce_in, t->bounce_accum);
            if (err != OB_OK) return err;
            glMemoryBarrier(barrier);
            main_in = plan->rgb ? main_accum : t->history[t->history_index];
            bounce_in = t->bounce_accum;
        } else {
            main_out = main_accum;
            bounce_out = t->bounce_accum;
        }
    } else {
        r->history_valid = false;
    }

    ob_timer_begin(&r->timers, "filter");
    void *fstate = ob_renderer_filter_state(r, s->filter, plan->rgb, &err);
    if (err != OB_OK) return err;
    const ob_filter_impl *filter = ob_filter_impl_at(s->filter);
    if (!plan->rgb) {
        err = run_filter(filter, fstate, t, main_in, main_out, t->scratch, false, 1.0f, s);
    } else {
        /* M and the bounce through the same filter (seed 003 §5.3 smooths them separately); the
         * sky is 1 in M and 0 in the bounce. The barrier orders the shared scratch target. */
        err = run_filter(filter, fstate, t, main_in, main_out, t->scratch_rgb, true, 1.0f, s);
    }
    if (err == OB_OK && plan->bounce) {
        /* A bounce beside a scalar visibility (vbgi) takes the filter's RGB variant. */
        void *bstate = plan->rgb ? fstate : ob_renderer_filter_state(r, s->filter, true, &err);
        glMemoryBarrier(barrier);
        if (err == OB_OK) err = run_filter(filter, bstate, t, bounce_in, bounce_out, t->scratch_rgb, true, 0.0f, s);
    }
    if (err == OB_OK && plan->bent) {
        /* The bent normal through the same filter's RGB variant (sky 0, no direction); compose
         * renormalises what the weights average. */
        void *bstate = ob_renderer_filter_state(r, s->filter, true, &err);
        glMemoryBarrier(barrier);
        if (err == OB_OK)
            err = run_filter(filter, bstate, t, t->bent_raw, g->k > 1 ? t->bent_filtered : r->bent, t->scratch_rgb, true,
                             0.0f, s);
    }
    if (err != OB_OK) return err;
    glMemoryBarrier(barrier);
    if (temporal && s->temporal_at == OB_TEMPORAL_AFTER_FILTER) {
        ob_timer_begin(&r->timers, "temporal");
        err = run_temporal(r, s, plan, t, main_out,
                           plan->rgb ? (g->k > 1 ? t->filtered_rgb : r->ao_rgb) : (g->k > 1 ? t->filtered : r->ao),
                           bounce_out, g->k > 1 ? t->bounce_filtered : r->bounce);
        if (err != OB_OK) return err;
        glMemoryBarrier(barrier);
    }
    if (g->k > 1) {
        ob_timer_begin(&r->timers, "upsample");
        const GLuint full_depth = r->gbuffer.linear_depth, full_normal = r->gbuffer.normal;
        const int up = s->upsample;
        /* The bounce, else the bent normals, rides in the main value's dispatch: the weights depend
         * on the geometry alone, so one pass computes them once for both (the same bits as two,
         * tests/test_filters.c). With both, the bent normals have a pass of their own. */
        GLuint second_low = 0, second_out = 0;
        if (plan->bounce) {
            second_low = t->bounce_filtered;
            second_out = r->bounce;
        } else if (plan->bent) {
            second_low = t->bent_filtered;
            second_out = r->bent;
        }
        if (plan->bent && plan->bounce)
            err = ob_upsample_run(&r->upsample_rgb, up, g, full_depth, full_normal, t->depth, t->normal,
                                  t->bent_filtered, r->bent, 0.0f, 0, 0);
        if (err == OB_OK)
            err = plan->rgb ? ob_upsample_run(&r->upsample_rgb, up, g, full_depth, full_normal, t->depth, t->normal,
                                              t->filtered_rgb, r->ao_rgb, 1.0f, second_low, second_out)
                            : ob_upsample_run(&r->upsample, up, g, full_depth, full_normal, t->depth, t->normal,
                                              t->filtered, r->ao, 1.0f, second_low, second_out);
        if (err != OB_OK) return err;
        glMemoryBarrier(barrier);
    }
    if (plan->rgb && !plan->bounce) {
        /* Bounce off: nothing to filter or upsample; the bounce view reads zeros. */
        const float zero[4] = {0.0f, 0.0f, 0.0f, 0.0f};
        ob_fill_run(&r->fill_rgb, true, r->bounce, zero);
    }

compose:;
    const ob_compose_inputs ci = {.linear_depth = r->gbuffer.linear_depth,
                                  .normal = r->gbuffer.normal,
                                  .albedo = r->gbuffer.albedo,
                                  .ao = plan->rgb ? r->ao_rgb : r->ao,
                                  .direct = r->direct,
                                  .environment = r->environment.texture,
                                  .directional = plan->rgb,
                                  .bounce = plan->bounce ? r->bounce : 0,
                                  .bent_normal = plan->bent ? r->bent : 0,
                                  .width = r->width,
                                  .height = r->height,
                                  .guard = r->guard,
                                  .ao_all_light = s->ao_all_light,
                                  .multibounce = s->multibounce,
                                  .ambient_mode = (int)s->ambient_mode};
    ob_timer_begin(&r->timers, "compose");
    err = ob_compose_run(&r->compose, &ci, r->radiance);
    if (err != OB_OK) return err;
    glMemoryBarrier(barrier);
    ob_hdr_run(&r->hdr, r->radiance, &s->hdr, r->final, &r->timers);
    glMemoryBarrier(GL_TEXTURE_UPDATE_BARRIER_BIT | barrier);
    return OB_OK;
}

static int scale_index(int divisor) { return divisor == 2 ? 1 : divisor == 4 ? 2 : 0; }

ob_error ob_render_frame(ob_renderer *r, const ob_camera *camera, const ob_settings *s)
{
    if (!r || !camera) return ob_set_error(OB_ERR_INVALID_ARGUMENT, "ob_render_frame: NULL argument");
    if (check_settings(s) != OB_OK) return ob_peek_error(NULL);
    if (!r->has_scene) return ob_set_error(OB_ERR_INVALID_ARGUMENT, "ob_render_frame: no scene (ob_renderer_set_scene)");
    if (s->ambient_mode == OB_AMBIENT_ENVIRONMENT && !r->environment.texture)
        return ob_set_error(OB_ERR_INVALID_ARGUMENT, "environment ambient without an environment map (--env FILE.hdr)");

    ob_camera cam = *camera;
    if (cam.fov_y_deg <= 0.0f) cam.fov_y_deg = 60.0f;
    if (cam.up[0] == 0.0f && cam.up[1] == 0.0f && cam.up[2] == 0.0f) cam.up[1] = 1.0f;
    if (cam.near_z <= 0.0f || cam.far_z <= cam.near_z) ob_camera_fit_planes(&cam, r->bounds_min, r->bounds_max);
    if (!(cam.fov_y_deg < 179.0f) || !isfinite(cam.eye[0] + cam.eye[1] + cam.eye[2] + cam.target[0] + cam.target[1] + cam.target[2] + cam.shift[0] + cam.shift[1]))
        return ob_set_error(OB_ERR_INVALID_ARGUMENT, "camera is not finite or its fov is not in (0, 179)");

    /* A new guard band remakes the targets before anything is drawn into them. */
    ob_error err = ob_renderer_reshape(r, r->width, r->height, ob_guard_pixels(s->guard, s->ao_divisor));
    if (err != OB_OK) return err;
    method_plan plan;
    err = plan_method(r, s, &plan);
    if (err != OB_OK) return err;

    mat4 view, proj;
    glm_lookat(cam.eye, cam.target, cam.up, view);
    glm_perspective(glm_rad(cam.fov_y_deg), (float)r->width / (float)r->height, cam.near_z, cam.far_z, proj);
    proj[2][0] = cam.shift[0]; /* off-axis frustum (ob_camera.shift): P20, P21 */
    proj[2][1] = cam.shift[1];
    ob_guard_projection((float *)proj, r->width, r->height, r->guard);
    if (plan.reads & OB_READS_EXTRA_VIEW) {
        /* The extra camera: an unshifted frustum of the same fov over the same (enlarged) buffer. */
        ob_camera extra;
        ob_extra_view_camera(&cam, &extra);
        mat4 ev, ep, inv_view, from, to;
        glm_lookat(extra.eye, extra.target, extra.up, ev);
        glm_perspective(glm_rad(cam.fov_y_deg), (float)r->gbuffer.width / (float)r->gbuffer.height, cam.near_z,
                        cam.far_z, ep);
        glm_mat4_inv(view, inv_view);
        glm_mat4_mul(ev, inv_view, from);
        glm_mat4_inv(from, to);
        memcpy(r->extra_view, ev, sizeof r->extra_view);
        memcpy(r->extra_proj, ep, sizeof r->extra_proj);
        memcpy(r->extra_from_view, from, sizeof r->extra_from_view);
        memcpy(r->extra_to_view, to, sizeof r->extra_to_view);
    }
    int si = scale_index(s->ao_divisor);
    ao_targets *t = ob_renderer_targets(r, si);
    r->last_scale = si;
    const ob_light *lights = s->light_count > 0 ? s->lights : r->scene_lights;
    int light_count = s->light_count > 0 ? s->light_count : r->scene_light_count;
    ob_frame_constants_fill(&r->frame_constants,
                            &(ob_frame_desc){.view = (const float *)view, .proj = (const float *)proj, .grid = &t->grid,
                                             .near_z = cam.near_z, .far_z = cam.far_z, .frame_index = r->frame++,
                                             .lights = lights, .light_count = light_count, .settings = s,
                                             .sh = (const float(*)[3])r->environment.sh});

    /* From here the targets are being overwritten: no whole frame to present until the end. */
    r->has_frame = false;
    ob_timers_frame_begin(&r->timers);
    err = run_passes(r, s, &plan, t, lights, light_count);
    ob_timers_frame_end(&r->timers);
    if (err != OB_OK) return err;
    GLenum e = glGetError();
    if (e != GL_NO_ERROR) return ob_set_error(OB_ERR_GL, "OpenGL error 0x%x during the frame", e);
    r->has_frame = true;
    r->last_far = cam.far_z;
    return OB_OK;
}

/* ob_compute_ao and ob_compute_ao_filtered: the method, and the filter when asked. */
static ob_error compute_ao(ob_renderer *r, uint32_t linear_depth_tex, uint32_t normal_tex, const float proj[16],
                           const ob_settings *s, uint32_t ao_out_tex, bool filtered)
{
    if (!r || !proj || !linear_depth_tex || !normal_tex || !ao_out_tex)
        return ob_set_error(OB_ERR_INVALID_ARGUMENT, "ob_compute_ao: NULL argument");
    if (check_settings(s) != OB_OK) return ob_peek_error(NULL);
    const ob_method_impl *m = ob_method_impl_at(s->method);
    if ((m->reads & (OB_READS_RADIANCE | OB_READS_ALBEDO)) || (m->writes & (OB_WRITES_VISIBILITY_RGB | OB_WRITES_BOUNCE)))
        return ob_set_error(OB_ERR_INVALID_ARGUMENT, "ob_compute_ao: %s needs the frame's direct light (ob_render_frame)",
                            m->info.name);
    /* The host's textures are the renderer's size, guard band included if it wants one (obscura.h):
     * the renderer's own targets drop theirs. */
    ob_error err = ob_renderer_reshape(r, r->width, r->height, 0);
    if (err != OB_OK) return err;
    method_plan plan;
    err = plan_method(r, s, &plan);
    if (err != OB_OK) return err;
    /* The caller's camera: only the projection is known, so view space is world space. */
    const ob_ao_grid grid = ob_ao_grid_make(r->width, r->height, 1);
    mat4 identity = GLM_MAT4_IDENTITY_INIT;
    ob_frame_constants_fill(&r->frame_constants,
                            &(ob_frame_desc){.view = (const float *)identity, .proj = proj, .grid = &grid,
                                             .frame_index = r->frame++});
    upload_frame(r);
    void *fstate = filtered ? ob_renderer_filter_state(r, s->filter, false, &err) : NULL;
    if (err != OB_OK) return err;
    /* Filtered: the method into the renderer's own full-size target, then the filter into the
     * caller's. */
    const ao_targets *t = ob_renderer_targets(r, 0);
    /* The engine's depth gets the MIP chain too when the method reads one (depth_mips on). */
    GLuint mips = 0;
    int mip_levels = 0;
    if (plan.reads & OB_READS_DEPTH_MIPS) {
        err = make_depth_mips(r, linear_depth_tex, r->width, r->height, &mips, &mip_levels);
        if (err != OB_OK) return err;
    }
    const ob_ao_inputs in = {.frame = &r->frame_constants, .linear_depth = linear_depth_tex, .view_normal = normal_tex,
                             .width = r->width, .height = r->height, .depth_mips = mips,
                             .depth_mip_levels = mip_levels};
    const ob_ao_outputs out = {.visibility = filtered ? t->raw : ao_out_tex};
    const GLbitfield barrier = GL_TEXTURE_FETCH_BARRIER_BIT | GL_SHADER_IMAGE_ACCESS_BARRIER_BIT;
    glMemoryBarrier(barrier);
    err = run_method(r, &plan, &in, &out);
    glMemoryBarrier(barrier);
    if (err != OB_OK || !filtered) return err;
    const ob_filter_inputs fin = {.src = t->raw, .dst = ao_out_tex, .scratch = t->scratch,
                                  .linear_depth = linear_depth_tex, .view_normal = normal_tex, .width = r->width,
                                  .height = r->height, .rgb = false, .sky = 1.0f};
    err = ob_filter_impl_at(s->filter)->run(fstate, &fin, s->filter_params);
    glMemoryBarrier(barrier);
    if (err != OB_OK) return err;
    GLenum e = glGetError();
    if (e != GL_NO_ERROR) return ob_set_error(OB_ERR_GL, "OpenGL error 0x%x in ob_compute_ao_filtered", e);
    return OB_OK;
}

ob_error ob_compute_ao(ob_renderer *r, uint32_t linear_depth_tex, uint32_t normal_tex, const float proj[16],
                       const ob_settings *s, uint32_t ao_out_tex)
{
    return compute_ao(r, linear_depth_tex, normal_tex, proj, s, ao_out_tex, false);
}

ob_error ob_compute_ao_filtered(ob_renderer *r, uint32_t linear_depth_tex, uint32_t normal_tex, const float proj[16],
                                const ob_settings *s, uint32_t ao_out_tex)
{
    return compute_ao(r, linear_depth_tex, normal_tex, proj, s, ao_out_tex, true);
}

ob_error ob_render_floor(ob_renderer *r, const ob_settings *s, ob_floor_info *info)
{
    if (!r) return ob_set_error(OB_ERR_INVALID_ARGUMENT, "ob_render_floor: NULL renderer");
    if (check_settings(s) != OB_OK) return ob_peek_error(NULL);
    const int si = scale_index(s->ao_divisor);
    if (!r->has_frame || r->last_scale != si || !r->scales[si].ready)
        return ob_set_error(OB_ERR_INVALID_ARGUMENT,
                            "ob_render_floor: no frame at AO scale 1/%d yet (the floor reads its depth and normals)",
                            s->ao_divisor > 0 ? s->ao_divisor : 1);
    method_plan plan;
    ob_error err = plan_method(r, s, &plan);
    if (err != OB_OK) return err;
    const ob_method_info *m = &plan.impl->info;
    /* The settings as the method resolves them (a radius that follows the scene, the sample count
     * of HBAO's directions x steps), so the floor takes exactly the method's N and R. */
    float radius = 0.0f, max_radius_px = 0.0f;
    for (int i = 0; i < m->param_count; ++i) {
        if (!strcmp(m->params[i].name, "radius")) radius = plan.params[i];
        if (!strcmp(m->params[i].name, "max_radius_px")) max_radius_px = plan.params[i];
    }
    const int taps = ob_method_samples(plan.impl, plan.params);
    if (taps <= 0 || !(radius > 0.0f))
        return ob_set_error(OB_ERR_INVALID_ARGUMENT, "ob_render_floor: %s has no %s", m->name,
                            taps <= 0 ? "sample count" : "radius");
    const ao_targets *t = &r->scales[si];
    /* R_px = R x (height / 2) x P11 / d, the methods' projection (hbao.c, alchemy.c px_per_unit). */
    const ob_floor_desc d = {.taps = taps,
                             .rays = plan.impl->count_rays ? plan.impl->count_rays(plan.params) : 0,
                             .radius = radius,
                             .px_per_unit = 0.5f * (float)t->grid.height / r->frame_constants.ao_proj_info[1],
                             .max_radius_px = max_radius_px};
    if (!r->floor_ready) {
        if (ob_floor_init(&r->floor) != OB_OK) {
            err = ob_peek_error(NULL);
            ob_floor_destroy(&r->floor);
            return err;
        }
        r->floor_ready = true;
    }
    ob_timers_frame_begin(&r->timers);
    ob_timer_begin(&r->timers, "floor");
    err = ob_floor_run(&r->floor, &d, t->depth, t->normal, t->grid.width, t->grid.height);
    ob_timers_frame_end(&r->timers);
    if (err != OB_OK) return err;
    GLenum e = glGetError();
    if (e != GL_NO_ERROR) return ob_set_error(OB_ERR_GL, "OpenGL error 0x%x in the floor kernel", e);
    if (info) *info = (ob_floor_info){.taps = d.taps, .rays = d.rays, .radius = d.radius};
    return OB_OK;
}
