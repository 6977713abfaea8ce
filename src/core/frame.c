/* The frame (docs/architecture.md "The frame"), each pass timed:
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

#include "base/error.h"
#include "sampling/sampling.h"
#include "core/renderer.h"

bool ob_projection_is_orthographic(const float *proj)
{
    /* Column-major: P23 = proj[11], P33 = proj[15] (clip w = P23 z + P33). */
    return proj[11] == 0.0f && proj[15] == 1.0f;
}

void ob_proj_info(const float *proj, float out[4])
{
    /* Column-major: P00 = proj[0], P11 = proj[5], P20 = proj[8], P21 = proj[9]; orthographic
     * (w = 1): ndc.x = P00 X + P30, so -P30 (proj[12]) takes P20's place in common.glsl's
     * X = (ndc.x + proj_info.z) * ob_depth_scale(d) / P00, and -P31 (proj[13]) P21's. */
    const bool ortho = ob_projection_is_orthographic(proj);
    out[0] = 1.0f / proj[0];
    out[1] = 1.0f / proj[5];
    out[2] = ortho ? -proj[12] : proj[8];
    out[3] = ortho ? -proj[13] : proj[9];
}

void ob_guard_projection(float proj[16], int width, int height, int guard)
{
    /* Belonogov 2018 §3.2.2: the enlarged image must hold the visible one at its centre, pixel for pixel.
     * ndc' = 2 (x + g + 1/2) / (W + 2g) - 1 = (2 (x + 1/2) / W - 1) W / (W + 2g), so ndc scales
     * about the centre by W / (W + 2g); ndc = (P00 X + P20 Z + P30) / w scales with P00, P20 and
     * P30 (an orthographic camera's offset; 0 in a perspective one, which stays 0). */
    if (guard <= 0) return;
    float sx = (float)width / (float)(width + 2 * guard);
    float sy = (float)height / (float)(height + 2 * guard);
    proj[0] *= sx;
    proj[8] *= sx;
    proj[12] *= sx;
    proj[5] *= sy;
    proj[9] *= sy;
    proj[13] *= sy;
}

/* The projection as seen from the AO grid. AO pixel i sits at full pixel k i + o, so along x
 * ndc_grid = a ndc_full + b with a = W / (k w) and b = a - 1 + (1 - (2o + 1)/k) / w (from
 * ndc_full = 2 (k i + o + 1/2) / W - 1 and ndc_grid = 2 (i + 1/2) / w - 1). Folding that into
 * P00, P20 (and P11, P21) keeps every method's reconstruction and projection exact; for an
 * orthographic camera (w = 1) the offset b goes into P30 (P31) instead. */
static void grid_projection(const ob_ao_grid *g, const float *proj, float *out)
{
    memcpy(out, proj, 16 * sizeof(float));
    if (g->k == 1) return;
    float ax = (float)g->full_width / (float)(g->k * g->width);
    float ay = (float)g->full_height / (float)(g->k * g->height);
    float bx = ax - 1.0f + (1.0f - (2.0f * (float)g->o + 1.0f) / (float)g->k) / (float)g->width;
    float by = ay - 1.0f + (1.0f - (2.0f * (float)g->o + 1.0f) / (float)g->k) / (float)g->height;
    if (ob_projection_is_orthographic(proj)) {
        /* ndc = P00 X + P20 Z + P30  ->  a ndc + b = a P00 X + a P20 Z + (a P30 + b) */
        out[0] = ax * proj[0];
        out[8] = ax * proj[8];
        out[12] = ax * proj[12] + bx;
        out[5] = ay * proj[5];
        out[9] = ay * proj[9];
        out[13] = ay * proj[13] + by;
        return;
    }
    /* ndc = (P00 X + P20 Z) / -Z  ->  a ndc + b = (a P00 X + (a P20 - b) Z) / -Z */
    out[0] = ax * proj[0];
    out[8] = ax * proj[8] - bx;
    out[5] = ay * proj[5];
    out[9] = ay * proj[9] - by;
}

void ob_ao_grid_projection(const ob_ao_grid *g, const float *proj, float out[16]) { grid_projection(g, proj, out); }

ob_error ob_jitter_offset(int index, int positions, float offset[2])
{
    if (positions < 1 || !offset)
        return ob_set_error(OB_ERR_INVALID_ARGUMENT, "ob_jitter_offset: %s",
                            !offset ? "NULL offset" : "positions below 1");
    /* Halton (1964) from index 1: point 0 is (0, 0), a pixel corner, and the first J points from 1
     * on cover the pixel evenly in both axes (bases 2 and 3 are coprime). */
    int i = index % positions;
    if (i < 0) i += positions;
    offset[0] = (float)ob_radical_inverse((uint32_t)i + 1u, 2u) - 0.5f;
    offset[1] = (float)ob_radical_inverse((uint32_t)i + 1u, 3u) - 0.5f;
    return OB_OK;
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
    f->orthographic = ob_projection_is_orthographic(d->proj) ? 1 : 0;
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

/* The extra view's targets at the G-buffer's size, made on first use and remade with it. */
static ob_error extra_targets(ob_renderer *r)
{
    int w = r->gbuffer.width, h = r->gbuffer.height;
    if (!r->extra_ubo) {
        if (ob_gbuffer_init(&r->extra_gbuffer, w, h) != OB_OK) {
            ob_error err = ob_peek_error(NULL);
            ob_gbuffer_destroy(&r->extra_gbuffer);
            return err;
        }
        glCreateBuffers(1, &r->extra_ubo);
        glNamedBufferStorage(r->extra_ubo, sizeof(ob_frame_constants), NULL, GL_DYNAMIC_STORAGE_BIT);
        r->extra_direct = ob_make_texture_2d(GL_RGBA16F, w, h);
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

/* The scene's passes before the AO chain: shadow maps, G-buffer, direct light, and what the
 * method reads beyond them (the extra view, the second depth layer). */
static ob_error run_scene_passes(ob_renderer *r, const ob_settings *s, const ob_method_plan *plan,
                                 const ob_light *lights, int light_count)
{
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
    ob_upload_frame(r); /* after ob_shadows_fill: each light's shadow map index */
    err = ob_lighting_run(&r->lighting, &r->frame_constants, r->inner_width, r->inner_height, r->gbuffer.linear_depth,
                          r->gbuffer.normal, r->gbuffer.albedo, r->direct);
    if (err != OB_OK) return err;
    glMemoryBarrier(barrier);
    if (!plan->impl->shader) return OB_OK;
    if (plan->reads & OB_READS_EXTRA_VIEW) {
        /* Belonogov 2018 §4.4: the extra camera's G-buffer and direct light, with its own per-frame
         * block (the same lights and shadow maps), then the main block bound again. */
        ob_timer_begin(&r->timers, "extra_view");
        err = run_extra_view(r, s, lights, light_count);
        if (err != OB_OK) return err;
    }
    if (plan->reads & OB_READS_SECOND_LAYER) {
        /* Depth peeling after the G-buffer, whose linear depth it peels behind. */
        ob_timer_begin(&r->timers, "second_layer");
        if (!r->peel.program && ob_peel_init(&r->peel) != OB_OK) return ob_peek_error(NULL);
        err = ob_peel_run(&r->peel, &r->gbuffer, f->view, f->proj);
        if (err != OB_OK) return err;
        glMemoryBarrier(barrier);
    }
    return OB_OK;
}

/* Every pass of the frame, stopping at the first failure; the caller closes the timers. */
static ob_error run_passes(ob_renderer *r, const ob_settings *s, const ob_method_plan *plan, ao_targets *t,
                           const ob_light *lights, int light_count)
{
    const GLbitfield barrier = GL_TEXTURE_FETCH_BARRIER_BIT | GL_SHADER_IMAGE_ACCESS_BARRIER_BIT;
    ob_error err = run_scene_passes(r, s, plan, lights, light_count);
    if (err != OB_OK) return err;
    const ob_chain_io io = {.depth = r->gbuffer.linear_depth,
                            .normal = r->gbuffer.normal,
                            .radiance = r->direct,
                            .albedo = r->gbuffer.albedo,
                            .facet = r->gbuffer.facet,
                            .second_depth = plan->reads & OB_READS_SECOND_LAYER ? r->peel.linear_depth : 0,
                            .second_plane = plan->reads & OB_READS_SECOND_LAYER ? r->peel.plane : 0,
                            .extra_view = (plan->reads & OB_READS_EXTRA_VIEW) != 0,
                            .ao = r->ao};
    err = ob_run_ao_chain(r, s, plan, t, &io);
    if (err != OB_OK) return err;
    const ob_compose_inputs ci = {.linear_depth = r->gbuffer.linear_depth,
                                  .normal = r->gbuffer.normal,
                                  .albedo = r->gbuffer.albedo,
                                  .ao = r->last.rgb ? r->ao_rgb : r->ao,
                                  .direct = r->direct,
                                  .environment = r->environment.texture,
                                  .directional = r->last.rgb,
                                  .bounce = r->last.bounce ? r->bounce : 0,
                                  .bent_normal = r->last.bent ? r->bent : 0,
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

ob_error ob_render_frame(ob_renderer *r, const ob_camera *camera, const ob_settings *s)
{
    if (!r || !camera) return ob_set_error(OB_ERR_INVALID_ARGUMENT, "ob_render_frame: NULL argument");
    if (ob_check_settings(s) != OB_OK) return ob_peek_error(NULL);
    if (!r->has_scene) return ob_set_error(OB_ERR_INVALID_ARGUMENT, "ob_render_frame: no scene (ob_renderer_set_scene)");
    if (s->ambient_mode == OB_AMBIENT_ENVIRONMENT && !r->environment.texture)
        return ob_set_error(OB_ERR_INVALID_ARGUMENT, "environment ambient without an environment map (--env FILE.hdr)");
    ob_gl_drop_pending(); /* the frame's GL calls are checked with glGetError at its end */

    ob_camera cam = *camera;
    if (cam.fov_y_deg <= 0.0f) cam.fov_y_deg = 60.0f;
    if (cam.up[0] == 0.0f && cam.up[1] == 0.0f && cam.up[2] == 0.0f) cam.up[1] = 1.0f;
    if (cam.near_z <= 0.0f || cam.far_z <= cam.near_z) ob_camera_fit_planes(&cam, r->bounds_min, r->bounds_max);
    if (!(cam.fov_y_deg < 179.0f) || !isfinite(cam.eye[0] + cam.eye[1] + cam.eye[2] + cam.target[0] + cam.target[1] + cam.target[2] + cam.shift[0] + cam.shift[1]))
        return ob_set_error(OB_ERR_INVALID_ARGUMENT, "camera is not finite or its fov is not in (0, 179)");

    /* A new guard band remakes the targets before anything is drawn into them. */
    ob_error err = ob_renderer_reshape(r, r->width, r->height, ob_guard_pixels(s->guard, s->ao_divisor));
    if (err != OB_OK) return err;
    ob_method_plan plan;
    err = ob_plan_method(r, s, r->scene_radius, &plan);
    if (err != OB_OK) return err;

    mat4 view, proj, unjittered;
    ob_camera_view_proj(&cam, r->width, r->height, (float *)view, (float *)proj);
    ob_guard_projection((float *)proj, r->width, r->height, r->guard);
    glm_mat4_copy(proj, unjittered);
    if (s->jitter > 0) {
        /* The frame's sample point in each pixel: P20 += 2 jx / width moves the image by -jx
         * pixels, so pixel (x, y) samples the scene at (x + 1/2 + jx, y + 1/2 + jy) of the
         * unjittered raster (ob_host_frame.jitter's convention); the enlarged buffer's width with
         * a guard band, whose pixels are the visible ones. */
        float j[2];
        ob_jitter_offset((int)(r->frame % (uint32_t)s->jitter), s->jitter, j);
        proj[2][0] += 2.0f * j[0] / (float)r->gbuffer.width;
        proj[2][1] += 2.0f * j[1] / (float)r->gbuffer.height;
    }
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
    int si = ob_scale_index(s->ao_divisor);
    ao_targets *t = ob_renderer_targets(r, si);
    r->last.scale = si;
    const ob_light *lights = s->light_count > 0 ? s->lights : r->scene_lights;
    int light_count = s->light_count > 0 ? s->light_count : r->scene_light_count;
    ob_frame_constants_fill(&r->frame_constants,
                            &(ob_frame_desc){.view = (const float *)view, .proj = (const float *)proj, .grid = &t->grid,
                                             .near_z = cam.near_z, .far_z = cam.far_z, .frame_index = r->frame++,
                                             .lights = lights, .light_count = light_count, .settings = s,
                                             .sh = (const float(*)[3])r->environment.sh});
    grid_projection(&t->grid, (const float *)unjittered, r->ao_proj_unjittered);

    /* From here the targets are being overwritten: no whole frame to present until the end. */
    r->has_frame = false;
    r->has_host_chain = false;
    ob_timers_frame_begin(&r->timers);
    err = run_passes(r, s, &plan, t, lights, light_count);
    ob_timers_frame_end(&r->timers);
    if (err != OB_OK) return err;
    GLenum e = glGetError();
    if (e != GL_NO_ERROR) return ob_set_error(OB_ERR_GL, "OpenGL error 0x%x during the frame", e);
    r->has_frame = true;
    r->last.far = cam.far_z;
    return OB_OK;
}

ob_error ob_render_floor(ob_renderer *r, const ob_settings *s, ob_floor_info *info)
{
    if (!r) return ob_set_error(OB_ERR_INVALID_ARGUMENT, "ob_render_floor: NULL renderer");
    if (ob_check_settings(s) != OB_OK) return ob_peek_error(NULL);
    ob_gl_drop_pending();
    const int si = ob_scale_index(s->ao_divisor);
    if (!r->has_frame || r->last.scale != si || !r->scales[si].ready)
        return ob_set_error(OB_ERR_INVALID_ARGUMENT,
                            "ob_render_floor: no frame at AO scale 1/%d yet (the floor reads its depth and normals)",
                            s->ao_divisor > 0 ? s->ao_divisor : 1);
    ob_method_plan plan;
    ob_error err = ob_plan_method(r, s, r->scene_radius, &plan);
    if (err != OB_OK) return err;
    const ob_method_info *m = &plan.impl->info;
    /* The settings as the method resolves them (a radius that follows the scene, the sample count
     * of HBAO's directions x steps), so the floor takes exactly the method's N and R. */
    const int radius_at = ob_method_role(plan.impl, OB_ROLE_RADIUS);
    const int max_px_at = ob_method_role(plan.impl, OB_ROLE_MAX_RADIUS_PX);
    const float radius = radius_at >= 0 ? plan.params[radius_at] : 0.0f;
    const float max_radius_px = max_px_at >= 0 ? plan.params[max_px_at] : 0.0f;
    const int taps = ob_method_samples(plan.impl, plan.params);
    if (taps <= 0 || !(radius > 0.0f))
        return ob_set_error(OB_ERR_INVALID_ARGUMENT, "ob_render_floor: %s has no %s", m->name,
                            taps <= 0 ? "sample count" : "radius");
    const ao_targets *t = &r->scales[si];
    /* R_px = R x (height / 2) x P11 / d, the methods' projection (hbao.c, alchemy.c px_per_unit):
     * the floor follows an ob_render_frame, whose camera is perspective (after an ob_host_ao, which
     * may be orthographic, has_frame is false). */
    const ob_floor_desc d = {.taps = taps,
                             .rays = plan.impl->count_rays ? plan.impl->count_rays(plan.params) : 0,
                             .radius = radius,
                             .px_per_unit = 0.5f * (float)t->grid.height / r->frame_constants.ao_proj_info[1],
                             .max_radius_px = max_radius_px};
    if (!r->floor.pass.program && ob_floor_init(&r->floor) != OB_OK) {
        err = ob_peek_error(NULL);
        ob_floor_destroy(&r->floor);
        return err;
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
