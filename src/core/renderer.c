/* The renderer's lifecycle (docs/architecture.md "The frame"): its targets, the passes it owns, the scene and
 * the environment it was given, and the method and filter states made on first use. The frame
 * itself is frame.c; read-back readback.c; the debug views present.c. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "base/error.h"
#include "core/renderer.h"

/* Delete every AO-resolution target and mark each scale not ready, so the next frame remakes it. */
static void release_scales(ob_renderer *r)
{
    for (int i = 0; i < OB_AO_SCALES; ++i) {
        ao_targets *t = &r->scales[i];
        GLuint tex[4] = {t->raw, t->filtered, t->scratch, t->multiplier};
        glDeleteTextures(4, tex);
        GLuint rgb[7] = {t->raw_rgb, t->filtered_rgb, t->scratch_rgb, t->bounce_raw, t->bounce_filtered,
                         t->bent_raw, t->bent_filtered};
        glDeleteTextures(7, rgb);
        GLuint temporal[16] = {t->accum,           t->history[0],        t->history[1],     t->history_age[0],
                               t->history_age[1],  t->accum_rgb,         t->history_rgb[0], t->history_rgb[1],
                               t->bounce_accum,    t->bounce_history[0], t->bounce_history[1], t->geometry[0].depth,
                               t->geometry[1].depth, t->motion, t->geometry[0].normal, t->geometry[1].normal};
        glDeleteTextures(16, temporal);
        if (t->grid.k > 1) {
            GLuint own[2] = {t->depth, t->normal};
            glDeleteTextures(2, own);
        }
        memset(t, 0, sizeof *t);
    }
}

/* The renderer's own full-resolution targets, in the order ao, final, direct, radiance: ao and
 * direct at the size with the guard band (the AO chain and SSDO's radiance look into it), final and
 * radiance at the visible size (compose crops; the HDR passes see only the visible frame). */
static void make_full_targets(GLuint tex[4], int width, int height, int guard)
{
    tex[0] = ob_make_texture_2d(GL_R32F, width + 2 * guard, height + 2 * guard);
    tex[1] = ob_make_texture_2d(GL_RGBA8, width, height);
    tex[2] = ob_make_texture_2d(GL_RGBA16F, width + 2 * guard, height + 2 * guard);
    tex[3] = ob_make_texture_2d(GL_RGBA16F, width, height);
}

static ob_error check_size(const ob_context *ctx, int width, int height)
{
    if (width <= 0 || height <= 0 || width > ctx->max_texture_size || height > ctx->max_texture_size)
        return ob_set_error(OB_ERR_BAD_SIZE, "size %dx%d is outside 1..%d (GL_MAX_TEXTURE_SIZE of %s)", width, height,
                            ctx->max_texture_size, ctx->renderer);
    return OB_OK;
}

/* A visible size and a guard band whose enlarged size the GL can hold. */
static ob_error check_guard(const ob_context *ctx, int width, int height, int guard)
{
    if (guard < 0 || guard > OB_GUARD_MAX)
        return ob_set_error(OB_ERR_BAD_SIZE, "guard band %d px is outside 0..%d", guard, OB_GUARD_MAX);
    int max = ctx->max_texture_size;
    if (width + 2 * guard > max || height + 2 * guard > max)
        return ob_set_error(OB_ERR_BAD_SIZE, "guard band %d px makes %dx%d into %dx%d, above GL_MAX_TEXTURE_SIZE %d of %s",
                            guard, width, height, width + 2 * guard, height + 2 * guard, max, ctx->renderer);
    return OB_OK;
}

/* A multiple of 4 k: the AO grid of divisor k then starts on a visible pixel's grid cell (AO pixel i
 * of the visible frame is i + guard / k of the enlarged one) and the 4x4 rotation tile, indexed by
 * AO pixel, falls on the same visible pixels as without the band, so away from the border nothing
 * changes by a single bit. */
int ob_guard_pixels(int guard, int k)
{
    int step = 4 * (k > 1 ? k : 1);
    return guard > 0 ? (guard + step - 1) / step * step : 0;
}

void ob_destroy_renderer(ob_renderer *r)
{
    if (!r) return;
    for (int i = 0; i < ob_method_count() && r->method_states; ++i)
        ob_method_destroy_state(ob_method_impl_at(i), r->method_states[i]);
    for (int i = 0; i < ob_filter_count(); ++i) {
        const ob_filter_impl *f = ob_filter_impl_at(i);
        if (r->filter_ready && r->filter_ready[i] && f->destroy) f->destroy(r->filter_states[i]);
        if (r->filter_ready_rgb && r->filter_ready_rgb[i] && f->destroy) f->destroy(r->filter_states_rgb[i]);
    }
    free(r->filter_states_rgb);
    free(r->filter_ready_rgb);
    free(r->method_states);
    free(r->filter_states);
    free(r->filter_ready);
    release_scales(r);
    ob_view_destroy(&r->view);
    /* Passes made on first use are zero until then, which their destroy functions take. */
    ob_depth_mips_destroy(&r->depth_mips);
    ob_second_back_destroy(&r->second_back);
    ob_floor_destroy(&r->floor);
    ob_peel_destroy(&r->peel);
    ob_host_passes_destroy(&r->host);
    if (r->extra_ubo) {
        ob_gbuffer_destroy(&r->extra_gbuffer);
        glDeleteTextures(1, &r->extra_direct);
        glDeleteBuffers(1, &r->extra_ubo);
    }
    ob_temporal_destroy(&r->temporal);
    ob_gbuffer_destroy(&r->gbuffer);
    ob_compute_pass_destroy(&r->downsample);
    ob_upsample_destroy(&r->upsample);
    ob_upsample_destroy(&r->upsample_rgb);
    ob_compute_pass_destroy(&r->edges);
    ob_compute_pass_destroy(&r->fill);
    ob_compute_pass_destroy(&r->fill_rgb);
    ob_compose_destroy(&r->compose);
    ob_lighting_destroy(&r->lighting);
    ob_shadows_destroy(&r->shadows);
    ob_hdr_destroy(&r->hdr);
    ob_environment_destroy(&r->environment);
    GLuint tex[7] = {r->ao, r->final, r->direct, r->radiance, r->ao_rgb, r->bounce, r->bent};
    glDeleteTextures(7, tex);
    if (r->frame_ubo) glDeleteBuffers(1, &r->frame_ubo);
    ob_timers_destroy(&r->timers);
    free(r);
}

ob_renderer *ob_make_renderer(ob_context *ctx, const ob_renderer_desc *desc)
{
    if (!ctx) {
        ob_set_error(OB_ERR_INVALID_ARGUMENT, "ob_make_renderer: no context");
        return NULL;
    }
    ob_renderer_desc d = desc ? *desc : (ob_renderer_desc){0};
    if (d.width == 0 && d.height == 0) {
        d.width = 640;
        d.height = 480;
    }
    if (check_size(ctx, d.width, d.height) != OB_OK) return NULL;
    ob_gl_drop_pending(); /* the passes below check their allocations with glGetError */
    ob_renderer *r = calloc(1, sizeof *r);
    if (!r) {
        ob_set_error(OB_ERR_OUT_OF_MEMORY, "out of memory making the renderer");
        return NULL;
    }
    r->ctx = ctx;
    r->width = d.width;
    r->height = d.height;
    r->inner_width = d.width;
    r->inner_height = d.height;
    r->method_states = calloc((size_t)ob_method_count(), sizeof *r->method_states);
    r->filter_states = calloc((size_t)ob_filter_count(), sizeof *r->filter_states);
    r->filter_ready = calloc((size_t)ob_filter_count(), sizeof *r->filter_ready);
    r->filter_states_rgb = calloc((size_t)ob_filter_count(), sizeof *r->filter_states_rgb);
    r->filter_ready_rgb = calloc((size_t)ob_filter_count(), sizeof *r->filter_ready_rgb);
    ob_timers_init(&r->timers);
    if (!r->method_states || !r->filter_states || !r->filter_ready || !r->filter_states_rgb ||
        !r->filter_ready_rgb) {
        ob_set_error(OB_ERR_OUT_OF_MEMORY, "out of memory making the renderer");
        ob_destroy_renderer(r);
        return NULL;
    }
    if (ob_gbuffer_init(&r->gbuffer, d.width, d.height) != OB_OK || ob_compose_init(&r->compose) != OB_OK ||
        ob_downsample_init(&r->downsample) != OB_OK || ob_upsample_init(&r->upsample, false) != OB_OK ||
        ob_edges_init(&r->edges) != OB_OK || ob_fill_init(&r->fill, false) != OB_OK ||
        ob_fill_init(&r->fill_rgb, true) != OB_OK || ob_lighting_init(&r->lighting) != OB_OK ||
        ob_shadows_init(&r->shadows) != OB_OK || ob_hdr_init(&r->hdr, d.width, d.height) != OB_OK) {
        ob_destroy_renderer(r);
        return NULL;
    }
    glCreateBuffers(1, &r->frame_ubo);
    glNamedBufferStorage(r->frame_ubo, sizeof(ob_frame_constants), NULL, GL_DYNAMIC_STORAGE_BIT);
    GLuint full[4] = {0, 0, 0, 0};
    make_full_targets(full, d.width, d.height, 0);
    r->ao = full[0];
    r->ao_is_one = false;
    r->final = full[1];
    r->direct = full[2];
    r->radiance = full[3];
    GLenum e = ob_gl_error();
    if (e != GL_NO_ERROR) {
        ob_set_error(OB_ERR_GL, "OpenGL error 0x%x making %dx%d targets", e, d.width, d.height);
        ob_destroy_renderer(r);
        return NULL;
    }
    return r;
}

ob_error ob_renderer_reshape(ob_renderer *r, int width, int height, int guard)
{
    if (check_size(r->ctx, width, height) != OB_OK) return OB_ERR_BAD_SIZE;
    if (check_guard(r->ctx, width, height, guard) != OB_OK) return OB_ERR_BAD_SIZE;
    if (width == r->width && height == r->height && guard == r->guard) return OB_OK;
    /* Errors raised before this call are not ours to report. */
    int drained = 0;
    while (drained++ < 64 && ob_gl_error() != GL_NO_ERROR) continue; /* bounded: a lost context repeats */
    /* Everything new is made before anything old is given up, so a failure leaves the renderer
     * whole at its old size and guard band. */
    const int inner_w = width + 2 * guard, inner_h = height + 2 * guard;
    GLuint full[4] = {0, 0, 0, 0};
    make_full_targets(full, width, height, guard);
    GLenum e = ob_gl_error();
    if (e != GL_NO_ERROR) {
        glDeleteTextures(4, full);
        return ob_set_error(OB_ERR_GL, "OpenGL error 0x%x making %dx%d targets (guard band %d px)", e, width, height,
                            guard);
    }
    const bool inner_changed = inner_w != r->inner_width || inner_h != r->inner_height;
    const bool visible_changed = width != r->width || height != r->height;
    ob_error err = inner_changed ? ob_gbuffer_resize(&r->gbuffer, inner_w, inner_h) : OB_OK;
    if (err == OB_OK && visible_changed) {
        err = ob_hdr_resize(&r->hdr, width, height);
        if (err != OB_OK && inner_changed) {
            const char *msg = NULL;
            ob_peek_error(&msg);
            char keep[1024] = "";
            snprintf(keep, sizeof keep, "%s", msg);
            ob_gbuffer_resize(&r->gbuffer, r->inner_width, r->inner_height);
            ob_set_error(err, "%s", keep);
        }
    }
    if (err != OB_OK) {
        glDeleteTextures(4, full);
        return err;
    }
    GLuint old[7] = {r->ao, r->final, r->direct, r->radiance, r->ao_rgb, r->bounce, r->bent};
    glDeleteTextures(7, old);
    r->ao = full[0];
    r->ao_is_one = false;
    r->final = full[1];
    r->direct = full[2];
    r->radiance = full[3];
    /* Remade at the new size by the next directional frame (ob_renderer_rgb_targets), like the AO scales
     * by ob_renderer_targets; the full-resolution scale's depth and normal were the old G-buffer's. */
    r->ao_rgb = 0;
    r->bounce = 0;
    r->bent = 0;
    release_scales(r);
    r->history_valid = false;
    r->last.scale = 0;
    r->width = width;
    r->height = height;
    r->guard = guard;
    r->inner_width = inner_w;
    r->inner_height = inner_h;
    r->has_frame = false;
    r->has_host_chain = false;
    return OB_OK;
}

void ob_renderer_reset_history(ob_renderer *r)
{
    if (!r) return;
    r->history_valid = false;
    /* The noise sequences (R2, golden ratio) start again with the history: a new history then
     * averages the best-spread prefix of each, and two runs after a reset see the same noise (the
     * flicker metric compares temporal on and off frame for frame). */
    r->frame = 0;
}

ob_error ob_renderer_resize(ob_renderer *r, int width, int height)
{
    if (!r) return ob_set_error(OB_ERR_INVALID_ARGUMENT, "ob_renderer_resize: NULL renderer");
    return ob_renderer_reshape(r, width, height, r->guard);
}

void ob_query_renderer_size(const ob_renderer *r, int *width, int *height)
{
    if (width) *width = r ? r->width : 0;
    if (height) *height = r ? r->height : 0;
}

ob_error ob_renderer_set_scene(ob_renderer *r, const ob_scene *scene)
{
    if (!r || !scene) return ob_set_error(OB_ERR_INVALID_ARGUMENT, "ob_renderer_set_scene: NULL argument");
    ob_error err = ob_gbuffer_set_scene(&r->gbuffer, scene);
    if (err != OB_OK) {
        /* Past its checks the G-buffer has released the old scene: none is drawn from now on,
         * so none may be claimed (ob_render_frame then says "no scene yet", not an empty frame). */
        if (err != OB_ERR_MODEL) r->has_scene = false;
        return err;
    }
    memcpy(r->bounds_min, scene->bounds_min, sizeof r->bounds_min);
    memcpy(r->bounds_max, scene->bounds_max, sizeof r->bounds_max);
    r->scene_radius = scene->ao_radius;
    memcpy(r->scene_lights, scene->lights, sizeof r->scene_lights);
    r->scene_light_count = scene->light_count;
    r->has_scene = true;
    return OB_OK;
}

ob_error ob_renderer_set_environment_rgb(ob_renderer *r, int width, int height, const float *rgb, const char *name)
{
    if (!r || !rgb) return ob_set_error(OB_ERR_INVALID_ARGUMENT, "ob_renderer_set_environment_rgb: NULL argument");
    return ob_environment_upload(&r->environment, rgb, width, height, name ? name : "(the host's pixels)");
}

void *ob_renderer_method_state(ob_renderer *r, int index, ob_error *err)
{
    *err = OB_OK;
    if (!r->method_states[index]) {
        r->method_states[index] = ob_method_make_state(ob_method_impl_at(index));
        if (!r->method_states[index]) *err = ob_peek_error(NULL);
    }
    return r->method_states[index];
}

void *ob_renderer_filter_state(ob_renderer *r, int index, bool rgb, ob_error *err)
{
    const ob_filter_impl *f = ob_filter_impl_at(index);
    void **states = rgb ? r->filter_states_rgb : r->filter_states;
    bool *ready = rgb ? r->filter_ready_rgb : r->filter_ready;
    void *(*init)(void) = rgb ? f->init_rgb : f->init;
    *err = OB_OK;
    if (!ready[index]) {
        if (init) {
            states[index] = init();
            if (!states[index]) {
                *err = ob_peek_error(NULL);
                return NULL;
            }
        }
        ready[index] = true;
    }
    return states[index];
}

/* The RGBA16F chains of directional methods, at this AO resolution and at full resolution. */
/* An RGBA16F target made the first time it is needed (0 until then, and again after a resize). */
static void need(GLuint *tex, int w, int h)
{
    if (!*tex) *tex = ob_make_texture_2d(GL_RGBA16F, w, h);
}

ob_error ob_renderer_rgb_targets(ob_renderer *r, ao_targets *t, bool directional, bool bent)
{
    int w = t->grid.width, h = t->grid.height;
    need(&t->scratch_rgb, w, h); /* both chains filter through it */
    if (directional) {
        need(&t->raw_rgb, w, h);
        need(&t->filtered_rgb, w, h);
        need(&t->bounce_raw, w, h);
        need(&t->bounce_filtered, w, h);
        need(&r->ao_rgb, r->inner_width, r->inner_height);
        need(&r->bounce, r->inner_width, r->inner_height);
    }
    if (bent) {
        need(&t->bent_raw, w, h);
        need(&t->bent_filtered, w, h);
        need(&r->bent, r->inner_width, r->inner_height);
    }
    if (!r->upsample_rgb.programs[0][0].program && ob_upsample_init(&r->upsample_rgb, true) != OB_OK)
        return ob_peek_error(NULL);
    GLenum e = ob_gl_error();
    if (e != GL_NO_ERROR) return ob_set_error(OB_ERR_GL, "OpenGL error 0x%x making the directional targets", e);
    return OB_OK;
}

ob_error ob_renderer_temporal_targets(ob_renderer *r, ao_targets *t)
{
    if (t->temporal_ready) return OB_OK;
    int w = t->grid.width, h = t->grid.height;
    /* All chains at once: a few AO-resolution textures, and a directional method switched on later
     * finds its histories there. */
    t->accum = ob_make_texture_2d(GL_R32F, w, h);
    t->accum_rgb = ob_make_texture_2d(GL_RGBA16F, w, h);
    t->bounce_accum = ob_make_texture_2d(GL_RGBA16F, w, h);
    for (int i = 0; i < 2; ++i) {
        t->history[i] = ob_make_texture_2d(GL_R32F, w, h);
        t->history_age[i] = ob_make_texture_2d(GL_R16F, w, h);
        t->history_rgb[i] = ob_make_texture_2d(GL_RGBA16F, w, h);
        t->bounce_history[i] = ob_make_texture_2d(GL_RGBA16F, w, h);
        /* Filtered: an RGB chain's Catmull-Rom resampling is five bilinear fetches (visibility's is
         * gathers). */
        GLuint filtered[2] = {t->history_rgb[i], t->bounce_history[i]};
        for (int k = 0; k < 2; ++k) {
            glTextureParameteri(filtered[k], GL_TEXTURE_MIN_FILTER, GL_LINEAR);
            glTextureParameteri(filtered[k], GL_TEXTURE_MAG_FILTER, GL_LINEAR);
        }
    }
    for (int i = 0; i < 2; ++i) {
        t->geometry[i].depth = ob_make_texture_2d(GL_R32F, w, h);
        t->geometry[i].normal = ob_make_texture_2d(GL_R32UI, w, h);
    }
    t->motion = ob_make_texture_2d(GL_RG16F, w, h);
    t->history_index = 0;
    t->temporal_ready = true;
    r->history_valid = false; /* new textures hold no history */
    GLenum e = ob_gl_error();
    if (e != GL_NO_ERROR) return ob_set_error(OB_ERR_GL, "OpenGL error 0x%x making the temporal targets", e);
    return OB_OK;
}

GLuint ob_renderer_second_layer(const ob_renderer *r)
{
    bool made = r->last.second_layer && r->peel.width == r->gbuffer.width && r->peel.height == r->gbuffer.height;
    return made ? r->peel.linear_depth : 0;
}

GLuint ob_renderer_extra_direct(const ob_renderer *r)
{
    bool made = r->last.extra_view && r->extra_gbuffer.width == r->gbuffer.width &&
                r->extra_gbuffer.height == r->gbuffer.height;
    return made ? r->extra_direct : 0;
}

ao_targets *ob_renderer_targets(ob_renderer *r, int index)
{
    ao_targets *t = &r->scales[index];
    if (t->ready) return t;
    t->grid = ob_ao_grid_make(r->inner_width, r->inner_height, 1 << index);
    int w = t->grid.width, h = t->grid.height;
    if (index == 0) {
        t->depth = r->gbuffer.linear_depth;
        t->normal = r->gbuffer.normal;
    } else {
        t->depth = ob_make_texture_2d(GL_R32F, w, h);
        t->normal = ob_make_texture_2d(GL_RGBA16F, w, h);
    }
    t->raw = ob_make_texture_2d(GL_R32F, w, h);
    t->filtered = ob_make_texture_2d(GL_R32F, w, h);
    t->scratch = ob_make_texture_2d(GL_R32F, w, h);
    t->multiplier = ob_make_texture_2d(GL_R32F, (w + OB_EDGE_BLOCK - 1) / OB_EDGE_BLOCK,
                                       (h + OB_EDGE_BLOCK - 1) / OB_EDGE_BLOCK);
    t->ready = true;
    return t;
}
