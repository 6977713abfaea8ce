/* The frame (DESIGN.md "The frame"), each pass timed:
 *   [shadow maps] -> gbuffer -> lighting (direct light, shadowed) -> [downsample to the AO
 *   resolution] -> [edges, for adaptive sample counts] -> ao -> filter (at the AO resolution)
 *   -> [joint bilateral upsample] -> compose (HDR radiance) -> luminance, bloom, tonemap.
 * The CLI, the tests and later the viewer all render through here. */
#include <cglm/cglm.h>
#include <limits.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "core/error.h"
#include "filters/filter.h"
#include "methods/method.h"
#include "passes/passes.h"

/* Targets at one AO resolution (k = 1, 2 or 4), made when a frame first asks for it. */
typedef struct ao_targets {
    ob_ao_grid grid;
    GLuint depth, normal;      /* k > 1: downsampled (owned); k = 1: the G-buffer's (not owned) */
    GLuint raw, filtered, scratch;
    GLuint multiplier;         /* adaptive sample counts, one per OB_EDGE_BLOCK^2 pixels */
    /* Directional methods (SSDO): RGBA16F M and bounce chains, made when one first runs. */
    GLuint raw_rgb, filtered_rgb, scratch_rgb, bounce_raw, bounce_filtered;
    bool ready, rgb_ready;
} ao_targets;

enum { SCALES = 3 }; /* k = 1, 2, 4 */

struct ob_renderer {
    ob_context *ctx;
    int width, height;
    ob_gbuffer gbuffer;
    ob_compute_pass downsample, upsample, edges;
    ob_compute_pass upsample_rgb;  /* made with the first directional frame */
    bool upsample_rgb_ready;
    ob_compose_pass compose;
    ob_lighting_pass lighting;
    ob_shadow_maps shadows;
    ob_hdr_pass hdr;
    ob_environment environment;
    ao_targets scales[SCALES];
    int last_scale;            /* index into scales of the last frame */
    GLuint ao, final;          /* full resolution */
    GLuint direct;             /* RGBA16F direct radiance; alpha = the key light's visibility */
    GLuint radiance;           /* RGBA16F composed HDR radiance, before tone mapping */
    GLuint ao_rgb, bounce;     /* RGBA16F full-resolution SSDO M and bounce (made on first use) */
    void **method_states;      /* lazily made, one per registry entry */
    bool *method_ready;
    void **filter_states;      /* the same for filters */
    bool *filter_ready;
    void **filter_states_rgb;  /* and their RGBA16F variants (init_rgb) */
    bool *filter_ready_rgb;
    ob_timer_set timers;
    bool has_scene;
    float bounds_min[3], bounds_max[3];
    float scene_radius;
    ob_light scene_lights[OB_MAX_LIGHTS];
    int scene_light_count;
    uint32_t frame;
    int last_method;           /* what the last frame ran, for the sample-count view */
    float last_params[OB_MAX_PARAMS];
    bool last_adaptive;
    bool last_rgb;             /* the last frame's method was directional */
    bool has_frame;            /* the targets hold a whole frame (ob_present) */
    float last_far;            /* the last frame's far plane (the depth view's scale) */
    ob_view_pass view;         /* ob_present */
};

/* Delete every AO-resolution target and mark each scale not ready, so the next frame remakes it. */
static void release_scales(ob_renderer *r)
{
    for (int i = 0; i < SCALES; ++i) {
        ao_targets *t = &r->scales[i];
        GLuint tex[4] = {t->raw, t->filtered, t->scratch, t->multiplier};
        glDeleteTextures(4, tex);
        GLuint rgb[5] = {t->raw_rgb, t->filtered_rgb, t->scratch_rgb, t->bounce_raw, t->bounce_filtered};
        glDeleteTextures(5, rgb);
        if (t->grid.k > 1) {
            GLuint own[2] = {t->depth, t->normal};
            glDeleteTextures(2, own);
        }
        memset(t, 0, sizeof *t);
    }
}

/* The renderer's own full-resolution targets, in the order ao, final, direct, radiance. */
static void make_full_targets(GLuint tex[4], int width, int height)
{
    tex[0] = ob_make_texture_2d(GL_R32F, width, height);
    tex[1] = ob_make_texture_2d(GL_RGBA8, width, height);
    tex[2] = ob_make_texture_2d(GL_RGBA16F, width, height);
    tex[3] = ob_make_texture_2d(GL_RGBA16F, width, height);
}

static ob_error check_size(const ob_context *ctx, int width, int height)
{
    if (width <= 0 || height <= 0 || width > ctx->max_texture_size || height > ctx->max_texture_size)
        return ob_set_error(OB_ERR_BAD_SIZE, "size %dx%d is outside 1..%d (GL_MAX_TEXTURE_SIZE of %s)", width, height,
                            ctx->max_texture_size, ctx->renderer);
    return OB_OK;
}

void ob_destroy_renderer(ob_renderer *r)
{
    if (!r) return;
    for (int i = 0; i < ob_method_count(); ++i) {
        const ob_method_impl *m = ob_method_impl_at(i);
        if (r->method_ready && r->method_ready[i] && m->destroy) m->destroy(r->method_states[i]);
    }
    for (int i = 0; i < ob_filter_count(); ++i) {
        const ob_filter_impl *f = ob_filter_impl_at(i);
        if (r->filter_ready && r->filter_ready[i] && f->destroy) f->destroy(r->filter_states[i]);
        if (r->filter_ready_rgb && r->filter_ready_rgb[i] && f->destroy) f->destroy(r->filter_states_rgb[i]);
    }
    free(r->filter_states_rgb);
    free(r->filter_ready_rgb);
    free(r->method_states);
    free(r->method_ready);
    free(r->filter_states);
    free(r->filter_ready);
    release_scales(r);
    ob_view_destroy(&r->view);
    ob_gbuffer_destroy(&r->gbuffer);
    ob_compute_pass_destroy(&r->downsample);
    ob_compute_pass_destroy(&r->upsample);
    ob_compute_pass_destroy(&r->upsample_rgb);
    ob_compute_pass_destroy(&r->edges);
    ob_compose_destroy(&r->compose);
    ob_lighting_destroy(&r->lighting);
    ob_shadows_destroy(&r->shadows);
    ob_hdr_destroy(&r->hdr);
    ob_environment_destroy(&r->environment);
    GLuint tex[6] = {r->ao, r->final, r->direct, r->radiance, r->ao_rgb, r->bounce};
    glDeleteTextures(6, tex);
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
    ob_renderer *r = calloc(1, sizeof *r);
    if (!r) {
        ob_set_error(OB_ERR_OUT_OF_MEMORY, "out of memory making the renderer");
        return NULL;
    }
    r->ctx = ctx;
    r->width = d.width;
    r->height = d.height;
    r->method_states = calloc((size_t)ob_method_count(), sizeof *r->method_states);
    r->method_ready = calloc((size_t)ob_method_count(), sizeof *r->method_ready);
    r->filter_states = calloc((size_t)ob_filter_count(), sizeof *r->filter_states);
    r->filter_ready = calloc((size_t)ob_filter_count(), sizeof *r->filter_ready);
    r->filter_states_rgb = calloc((size_t)ob_filter_count(), sizeof *r->filter_states_rgb);
    r->filter_ready_rgb = calloc((size_t)ob_filter_count(), sizeof *r->filter_ready_rgb);
    ob_timers_init(&r->timers);
    if (!r->method_states || !r->method_ready || !r->filter_states || !r->filter_ready || !r->filter_states_rgb ||
        !r->filter_ready_rgb) {
        ob_set_error(OB_ERR_OUT_OF_MEMORY, "out of memory making the renderer");
        ob_destroy_renderer(r);
        return NULL;
    }
    if (ob_gbuffer_init(&r->gbuffer, d.width, d.height) != OB_OK || ob_compose_init(&r->compose) != OB_OK ||
        ob_downsample_init(&r->downsample) != OB_OK || ob_upsample_init(&r->upsample) != OB_OK ||
        ob_edges_init(&r->edges) != OB_OK || ob_lighting_init(&r->lighting) != OB_OK ||
        ob_shadows_init(&r->shadows) != OB_OK || ob_hdr_init(&r->hdr, d.width, d.height) != OB_OK) {
        ob_destroy_renderer(r);
        return NULL;
    }
    GLuint full[4] = {0, 0, 0, 0};
    make_full_targets(full, d.width, d.height);
    r->ao = full[0];
    r->final = full[1];
    r->direct = full[2];
    r->radiance = full[3];
    GLenum e = glGetError();
    if (e != GL_NO_ERROR) {
        ob_set_error(OB_ERR_GL, "OpenGL error 0x%x making %dx%d targets", e, d.width, d.height);
        ob_destroy_renderer(r);
        return NULL;
    }
    return r;
}

ob_error ob_renderer_resize(ob_renderer *r, int width, int height)
{
    if (!r) return ob_set_error(OB_ERR_INVALID_ARGUMENT, "ob_renderer_resize: NULL renderer");
    if (check_size(r->ctx, width, height) != OB_OK) return OB_ERR_BAD_SIZE;
    if (width == r->width && height == r->height) return OB_OK;
    /* Errors raised before this call are not ours to report. */
    int drained = 0;
    while (drained++ < 64 && glGetError() != GL_NO_ERROR) continue; /* bounded: a lost context repeats */
    /* Everything new is made before anything old is given up, so a failure leaves the renderer
     * whole at its old size. */
    GLuint full[4] = {0, 0, 0, 0};
    make_full_targets(full, width, height);
    GLenum e = glGetError();
    if (e != GL_NO_ERROR) {
        glDeleteTextures(4, full);
        return ob_set_error(OB_ERR_GL, "OpenGL error 0x%x making %dx%d targets", e, width, height);
    }
    int old_width = r->width, old_height = r->height;
    ob_error err = ob_gbuffer_resize(&r->gbuffer, width, height);
    if (err == OB_OK) {
        err = ob_hdr_resize(&r->hdr, width, height);
        if (err != OB_OK) {
            const char *msg = NULL;
            ob_peek_error(&msg);
            char keep[1024] = "";
            snprintf(keep, sizeof keep, "%s", msg);
            ob_gbuffer_resize(&r->gbuffer, old_width, old_height);
            ob_set_error(err, "%s", keep);
        }
    }
    if (err != OB_OK) {
        glDeleteTextures(4, full);
        return err;
    }
    GLuint old[6] = {r->ao, r->final, r->direct, r->radiance, r->ao_rgb, r->bounce};
    glDeleteTextures(6, old);
    r->ao = full[0];
    r->final = full[1];
    r->direct = full[2];
    r->radiance = full[3];
    /* Remade at the new size by the next directional frame (rgb_targets_for), like the AO scales
     * by targets_for; the full-resolution scale's depth and normal were the old G-buffer's. */
    r->ao_rgb = 0;
    r->bounce = 0;
    release_scales(r);
    r->last_scale = 0;
    r->width = width;
    r->height = height;
    r->has_frame = false;
    return OB_OK;
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
    if (err != OB_OK) return err;
    memcpy(r->bounds_min, scene->bounds_min, sizeof r->bounds_min);
    memcpy(r->bounds_max, scene->bounds_max, sizeof r->bounds_max);
    r->scene_radius = scene->ao_radius;
    memcpy(r->scene_lights, scene->lights, sizeof r->scene_lights);
    r->scene_light_count = scene->light_count;
    r->has_scene = true;
    return OB_OK;
}

static void *filter_state(ob_renderer *r, int index, bool rgb, ob_error *err)
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
static ob_error rgb_targets_for(ob_renderer *r, ao_targets *t)
{
    if (!t->rgb_ready) {
        int w = t->grid.width, h = t->grid.height;
        t->raw_rgb = ob_make_texture_2d(GL_RGBA16F, w, h);
        t->filtered_rgb = ob_make_texture_2d(GL_RGBA16F, w, h);
        t->scratch_rgb = ob_make_texture_2d(GL_RGBA16F, w, h);
        t->bounce_raw = ob_make_texture_2d(GL_RGBA16F, w, h);
        t->bounce_filtered = ob_make_texture_2d(GL_RGBA16F, w, h);
        t->rgb_ready = true;
    }
    if (!r->ao_rgb) r->ao_rgb = ob_make_texture_2d(GL_RGBA16F, r->width, r->height);
    if (!r->bounce) r->bounce = ob_make_texture_2d(GL_RGBA16F, r->width, r->height);
    if (!r->upsample_rgb_ready) {
        if (ob_upsample_init_rgb(&r->upsample_rgb) != OB_OK) return ob_peek_error(NULL);
        r->upsample_rgb_ready = true;
    }
    GLenum e = glGetError();
    if (e != GL_NO_ERROR) return ob_set_error(OB_ERR_GL, "OpenGL error 0x%x making the SSDO targets", e);
    return OB_OK;
}

static int scale_index(int divisor) { return divisor == 2 ? 1 : divisor == 4 ? 2 : 0; }

static ao_targets *targets_for(ob_renderer *r, int index)
{
    ao_targets *t = &r->scales[index];
    if (t->ready) return t;
    t->grid = ob_ao_grid_make(r->width, r->height, 1 << index);
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

static void *method_state(ob_renderer *r, int index, ob_error *err)
{
    const ob_method_impl *m = ob_method_impl_at(index);
    *err = OB_OK;
    if (!r->method_ready[index]) {
        if (m->init) {
            r->method_states[index] = m->init();
            if (!r->method_states[index]) {
                *err = ob_peek_error(NULL);
                return NULL;
            }
        }
        r->method_ready[index] = true;
    }
    return r->method_states[index];
}

/* Parameters as the method sees them: explicit values, else defaults, with radii that were not
 * set following the scene. */
static void resolve_params(const ob_renderer *r, const ob_settings *s, float *out)
{
    const ob_method_info *m = ob_method_at(s->method);
    for (int i = 0; i < m->param_count; ++i) {
        out[i] = s->params[i];
        if (m->params[i].follows_scene_radius && !(s->params_set & (1u << i)) && r->scene_radius > 0.0f)
            out[i] = r->scene_radius;
    }
}

static void proj_info_from(const float *proj, float out[4]);
static void proj_info_from(const float *proj, float out[4])
{
    /* Column-major: P00 = proj[0], P11 = proj[5], P20 = proj[8], P21 = proj[9]. */
    out[0] = 1.0f / proj[0];
    out[1] = 1.0f / proj[5];
    out[2] = proj[8];
    out[3] = proj[9];
}

static ob_error run_method(ob_renderer *r, const ob_ao_inputs *in, const ob_settings *s, GLuint ao_out)
{
    ob_error err = OB_OK;
    void *state = method_state(r, s->method, &err);
    if (err != OB_OK) return err;
    float params[OB_MAX_PARAMS] = {0};
    resolve_params(r, s, params);
    r->last_method = s->method;
    memcpy(r->last_params, params, sizeof params);
    r->last_adaptive = in->sample_multiplier != 0;
    return ob_method_impl_at(s->method)->run(state, in, params, ao_out);
}

static ob_error check_settings(const ob_settings *s)
{
    if (!s || !ob_method_at(s->method) || !ob_filter_at(s->filter))
        return ob_set_error(OB_ERR_INVALID_ARGUMENT, "settings are not initialised");
    if (s->ao_divisor != 0 && s->ao_divisor != 1 && s->ao_divisor != 2 && s->ao_divisor != 4)
        return ob_set_error(OB_ERR_OUT_OF_RANGE, "ao divisor %d is not 1, 2 or 4", s->ao_divisor);
    return OB_OK;
}

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
    if (!(cam.fov_y_deg < 179.0f) || !isfinite(cam.eye[0] + cam.eye[1] + cam.eye[2] + cam.target[0] + cam.target[1] + cam.target[2]))
        return ob_set_error(OB_ERR_INVALID_ARGUMENT, "camera is not finite or its fov is not in (0, 179)");

    mat4 view, proj;
    glm_lookat(cam.eye, cam.target, cam.up, view);
    glm_perspective(glm_rad(cam.fov_y_deg), (float)r->width / (float)r->height, cam.near_z, cam.far_z, proj);

    int si = scale_index(s->ao_divisor);
    ao_targets *t = targets_for(r, si);
    r->last_scale = si;
    const ob_ao_grid *g = &t->grid;

    ob_ao_inputs in;
    memset(&in, 0, sizeof in);
    in.linear_depth = t->depth;
    in.view_normal = t->normal;
    in.width = g->width;
    in.height = g->height;
    grid_projection(g, (const float *)proj, in.proj);
    proj_info_from(in.proj, in.proj_info);
    in.frame = r->frame++;
    in.sample_multiplier = s->adaptive ? t->multiplier : 0;
    const bool rgb = ob_method_impl_at(s->method)->rgb;
    /* Directional methods with their bounce turned off leave the bounce chain idle. */
    const bool has_bounce = rgb && !(ob_settings_get(s, "bounce") == 0.0f);

    const ob_light *lights = s->light_count > 0 ? s->lights : r->scene_lights;
    int light_count = s->light_count > 0 ? s->light_count : r->scene_light_count;
    mat4 inv_view;
    glm_mat4_inv(view, inv_view);
    float full_info[4];
    proj_info_from((const float *)proj, full_info);

    /* From here the targets are being overwritten: no whole frame to present until the end. */
    r->has_frame = false;
    ob_timers_frame_begin(&r->timers);
    ob_error err = ob_shadows_render(&r->shadows, &r->gbuffer, lights, light_count, r->bounds_min, r->bounds_max,
                                     &s->shadow, &r->timers);
    if (err != OB_OK) {
        ob_timers_frame_end(&r->timers);
        return err;
    }
    ob_timer_begin(&r->timers, "gbuffer");
    ob_gbuffer_run(&r->gbuffer, (const float *)view, (const float *)proj);
    /* Each compute pass reads what the previous one wrote with image stores or as attachments. */
    const GLbitfield barrier = GL_TEXTURE_FETCH_BARRIER_BIT | GL_SHADER_IMAGE_ACCESS_BARRIER_BIT;
    glMemoryBarrier(barrier | GL_FRAMEBUFFER_BARRIER_BIT);
    ob_timer_begin(&r->timers, "lighting");
    ob_lighting_setup(&r->lighting, lights, light_count, (const float *)inv_view, full_info, r->width, r->height);
    ob_shadows_fill(&r->shadows, &r->lighting.constants);
    ob_lighting_run(&r->lighting, r->gbuffer.linear_depth, r->gbuffer.normal, r->gbuffer.albedo, r->direct);
    glMemoryBarrier(barrier);
    if (g->k > 1) {
        ob_timer_begin(&r->timers, "downsample");
        ob_downsample_run(&r->downsample, g, r->gbuffer.linear_depth, r->gbuffer.normal, t->depth, t->normal);
        glMemoryBarrier(barrier);
    }
    if (s->adaptive) {
        ob_timer_begin(&r->timers, "edges");
        ob_edges_run(&r->edges, g, t->depth, t->normal, t->multiplier);
        glMemoryBarrier(barrier);
    }
    if (rgb) {
        err = rgb_targets_for(r, t);
        if (err != OB_OK) {
            ob_timers_frame_end(&r->timers);
            return err;
        }
        /* SSDO reads the direct light just written, the lights and the ambient (ob_ao_inputs). */
        in.direct = r->direct;
        in.albedo = r->gbuffer.albedo;
        in.grid_k = g->k;
        in.grid_o = g->o;
        in.lights = &r->lighting.constants;
        in.ambient_mode = s->ambient_mode;
        memcpy(in.ambient, s->ambient, sizeof in.ambient);
        memcpy(in.sky, s->sky, sizeof in.sky);
        memcpy(in.ground, s->ground, sizeof in.ground);
        memcpy(in.sh, r->environment.sh, sizeof in.sh);
        in.bounce_out = t->bounce_raw;
    }
    r->last_rgb = rgb;
    ob_timer_begin(&r->timers, "ao");
    err = run_method(r, &in, s, rgb ? t->raw_rgb : t->raw);
    if (err != OB_OK) {
        ob_timers_frame_end(&r->timers);
        return err;
    }
    glMemoryBarrier(barrier);
    ob_timer_begin(&r->timers, "filter");
    void *fstate = filter_state(r, s->filter, rgb, &err);
    if (err != OB_OK) {
        ob_timers_frame_end(&r->timers);
        return err;
    }
    const ob_filter_impl *filter = ob_filter_impl_at(s->filter);
    if (!rgb) {
        const ob_filter_inputs fin = {.src = t->raw, .dst = g->k > 1 ? t->filtered : r->ao, .scratch = t->scratch,
                                      .linear_depth = t->depth, .view_normal = t->normal, .width = g->width,
                                      .height = g->height, .rgb = false, .sky = 1.0f};
        err = filter->run(fstate, &fin, s->filter_params);
    } else {
        /* M and the bounce through the same filter (seed 003 §5.3 smooths them separately); the
         * sky is 1 in M and 0 in the bounce. The barrier orders the shared scratch target. */
        const ob_filter_inputs fm = {.src = t->raw_rgb, .dst = g->k > 1 ? t->filtered_rgb : r->ao_rgb,
                                     .scratch = t->scratch_rgb, .linear_depth = t->depth, .view_normal = t->normal,
                                     .width = g->width, .height = g->height, .rgb = true, .sky = 1.0f};
        const ob_filter_inputs fb = {.src = t->bounce_raw, .dst = g->k > 1 ? t->bounce_filtered : r->bounce,
                                     .scratch = t->scratch_rgb, .linear_depth = t->depth, .view_normal = t->normal,
                                     .width = g->width, .height = g->height, .rgb = true, .sky = 0.0f};
        err = filter->run(fstate, &fm, s->filter_params);
        glMemoryBarrier(barrier);
        if (err == OB_OK && has_bounce) err = filter->run(fstate, &fb, s->filter_params);
    }
    if (err != OB_OK) {
        ob_timers_frame_end(&r->timers);
        return err;
    }
    glMemoryBarrier(barrier);
    if (g->k > 1) {
        ob_timer_begin(&r->timers, "upsample");
        if (!rgb) {
            ob_upsample_run(&r->upsample, g, r->gbuffer.linear_depth, r->gbuffer.normal, t->depth, t->normal,
                            t->filtered, r->ao);
        } else {
            ob_upsample_run_rgb(&r->upsample_rgb, g, r->gbuffer.linear_depth, r->gbuffer.normal, t->depth, t->normal,
                                t->filtered_rgb, r->ao_rgb, 1.0f);
            if (has_bounce)
                ob_upsample_run_rgb(&r->upsample_rgb, g, r->gbuffer.linear_depth, r->gbuffer.normal, t->depth,
                                    t->normal, t->bounce_filtered, r->bounce, 0.0f);
        }
        glMemoryBarrier(barrier);
    }
    GLuint ao = rgb ? r->ao_rgb : r->ao;
    if (rgb && !has_bounce) {
        /* Bounce off: nothing to filter or upsample; the bounce view reads zeros. */
        const float zero[4] = {0.0f, 0.0f, 0.0f, 0.0f};
        glClearTexImage(r->bounce, 0, GL_RGBA, GL_FLOAT, zero);
    }

    ob_compose_inputs ci;
    memset(&ci, 0, sizeof ci);
    ci.linear_depth = r->gbuffer.linear_depth;
    ci.normal = r->gbuffer.normal;
    ci.albedo = r->gbuffer.albedo;
    ci.ao = ao;
    ci.direct = r->direct;
    ci.environment = r->environment.texture;
    ci.width = r->width;
    ci.height = r->height;
    memcpy(ci.proj_info, full_info, sizeof ci.proj_info);
    memcpy(ci.inv_view, inv_view, sizeof ci.inv_view);
    ci.ambient_mode = s->ambient_mode;
    memcpy(ci.ambient, s->ambient, sizeof ci.ambient);
    memcpy(ci.sky, s->sky, sizeof ci.sky);
    memcpy(ci.ground, s->ground, sizeof ci.ground);
    memcpy(ci.background, s->background, sizeof ci.background);
    memcpy(ci.sh, r->environment.sh, sizeof ci.sh);
    ci.ao_all_light = s->ao_all_light;
    ci.directional = rgb;
    ci.bounce = has_bounce ? r->bounce : 0;
    ob_timer_begin(&r->timers, "compose");
    ob_compose_run(&r->compose, &ci, r->radiance);
    glMemoryBarrier(barrier);
    ob_hdr_run(&r->hdr, r->radiance, &s->hdr, r->final, &r->timers);
    glMemoryBarrier(GL_TEXTURE_UPDATE_BARRIER_BIT | barrier);
    ob_timers_frame_end(&r->timers);
    GLenum e = glGetError();
    if (e != GL_NO_ERROR) return ob_set_error(OB_ERR_GL, "OpenGL error 0x%x during the frame", e);
    r->has_frame = true;
    r->last_far = cam.far_z;
    return OB_OK;
}

ob_error ob_compute_ao(ob_renderer *r, uint32_t linear_depth_tex, uint32_t normal_tex, const float proj[16],
                       const ob_settings *s, uint32_t ao_out_tex)
{
    if (!r || !proj || !linear_depth_tex || !normal_tex || !ao_out_tex)
        return ob_set_error(OB_ERR_INVALID_ARGUMENT, "ob_compute_ao: NULL argument");
    if (check_settings(s) != OB_OK) return ob_peek_error(NULL);
    if (ob_method_impl_at(s->method)->rgb)
        return ob_set_error(OB_ERR_INVALID_ARGUMENT, "ob_compute_ao: %s needs the frame's direct light (ob_render_frame)",
                            ob_method_at(s->method)->name);
    ob_ao_inputs in;
    memset(&in, 0, sizeof in);
    in.linear_depth = linear_depth_tex;
    in.view_normal = normal_tex;
    in.width = r->width;
    in.height = r->height;
    memcpy(in.proj, proj, sizeof in.proj);
    proj_info_from(in.proj, in.proj_info);
    in.frame = r->frame++;
    glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT | GL_SHADER_IMAGE_ACCESS_BARRIER_BIT);
    ob_error err = run_method(r, &in, s, ao_out_tex);
    glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT | GL_SHADER_IMAGE_ACCESS_BARRIER_BIT);
    return err;
}

/* Per-pixel sample counts of the last frame at full resolution: the method's count, or under
 * adaptive sampling its base x the edge pass's multiplier. */
static ob_error read_sample_counts(ob_renderer *r, float *dst)
{
    const ao_targets *t = &r->scales[r->last_scale];
    if (!t->ready) return ob_set_error(OB_ERR_INVALID_ARGUMENT, "no frame rendered yet");
    const ob_method_impl *m = ob_method_impl_at(r->last_method);
    int samples = ob_method_samples(m, r->last_params);
    int bw = (t->grid.width + OB_EDGE_BLOCK - 1) / OB_EDGE_BLOCK, bh = (t->grid.height + OB_EDGE_BLOCK - 1) / OB_EDGE_BLOCK;
    float *mult = NULL;
    float *depth = malloc((size_t)r->width * (size_t)r->height * sizeof(float));
    if (!depth) return ob_set_error(OB_ERR_OUT_OF_MEMORY, "out of memory reading sample counts");
    glGetTextureImage(r->gbuffer.linear_depth, 0, GL_RED, GL_FLOAT,
                      (GLsizei)((size_t)r->width * (size_t)r->height * sizeof(float)), depth);
    if (r->last_adaptive && m->adapts) {
        mult = malloc((size_t)bw * (size_t)bh * sizeof(float));
        if (!mult) {
            free(depth);
            return ob_set_error(OB_ERR_OUT_OF_MEMORY, "out of memory reading sample counts");
        }
        glGetTextureImage(t->multiplier, 0, GL_RED, GL_FLOAT, (GLsizei)((size_t)bw * (size_t)bh * sizeof(float)), mult);
    }
    for (int y = 0; y < r->height; ++y)
        for (int x = 0; x < r->width; ++x) {
            int bx = (x / t->grid.k) / OB_EDGE_BLOCK, by = (y / t->grid.k) / OB_EDGE_BLOCK;
            size_t i = (size_t)y * (size_t)r->width + (size_t)x;
            float count = (float)samples;
            if (mult) count = (float)ob_adaptive_base(samples) * mult[(size_t)by * (size_t)bw + (size_t)bx];
            dst[i] = depth[i] > 0.0f ? count : 0.0f; /* the sky takes no samples */
        }
    free(mult);
    free(depth);
    return OB_OK;
}

/* An RGBA16F target as 3 floats per pixel, or (channels 1) the average of its three channels:
 * the AO views of a directional method show M's mean. */
static ob_error read_rgb(GLuint tex, int w, int h, float *dst, int channels)
{
    size_t n = (size_t)w * (size_t)h;
    float *rgba = malloc(n * 4 * sizeof(float));
    if (!rgba) return ob_set_error(OB_ERR_OUT_OF_MEMORY, "out of memory reading an image");
    glGetTextureImage(tex, 0, GL_RGBA, GL_FLOAT, (GLsizei)(n * 4 * sizeof(float)), rgba);
    for (size_t i = 0; i < n; ++i) {
        if (channels == 1) {
            dst[i] = (rgba[4 * i] + rgba[4 * i + 1] + rgba[4 * i + 2]) / 3.0f;
        } else {
            for (int c = 0; c < 3; ++c) dst[3 * i + (size_t)c] = rgba[4 * i + (size_t)c];
        }
    }
    free(rgba);
    GLenum e = glGetError();
    if (e != GL_NO_ERROR) return ob_set_error(OB_ERR_GL, "OpenGL error 0x%x reading an image", e);
    return OB_OK;
}

size_t ob_image_size(const ob_renderer *r, ob_image_kind kind)
{
    if (!r) return 0;
    size_t px = (size_t)r->width * (size_t)r->height;
    switch (kind) {
    case OB_IMAGE_FINAL_RGBA8: return px * 4;
    case OB_IMAGE_AO_RAW_F32: {
        const ob_ao_grid *g = &r->scales[r->last_scale].grid;
        return (size_t)(g->width > 0 ? g->width : r->width) * (size_t)(g->height > 0 ? g->height : r->height) *
               sizeof(float);
    }
    case OB_IMAGE_SAMPLES_F32:
    case OB_IMAGE_AO_F32:
    case OB_IMAGE_DEPTH_F32: return px * sizeof(float);
    case OB_IMAGE_NORMAL_F32:
    case OB_IMAGE_RADIANCE_F32:
    case OB_IMAGE_AO_RGB_F32:
    case OB_IMAGE_BOUNCE_F32:
    case OB_IMAGE_HDR_F32:
    case OB_IMAGE_ALBEDO_F32: return px * 3 * sizeof(float);
    case OB_IMAGE_SHADOW_F32: return px * sizeof(float);
    }
    return 0;
}

ob_error ob_read_image(ob_renderer *r, ob_image_kind kind, void *dst, size_t dst_size)
{
    size_t need = ob_image_size(r, kind);
    if (!r || !dst || need == 0) return ob_set_error(OB_ERR_INVALID_ARGUMENT, "ob_read_image: bad argument");
    if (dst_size < need) return ob_set_error(OB_ERR_INVALID_ARGUMENT, "ob_read_image: buffer of %zu bytes, need %zu", dst_size, need);
    glPixelStorei(GL_PACK_ALIGNMENT, 1);
    switch (kind) {
    case OB_IMAGE_FINAL_RGBA8: {
        glGetTextureImage(r->final, 0, GL_RGBA, GL_UNSIGNED_BYTE, (GLsizei)need, dst);
        /* GL's rows run bottom to top; image files want top first. */
        size_t row = (size_t)r->width * 4;
        unsigned char *p = dst;
        unsigned char *tmp = malloc(row);
        if (!tmp) return ob_set_error(OB_ERR_OUT_OF_MEMORY, "out of memory reading the image");
        for (int y = 0; y < r->height / 2; ++y) {
            unsigned char *a = p + (size_t)y * row, *b = p + (size_t)(r->height - 1 - y) * row;
            memcpy(tmp, a, row);
            memcpy(a, b, row);
            memcpy(b, tmp, row);
        }
        free(tmp);
        break;
    }
    case OB_IMAGE_AO_F32:
        if (r->last_rgb) return read_rgb(r->ao_rgb, r->width, r->height, dst, 1);
        glGetTextureImage(r->ao, 0, GL_RED, GL_FLOAT, (GLsizei)need, dst);
        break;
    case OB_IMAGE_AO_RAW_F32:
        if (!r->scales[r->last_scale].ready) return ob_set_error(OB_ERR_INVALID_ARGUMENT, "no frame rendered yet");
        if (r->last_rgb) {
            const ao_targets *t = &r->scales[r->last_scale];
            return read_rgb(t->raw_rgb, t->grid.width, t->grid.height, dst, 1);
        }
        glGetTextureImage(r->scales[r->last_scale].raw, 0, GL_RED, GL_FLOAT, (GLsizei)need, dst);
        break;
    case OB_IMAGE_AO_RGB_F32:
        if (r->last_rgb) return read_rgb(r->ao_rgb, r->width, r->height, dst, 3);
        /* An AO method: its visibility in all three channels. */
        glGetTextureImage(r->ao, 0, GL_RED, GL_FLOAT, (GLsizei)(need / 3), dst);
        for (size_t i = need / sizeof(float) / 3; i-- > 0;) {
            float v = ((float *)dst)[i];
            for (int c = 0; c < 3; ++c) ((float *)dst)[3 * i + (size_t)c] = v;
        }
        break;
    case OB_IMAGE_BOUNCE_F32:
        if (r->last_rgb) return read_rgb(r->bounce, r->width, r->height, dst, 3);
        memset(dst, 0, need);
        break;
    case OB_IMAGE_SAMPLES_F32: {
        ob_error e = read_sample_counts(r, dst);
        if (e != OB_OK) return e;
        break;
    }
    case OB_IMAGE_DEPTH_F32: glGetTextureImage(r->gbuffer.linear_depth, 0, GL_RED, GL_FLOAT, (GLsizei)need, dst); break;
    case OB_IMAGE_NORMAL_F32: glGetTextureImage(r->gbuffer.normal, 0, GL_RGB, GL_FLOAT, (GLsizei)need, dst); break;
    case OB_IMAGE_RADIANCE_F32: glGetTextureImage(r->direct, 0, GL_RGB, GL_FLOAT, (GLsizei)need, dst); break;
    case OB_IMAGE_HDR_F32: glGetTextureImage(r->radiance, 0, GL_RGB, GL_FLOAT, (GLsizei)need, dst); break;
    case OB_IMAGE_ALBEDO_F32: glGetTextureImage(r->gbuffer.albedo, 0, GL_RGB, GL_FLOAT, (GLsizei)need, dst); break;
    case OB_IMAGE_SHADOW_F32: {
        /* The key light's visibility is the direct-light target's alpha. */
        size_t n = (size_t)r->width * (size_t)r->height;
        float *rgba = malloc(n * 4 * sizeof(float));
        if (!rgba) return ob_set_error(OB_ERR_OUT_OF_MEMORY, "out of memory reading the shadow view");
        glGetTextureImage(r->direct, 0, GL_RGBA, GL_FLOAT, (GLsizei)(n * 4 * sizeof(float)), rgba);
        for (size_t i = 0; i < n; ++i) ((float *)dst)[i] = rgba[4 * i + 3];
        free(rgba);
        break;
    }
    }
    GLenum e = glGetError();
    if (e != GL_NO_ERROR) return ob_set_error(OB_ERR_GL, "OpenGL error 0x%x reading an image", e);
    return OB_OK;
}

int ob_query_timings(ob_renderer *r, ob_pass_timing *out, int max)
{
    if (!r || !out) return 0;
    int n = r->timers.count < max ? r->timers.count : max;
    for (int i = 0; i < n; ++i) {
        out[i].name = r->timers.names[i];
        out[i].ms = r->timers.ms[i];
    }
    return n;
}

ob_error ob_renderer_set_environment(ob_renderer *r, const char *hdr_path)
{
    if (!r || !hdr_path) return ob_set_error(OB_ERR_INVALID_ARGUMENT, "ob_renderer_set_environment: NULL argument");
    return ob_environment_load(&r->environment, hdr_path);
}

/* The inputs of the view pass for the last frame's `view` (ob_present, ob_read_view). */
static ob_error view_inputs(ob_renderer *r, ob_view view, const char *who, ob_view_inputs *in)
{
    if (!r) return ob_set_error(OB_ERR_INVALID_ARGUMENT, "%s: NULL renderer", who);
    if ((int)view < 0 || view >= OB_VIEW_COUNT)
        return ob_set_error(OB_ERR_INVALID_ARGUMENT, "%s: view %d is not one of the %d views", who, (int)view,
                            (int)OB_VIEW_COUNT);
    if (!r->has_frame)
        return ob_set_error(OB_ERR_INVALID_ARGUMENT, "%s: no frame rendered yet (or since the last resize)", who);
    const ao_targets *t = &r->scales[r->last_scale];
    memset(in, 0, sizeof *in);
    in->view = view;
    in->directional = r->last_rgb;
    in->width = r->width;
    in->height = r->height;
    in->far_z = r->last_far;
    in->grid_k = t->grid.k;
    switch (view) {
    case OB_VIEW_FINAL: in->source = r->final; break;
    case OB_VIEW_AO: in->source = r->last_rgb ? r->ao_rgb : r->ao; break;
    case OB_VIEW_NORMALS: in->source = r->gbuffer.normal; break;
    case OB_VIEW_DEPTH: in->source = r->gbuffer.linear_depth; break;
    case OB_VIEW_SHADOW:
    case OB_VIEW_RADIANCE: in->source = r->direct; break;
    case OB_VIEW_BOUNCE: in->source = r->last_rgb ? r->bounce : r->gbuffer.linear_depth; break; /* black if not */
    case OB_VIEW_SAMPLES: {
        /* The counts of read_sample_counts, over the most a pixel could take (multiplier <= 3). */
        in->source = r->gbuffer.linear_depth;
        const ob_method_impl *m = ob_method_impl_at(r->last_method);
        int samples = ob_method_samples(m, r->last_params);
        bool adaptive = r->last_adaptive && m->adapts;
        in->samples = adaptive ? ob_adaptive_base(samples) : samples;
        in->multiplier = adaptive ? t->multiplier : 0;
        in->max_samples = adaptive ? 3 * in->samples : samples;
        break;
    }
    case OB_VIEW_COUNT: break;
    }
    return OB_OK;
}

ob_error ob_present(ob_renderer *r, ob_view view, uint32_t framebuffer, int x, int y, int width, int height)
{
    if (r && (width <= 0 || height <= 0 || x > INT_MAX - width || y > INT_MAX - height))
        return ob_set_error(OB_ERR_INVALID_ARGUMENT, "ob_present: rectangle %d,%d %dx%d is empty or overflows", x, y,
                            width, height);
    ob_view_inputs in;
    ob_error err = view_inputs(r, view, "ob_present", &in);
    if (err != OB_OK) return err;
    return ob_view_present(&r->view, &in, framebuffer, x, y, width, height);
}

ob_error ob_read_view(ob_renderer *r, ob_view view, uint8_t *dst, size_t dst_size)
{
    ob_view_inputs in;
    ob_error err = view_inputs(r, view, "ob_read_view", &in);
    if (err != OB_OK) return err;
    size_t need = ob_image_size(r, OB_IMAGE_FINAL_RGBA8);
    if (!dst || dst_size < need)
        return ob_set_error(OB_ERR_INVALID_ARGUMENT, "ob_read_view: buffer of %zu bytes, need %zu", dst ? dst_size : 0,
                            need);
    if (view == OB_VIEW_FINAL) return ob_read_image(r, OB_IMAGE_FINAL_RGBA8, dst, dst_size);
    GLuint tex = 0;
    err = ob_view_render(&r->view, &in, &tex);
    if (err != OB_OK) return err;
    glMemoryBarrier(GL_TEXTURE_UPDATE_BARRIER_BIT);
    glPixelStorei(GL_PACK_ALIGNMENT, 1);
    glGetTextureImage(tex, 0, GL_RGBA, GL_UNSIGNED_BYTE, (GLsizei)need, dst);
    /* GL's rows run bottom to top; image files want top first. */
    size_t row = (size_t)r->width * 4;
    for (int y = 0; y < r->height / 2; ++y) {
        uint8_t *a = dst + (size_t)y * row, *b = dst + (size_t)(r->height - 1 - y) * row;
        for (size_t i = 0; i < row; ++i) {
            uint8_t c = a[i];
            a[i] = b[i];
            b[i] = c;
        }
    }
    GLenum e = glGetError();
    if (e != GL_NO_ERROR) return ob_set_error(OB_ERR_GL, "OpenGL error 0x%x reading the %s view", e, ob_view_name(view));
    return OB_OK;
}
