/* Shadow maps (SSDO thesis §2.1, §5.1, §6.1): hard, percentage-closer filtered and variance shadow
 * maps for directional, spot and point lights. "In the first step of the rendering the
 * application creates the shadow maps for every light. The shadow maps are then used to compute
 * shadows in the direct illumination step" (§5.1): ob_shadows_render is that first step,
 * shaders/shadow.glsl (included by shaders/lighting.glsl) the second.
 *
 *   directional: orthographic along the light, fitted so all 8 corners of the scene bounds are
 *                inside; stores the hardware depth (linear under an orthographic projection)
 *   spot:        perspective around the cone (fov = 2 x outer half-angle + 2 degrees, at most
 *                160), near/far fitted to the bounds; stores distance / far
 *   point:       a cube (six 90-degree faces) storing distance / far, so the lookup compares one
 *                direction-independent value and needs no face matrices
 *   VSM:         moments (z, z^2) of the directional and spot maps, Gaussian-blurred (sigma =
 *                vsm_blur texels) by shaders/shadow_vsm.glsl; point lights use PCF instead
 *
 * No glPolygonOffset: the bias is applied in the lookup (shadow.glsl), where the angle to the
 * light and the filter's footprint are known, so hard, PCF and VSM each get the bias their
 * footprint needs from the same two settings; the maps themselves stay exact. No depth clamp
 * either: the near and far planes enclose the bounds, so nothing is clipped. */
#include <cglm/cglm.h>
#include <float.h>
#include <math.h>
#include <string.h>

#include "base/error.h"
#include "passes/passes.h"
#include "shadow_params.h"

/* VSM's variance floor (shadow_options.z), in squared normalised depth. Catastrophic
 * cancellation in E[z^2] - E[z]^2 of 32-bit floats leaves errors around 1e-7 for z near 1 (SSDO
 * thesis §6.1: too small a floor shows as speckles, and 16-bit moments needed a "higher threshold");
 * 1e-5 is a hundred times that and still darkens an occluder 1% of the depth range in front of
 * the receiver to p_max = 0.09, under the light-bleeding cut. */
#define VSM_MIN_VARIANCE 1e-5f
/* Spot maps reach 2 degrees past the outer cone: the PCF kernel and the bilinear taps of a point
 * on the cone's edge stay inside the map (2 degrees is 6 texels of a 90-degree map at 256, 45 at 2048). */
#define SPOT_MARGIN_DEG 2.0f
/* A perspective map past 160 degrees spends most texels on its rim; wider cones are clipped there
 * and the points beyond are treated as lit. */
#define SPOT_MAX_HALF_DEG 80.0f
#define MIN_MAP_SIZE 16

ob_error ob_shadows_init(ob_shadow_maps *s)
{
    memset(s, 0, sizeof *s);
    s->method = OB_SHADOW_NONE;
    for (int i = 0; i < OB_MAX_LIGHTS; ++i) s->light_map[i] = -1;
    s->depth_program = ob_make_raster_program("shadow_depth.vert.glsl", "shadow_depth.frag.glsl", NULL);
    if (!s->depth_program) return ob_peek_error(NULL);
    s->distance_program =
        ob_make_raster_program("shadow_depth.vert.glsl", "shadow_depth.frag.glsl", "#define OB_SHADOW_DISTANCE 1\n");
    if (!s->distance_program) {
        ob_shadows_destroy(s);
        return ob_peek_error(NULL);
    }
    ob_error err = ob_compute_pass_init(&s->vsm_x, "shadow_vsm.glsl", "#define OB_SHADOW_VSM_MOMENTS 1\n",
                                        sizeof(ob_shadow_vsm_constants));
    if (err == OB_OK) err = ob_compute_pass_init(&s->vsm_y, "shadow_vsm.glsl", NULL, sizeof(ob_shadow_vsm_constants));
    if (err != OB_OK) {
        ob_shadows_destroy(s);
        return err;
    }
    glCreateBuffers(1, &s->ubo);
    glNamedBufferStorage(s->ubo, sizeof(ob_shadow_depth_constants), NULL, GL_DYNAMIC_STORAGE_BIT);
    glCreateFramebuffers(1, &s->fbo);
    glNamedFramebufferDrawBuffer(s->fbo, GL_NONE);
    glNamedFramebufferReadBuffer(s->fbo, GL_NONE);
    /* Point-light PCF reads across cube faces; without seamless filtering the bilinear taps at a
     * face's border clamp and draw the cube's edges into the penumbra. Global state, and no
     * other pass samples cube maps. */
    glEnable(GL_TEXTURE_CUBE_MAP_SEAMLESS);
    return OB_OK;
}

static void delete_texture(GLuint *tex)
{
    if (*tex) glDeleteTextures(1, tex);
    *tex = 0;
}

void ob_shadows_destroy(ob_shadow_maps *s)
{
    if (s->depth_program) glDeleteProgram(s->depth_program);
    if (s->distance_program) glDeleteProgram(s->distance_program);
    ob_compute_pass_destroy(&s->vsm_x);
    ob_compute_pass_destroy(&s->vsm_y);
    ob_compute_pass_destroy(&s->vsm_x16);
    ob_compute_pass_destroy(&s->vsm_y16);
    if (s->ubo) glDeleteBuffers(1, &s->ubo);
    if (s->fbo) glDeleteFramebuffers(1, &s->fbo);
    delete_texture(&s->maps_2d);
    delete_texture(&s->maps_cube);
    delete_texture(&s->moments);
    delete_texture(&s->scratch);
    memset(s, 0, sizeof *s);
    for (int i = 0; i < OB_MAX_LIGHTS; ++i) s->light_map[i] = -1;
}

/* ---- settings -------------------------------------------------------------------------------- */

static bool in_range(float v, float lo, float hi) { return isfinite(v) && v >= lo && v <= hi; }

static ob_error check_settings(const ob_shadow_settings *st, int max_size)
{
    if (st->method < OB_SHADOW_NONE || st->method > OB_SHADOW_VSM)
        return ob_set_error(OB_ERR_OUT_OF_RANGE, "shadow method %d unknown", (int)st->method);
    if (st->size < MIN_MAP_SIZE || st->size > max_size)
        return ob_set_error(OB_ERR_OUT_OF_RANGE, "shadow map size %d outside %d..%d", st->size, MIN_MAP_SIZE,
                            max_size);
    if (!in_range(st->bias, 0.0f, 1e4f) || !in_range(st->slope_bias, 0.0f, 1e4f))
        return ob_set_error(OB_ERR_OUT_OF_RANGE, "shadow bias %g / slope bias %g: must be finite and >= 0",
                            (double)st->bias, (double)st->slope_bias);
    /* PCF's radius also serves VSM's point lights (their PCF fallback). */
    if ((st->method == OB_SHADOW_PCF || st->method == OB_SHADOW_VSM) &&
        (st->pcf_radius < 1 || st->pcf_radius > OB_SHADOW_MAX_PCF_RADIUS))
        return ob_set_error(OB_ERR_OUT_OF_RANGE, "shadow pcf_radius %d outside 1..%d", st->pcf_radius,
                            OB_SHADOW_MAX_PCF_RADIUS);
    if (st->method == OB_SHADOW_VSM && !in_range(st->vsm_blur, 0.0f, OB_SHADOW_VSM_MAX_RADIUS / 2.0f))
        return ob_set_error(OB_ERR_OUT_OF_RANGE, "shadow vsm_blur %g outside 0..%g", (double)st->vsm_blur,
                            OB_SHADOW_VSM_MAX_RADIUS / 2.0);
    if (st->method == OB_SHADOW_VSM && st->vsm_bits != 0 && st->vsm_bits != 16 && st->vsm_bits != 32)
        return ob_set_error(OB_ERR_OUT_OF_RANGE, "shadow vsm_bits %d: must be 16 or 32", st->vsm_bits);
    if (st->method == OB_SHADOW_VSM && !in_range(st->vsm_bleed, 0.0f, 0.99f))
        return ob_set_error(OB_ERR_OUT_OF_RANGE, "shadow vsm_bleed %g outside 0..0.99", (double)st->vsm_bleed);
    return OB_OK;
}

/* ---- allocation ------------------------------------------------------------------------------ */

static GLuint make_depth_array(GLenum target, int size, int layers)
{
    GLuint tex = 0;
    glCreateTextures(target, 1, &tex);
    glTextureStorage3D(tex, 1, GL_DEPTH_COMPONENT32F, size, size, layers);
    glTextureParameteri(tex, GL_TEXTURE_COMPARE_FUNC, GL_LEQUAL); /* 1 = ref <= stored = lit */
    if (target == GL_TEXTURE_2D_ARRAY) {
        /* Past the map's edge the border's depth 1 is "nothing in front": lit. */
        const float border[4] = {1.0f, 1.0f, 1.0f, 1.0f};
        glTextureParameteri(tex, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_BORDER);
        glTextureParameteri(tex, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_BORDER);
        glTextureParameterfv(tex, GL_TEXTURE_BORDER_COLOR, border);
    }
    return tex;
}

static GLenum moment_format(int bits) { return bits == 16 ? GL_RG16F : GL_RG32F; }

static GLuint make_moments(GLenum target, int size, int layers, int bits)
{
    GLuint tex = 0;
    glCreateTextures(target, 1, &tex);
    if (target == GL_TEXTURE_2D_ARRAY)
        glTextureStorage3D(tex, 1, moment_format(bits), size, size, layers);
    else
        glTextureStorage2D(tex, 1, moment_format(bits), size, size);
    /* Bilinear: the lookup filters the moments once more for free (SSDO thesis §2.1: VSM may be
     * filtered "with arbitrary size kernel"). The border (1, 1) is a lit depth with no variance. */
    const float border[4] = {1.0f, 1.0f, 0.0f, 0.0f};
    glTextureParameteri(tex, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
    glTextureParameteri(tex, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    glTextureParameteri(tex, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_BORDER);
    glTextureParameteri(tex, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_BORDER);
    glTextureParameterfv(tex, GL_TEXTURE_BORDER_COLOR, border);
    return tex;
}

static ob_error allocate(ob_shadow_maps *s, int size, int layers_2d, int cubes, int moment_layers, int bits)
{
    if (size != s->size || layers_2d != s->layers_2d) {
        delete_texture(&s->maps_2d);
        if (layers_2d > 0) s->maps_2d = make_depth_array(GL_TEXTURE_2D_ARRAY, size, layers_2d);
    }
    if (size != s->size || cubes != s->cubes) {
        delete_texture(&s->maps_cube);
        if (cubes > 0) s->maps_cube = make_depth_array(GL_TEXTURE_CUBE_MAP_ARRAY, size, 6 * cubes);
    }
    if (size != s->size || moment_layers != s->moment_layers || bits != s->moment_bits) {
        delete_texture(&s->moments);
        delete_texture(&s->scratch);
        if (moment_layers > 0) {
            s->moments = make_moments(GL_TEXTURE_2D_ARRAY, size, moment_layers, bits);
            s->scratch = make_moments(GL_TEXTURE_2D, size, 1, bits);
        }
    }
    s->moment_bits = bits;
    s->size = size;
    s->layers_2d = layers_2d;
    s->cubes = cubes;
    s->moment_layers = moment_layers;
    /* Four 8192^2 cube maps are 6 GiB: ask the GL whether the storage was there. */
    bool oom = false;
    for (GLenum e = glGetError(); e != GL_NO_ERROR; e = glGetError()) oom = oom || e == GL_OUT_OF_MEMORY;
    if (oom) {
        delete_texture(&s->maps_2d);
        delete_texture(&s->maps_cube);
        delete_texture(&s->moments);
        delete_texture(&s->scratch);
        s->size = s->layers_2d = s->cubes = s->moment_layers = s->moment_bits = 0;
        return ob_set_error(OB_ERR_OUT_OF_MEMORY, "no GPU memory for %d + %d cube shadow maps of %d^2", layers_2d,
                            cubes, size);
    }
    return OB_OK;
}

/* ---- light projections ----------------------------------------------------------------------- */

static void normalized_or_up(const float v[3], vec3 out)
{
    float len = sqrtf(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
    if (len > 0.0f && isfinite(len)) {
        glm_vec3_scale((float *)v, 1.0f / len, out);
    } else {
        /* The lighting pass makes the same choice for a zero direction (lighting.c). */
        out[0] = 0.0f;
        out[1] = 1.0f;
        out[2] = 0.0f;
    }
}

/* An up vector not parallel to `forward`. */
static void pick_up(const vec3 forward, vec3 up)
{
    up[0] = 0.0f;
    up[1] = fabsf(forward[1]) > 0.99f ? 0.0f : 1.0f;
    up[2] = fabsf(forward[1]) > 0.99f ? 1.0f : 0.0f;
}

static void corner(const float bmin[3], const float bmax[3], int i, vec3 out)
{
    out[0] = (i & 1) ? bmax[0] : bmin[0];
    out[1] = (i & 2) ? bmax[1] : bmin[1];
    out[2] = (i & 4) ? bmax[2] : bmin[2];
}

static float bounds_diagonal(const float bmin[3], const float bmax[3])
{
    float dx = bmax[0] - bmin[0], dy = bmax[1] - bmin[1], dz = bmax[2] - bmin[2];
    float d = sqrtf(dx * dx + dy * dy + dz * dz);
    return d > 0.0f && isfinite(d) ? d : 1.0f;
}

/* Farthest and nearest distance from p to the box (nearest 0 when p is inside). */
static void box_distances(const float bmin[3], const float bmax[3], const vec3 p, float *nearest, float *farthest)
{
    float far2 = 0.0f, near2 = 0.0f;
    for (int i = 0; i < 8; ++i) {
        vec3 c;
        corner(bmin, bmax, i, c);
        float d2 = glm_vec3_distance2((float *)p, c);
        if (d2 > far2) far2 = d2;
    }
    for (int k = 0; k < 3; ++k) {
        float d = p[k] < bmin[k] ? bmin[k] - p[k] : (p[k] > bmax[k] ? p[k] - bmax[k] : 0.0f);
        near2 += d * d;
    }
    *nearest = sqrtf(near2);
    *farthest = sqrtf(far2);
}

/* Directional: an orthographic box around the scene, seen along -direction. Returns the
 * world -> clip matrix and the bias constants (shadow_params.xy) in normalised depth. */
static void directional_map(const ob_light *l, const float bmin[3], const float bmax[3], const ob_shadow_settings *st,
                            mat4 view_proj, float params[4])
{
    vec3 dir, up, center, eye;
    normalized_or_up(l->direction, dir);
    pick_up(dir, up);
    for (int k = 0; k < 3; ++k) center[k] = 0.5f * (bmin[k] + bmax[k]);
    glm_vec3_add(center, dir, eye); /* any eye on the line: the planes below come from the corners */
    mat4 view, proj;
    glm_lookat(eye, center, up, view);
    vec3 lo = {FLT_MAX, FLT_MAX, FLT_MAX}, hi = {-FLT_MAX, -FLT_MAX, -FLT_MAX};
    for (int i = 0; i < 8; ++i) {
        vec3 c, v;
        corner(bmin, bmax, i, c);
        glm_mat4_mulv3(view, c, 1.0f, v);
        glm_vec3_minv(lo, v, lo);
        glm_vec3_maxv(hi, v, hi);
    }
    /* 1% margins: the corners stay strictly inside, and a flat scene still gets a depth range. */
    float diag = bounds_diagonal(bmin, bmax);
    float mx = 0.01f * (hi[0] - lo[0]) + 1e-4f * diag, my = 0.01f * (hi[1] - lo[1]) + 1e-4f * diag;
    float mz = 0.01f * diag;
    float left = lo[0] - mx, right = hi[0] + mx, bottom = lo[1] - my, top = hi[1] + my;
    float near_z = -hi[2] - mz, far_z = -lo[2] + mz; /* view space looks down -Z */
    glm_ortho(left, right, bottom, top, near_z, far_z, proj);
    glm_mat4_mul(proj, view, view_proj);
    /* Biases are given in texels' world size; the lookup compares depth normalised to the range. */
    float texel = fmaxf(right - left, top - bottom) / (float)st->size;
    float range = far_z - near_z;
    params[0] = st->bias * texel / range;
    params[1] = st->slope_bias * texel / range;
    params[3] = 0.0f; /* orthographic: hardware depth, no far */
}

/* Near plane for a perspective map from a light at distance `nearest` from the bounds: a point at
 * distance d lies at view depth >= d cos(the frustum's widest half-angle). */
static float fit_near(float nearest, float far_z, float tan_half)
{
    float cos_diag = cosf(atanf(sqrtf(2.0f) * tan_half));
    float n = 0.99f * nearest * cos_diag;
    return fmaxf(n, 1e-3f * far_z);
}

static void spot_map(const ob_light *l, const float bmin[3], const float bmax[3], const ob_shadow_settings *st,
                     mat4 view_proj, float params[4])
{
    vec3 pos = {l->position[0], l->position[1], l->position[2]}, axis, up, target;
    normalized_or_up(l->direction, axis);
    pick_up(axis, up);
    glm_vec3_add(pos, axis, target);
    float outer = l->spot_outer_deg > 0.0f ? l->spot_outer_deg : 45.0f;
    float half = fminf(outer + SPOT_MARGIN_DEG, SPOT_MAX_HALF_DEG);
    float tan_half = tanf(glm_rad(half));
    float nearest = 0.0f, farthest = 0.0f;
    box_distances(bmin, bmax, pos, &nearest, &farthest);
    float far_z = 1.01f * farthest + 1e-4f * bounds_diagonal(bmin, bmax);
    float near_z = fit_near(nearest, far_z, tan_half);
    mat4 view, proj;
    glm_lookat(pos, target, up, view);
    glm_perspective(2.0f * glm_rad(half), 1.0f, near_z, far_z, proj);
    glm_mat4_mul(proj, view, view_proj);
    /* A texel spans 2 tan(half)/size per unit of distance; stored depth is distance/far, so the
     * bias per unit of stored depth is bias x that span (the shader multiplies by the depth). */
    float k = 2.0f * tan_half / (float)st->size;
    params[0] = st->bias * k;
    params[1] = st->slope_bias * k;
    params[3] = far_z;
}

/* The six faces of a cube map, in GL's layer order +X -X +Y -Y +Z -Z, with the up vectors that make
 * the rendered image's x and y the face's s and t (GL 4.5 table 8.19: on +X, s runs along -Z and
 * t along -Y). */
static const float cube_dirs[6][3] = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
static const float cube_ups[6][3] = {{0, -1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}, {0, -1, 0}, {0, -1, 0}};

static void point_map(const ob_light *l, const float bmin[3], const float bmax[3], const ob_shadow_settings *st,
                      float *near_out, float *far_out, float params[4])
{
    vec3 pos = {l->position[0], l->position[1], l->position[2]};
    float nearest = 0.0f, farthest = 0.0f;
    box_distances(bmin, bmax, pos, &nearest, &farthest);
    float far_z = 1.01f * farthest + 1e-4f * bounds_diagonal(bmin, bmax);
    *far_out = far_z;
    *near_out = fit_near(nearest, far_z, 1.0f);
    float k = 2.0f / (float)st->size; /* a 90-degree face: tan(45) = 1 */
    params[0] = st->bias * k;
    params[1] = st->slope_bias * k;
    params[3] = far_z;
}

/* ---- rendering ------------------------------------------------------------------------------- */

static void draw_layer(ob_shadow_maps *s, const ob_gbuffer *g, GLuint tex, int layer, const float *view_proj,
                       const float light[4])
{
    ob_shadow_depth_constants c;
    memset(&c, 0, sizeof c);
    memcpy(c.view_proj, view_proj, sizeof c.view_proj);
    memcpy(c.light_position, light, sizeof c.light_position);
    c.inv_far = light[3];
    glNamedBufferSubData(s->ubo, 0, sizeof c, &c);
    glNamedFramebufferTextureLayer(s->fbo, GL_DEPTH_ATTACHMENT, tex, 0, layer);
    const float one = 1.0f;
    glClearNamedFramebufferfv(s->fbo, GL_DEPTH, 0, &one);
    for (int i = 0; i < g->mesh_count; ++i) {
        glBindVertexArray(g->meshes[i].vao);
        glDrawElements(GL_TRIANGLES, g->meshes[i].index_count, GL_UNSIGNED_INT, NULL);
    }
}

/* Normalised Gaussian weights w[0..radius] (the renormalised truncation of gaussian.c). */
static int vsm_weights(float sigma, float weights[][4])
{
    int radius = (int)ceilf(2.0f * sigma);
    if (radius > OB_SHADOW_VSM_MAX_RADIUS) radius = OB_SHADOW_VSM_MAX_RADIUS;
    if (sigma <= 1e-3f) radius = 0;
    float sum = 0.0f;
    for (int i = 0; i <= radius; ++i) {
        float w = radius == 0 ? 1.0f : expf(-(float)(i * i) / (2.0f * sigma * sigma));
        weights[i][0] = w;
        sum += i == 0 ? w : 2.0f * w;
    }
    for (int i = 0; i <= radius; ++i) weights[i][0] /= sum;
    return radius;
}

static void blur_moments(ob_shadow_maps *s, float sigma)
{
    const bool half = s->moment_bits == 16;
    ob_compute_pass *pass_x = half ? &s->vsm_x16 : &s->vsm_x, *pass_y = half ? &s->vsm_y16 : &s->vsm_y;
    const GLenum format = moment_format(s->moment_bits);
    ob_shadow_vsm_constants c;
    memset(&c, 0, sizeof c);
    int radius = vsm_weights(sigma, c.weights);
    c.size[0] = c.size[1] = s->size;
    c.radius = radius;
    /* Invocations: x = a run of OB_SHADOW_VSM_RUN texels along the axis, y = the line across it. */
    int runs = (s->size + OB_SHADOW_VSM_RUN - 1) / OB_SHADOW_VSM_RUN;
    for (int layer = 0; layer < s->moment_layers; ++layer) {
        c.layer = layer;
        /* x: depth -> moments, blurred along x, into the scratch texture. */
        c.axis[0] = 1;
        c.axis[1] = 0;
        ob_compute_pass_use(pass_x, &c, sizeof c);
        glBindTextureUnit(OB_UNIT_SOURCE, s->maps_2d);
        glBindImageTexture(OB_IMAGE_UNIT_OUT, s->scratch, 0, GL_FALSE, 0, GL_WRITE_ONLY, format);
        ob_dispatch_2d(runs, s->size, OB_SHADOW_GROUP_X, OB_SHADOW_GROUP_Y);
        glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT | GL_SHADER_IMAGE_ACCESS_BARRIER_BIT);
        /* y: scratch -> the moments layer (bound as a plain 2D image). */
        c.axis[0] = 0;
        c.axis[1] = 1;
        ob_compute_pass_use(pass_y, &c, sizeof c);
        glBindTextureUnit(OB_UNIT_SOURCE, s->scratch);
        glBindImageTexture(OB_IMAGE_UNIT_OUT, s->moments, 0, GL_FALSE, layer, GL_WRITE_ONLY, format);
        ob_dispatch_2d(runs, s->size, OB_SHADOW_GROUP_X, OB_SHADOW_GROUP_Y);
        /* The next layer's x pass overwrites the scratch this pass reads, and the lighting pass
         * samples the moments. */
        glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT | GL_SHADER_IMAGE_ACCESS_BARRIER_BIT);
    }
}

/* The filter and comparison each method samples with. HARD: the nearest texel, one comparison.
 * PCF: GL_LINEAR, so each comparison is a bilinear 2x2 percentage-closer filter (§5.1). VSM: the
 * 2D depth is only read by texelFetch in shadow_vsm.glsl, with comparison off (sampling a
 * comparing texture through a plain sampler is undefined); its point lights use PCF. */
static void set_sampling(const ob_shadow_maps *s, ob_shadow_method method)
{
    GLint filter = method == OB_SHADOW_HARD ? GL_NEAREST : GL_LINEAR;
    if (s->maps_2d) {
        glTextureParameteri(s->maps_2d, GL_TEXTURE_MIN_FILTER, filter);
        glTextureParameteri(s->maps_2d, GL_TEXTURE_MAG_FILTER, filter);
        glTextureParameteri(s->maps_2d, GL_TEXTURE_COMPARE_MODE,
                            method == OB_SHADOW_VSM ? GL_NONE : GL_COMPARE_REF_TO_TEXTURE);
    }
    if (s->maps_cube) {
        glTextureParameteri(s->maps_cube, GL_TEXTURE_MIN_FILTER, filter);
        glTextureParameteri(s->maps_cube, GL_TEXTURE_MAG_FILTER, filter);
        glTextureParameteri(s->maps_cube, GL_TEXTURE_COMPARE_MODE, GL_COMPARE_REF_TO_TEXTURE);
    }
}

/* The maps of the last render still hold for these inputs (field by field: the settings struct
 * has padding that memcmp would read). */
static bool same_inputs(const ob_shadow_maps *s, const ob_gbuffer *g, const ob_light *lights, int count,
                        const float bmin[3], const float bmax[3], const ob_shadow_settings *st)
{
    const ob_shadow_settings *k = &s->key_settings;
    if (!s->key_valid || s->key_count != count || s->key_scene != g->scene_generation) return false;
    if (k->method != st->method || k->size != st->size || k->bias != st->bias || k->slope_bias != st->slope_bias ||
        k->pcf_radius != st->pcf_radius || k->vsm_blur != st->vsm_blur || k->vsm_bleed != st->vsm_bleed ||
        k->vsm_bits != st->vsm_bits)
        return false;
    for (int i = 0; i < 3; ++i)
        if (s->key_bounds[i] != bmin[i] || s->key_bounds[3 + i] != bmax[i]) return false;
    return memcmp(s->key_lights, lights, (size_t)count * sizeof *lights) == 0; /* ob_light: 4-byte fields only */
}

ob_error ob_shadows_render(ob_shadow_maps *s, const ob_gbuffer *g, const ob_light *lights, int light_count,
                           const float bounds_min[3], const float bounds_max[3], const ob_shadow_settings *settings,
                           ob_timer_set *timers)
{
    if (settings && settings->reuse && settings->method != OB_SHADOW_NONE && light_count > 0 && g && lights &&
        bounds_min && bounds_max &&
        same_inputs(s, g, lights, light_count < OB_MAX_SHADOW_MAPS ? light_count : OB_MAX_SHADOW_MAPS, bounds_min,
                    bounds_max, settings))
        return OB_OK; /* matrices, params, light_map and options are those of the kept maps */
    s->key_valid = false;
    s->method = OB_SHADOW_NONE;
    for (int i = 0; i < OB_MAX_LIGHTS; ++i) s->light_map[i] = -1;
    if (!settings || settings->method == OB_SHADOW_NONE || light_count <= 0) return OB_OK;
    if (!g || !lights || !bounds_min || !bounds_max)
        return ob_set_error(OB_ERR_INVALID_ARGUMENT, "ob_shadows_render: NULL G-buffer, lights or bounds");

    /* Which lights get a map, and where it lives: a layer of the 2D array or a cube of the cube
     * array. The map index m (light_direction.w) picks shadow_matrix/params; params.z the layer. */
    int count = light_count < OB_MAX_SHADOW_MAPS ? light_count : OB_MAX_SHADOW_MAPS;
    int layers_2d = 0, cubes = 0;
    int layer_of[OB_MAX_SHADOW_MAPS] = {0};
    for (int m = 0; m < count; ++m) layer_of[m] = lights[m].type == OB_LIGHT_POINT ? cubes++ : layers_2d++;

    GLint max_size = 0, max_cube = 0;
    glGetIntegerv(GL_MAX_TEXTURE_SIZE, &max_size);
    glGetIntegerv(GL_MAX_CUBE_MAP_TEXTURE_SIZE, &max_cube);
    ob_error err = check_settings(settings, cubes > 0 && max_cube < max_size ? max_cube : max_size);
    if (err != OB_OK) return err;
    int bits = settings->vsm_bits == 16 ? 16 : 32;
    if (settings->method == OB_SHADOW_VSM && bits == 16 && !s->vsm_x16.program) {
        /* The 16-bit moments' passes, on first use: most frames never ask for them. */
        err = ob_compute_pass_init(&s->vsm_x16, "shadow_vsm.glsl",
                                   "#define OB_SHADOW_VSM_MOMENTS 1\n#define OB_SHADOW_VSM_FORMAT rg16f\n",
                                   sizeof(ob_shadow_vsm_constants));
        if (err == OB_OK)
            err = ob_compute_pass_init(&s->vsm_y16, "shadow_vsm.glsl", "#define OB_SHADOW_VSM_FORMAT rg16f\n",
                                       sizeof(ob_shadow_vsm_constants));
        if (err != OB_OK) return err;
    }
    err = allocate(s, settings->size, layers_2d, cubes, settings->method == OB_SHADOW_VSM ? layers_2d : 0, bits);
    if (err != OB_OK) return err;

    if (timers) ob_timer_begin(timers, "shadow");
    set_sampling(s, settings->method);
    GLint viewport[4] = {0, 0, 0, 0};
    glGetIntegerv(GL_VIEWPORT, viewport);
    GLboolean depth_test = glIsEnabled(GL_DEPTH_TEST);
    glBindFramebuffer(GL_FRAMEBUFFER, s->fbo);
    glViewport(0, 0, s->size, s->size);
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_LESS);
    glDepthMask(GL_TRUE);
    /* Both faces: scenes are full of single-sided sheets (floors, walls) that must still cast. */
    glDisable(GL_CULL_FACE);
    glBindBufferBase(GL_UNIFORM_BUFFER, OB_BINDING_PASS, s->ubo);

    memset(s->matrix, 0, sizeof s->matrix);
    memset(s->params, 0, sizeof s->params);
    for (int m = 0; m < count; ++m) {
        const ob_light *l = &lights[m];
        float *params = s->params[m];
        mat4 view_proj;
        if (l->type == OB_LIGHT_POINT) {
            float near_z = 0.0f, far_z = 0.0f;
            point_map(l, bounds_min, bounds_max, settings, &near_z, &far_z, params);
            const float light[4] = {l->position[0], l->position[1], l->position[2], 1.0f / far_z};
            vec3 pos = {l->position[0], l->position[1], l->position[2]};
            mat4 proj;
            glm_perspective(glm_rad(90.0f), 1.0f, near_z, far_z, proj);
            glUseProgram(s->distance_program);
            for (int f = 0; f < 6; ++f) {
                vec3 target, up = {cube_ups[f][0], cube_ups[f][1], cube_ups[f][2]};
                mat4 view;
                glm_vec3_add(pos, (float *)cube_dirs[f], target);
                glm_lookat(pos, target, up, view);
                glm_mat4_mul(proj, view, view_proj);
                draw_layer(s, g, s->maps_cube, 6 * layer_of[m] + f, (const float *)view_proj, light);
            }
            glm_mat4_identity(view_proj); /* unused by the lookup: cubes are indexed by direction */
        } else if (l->type == OB_LIGHT_SPOT) {
            spot_map(l, bounds_min, bounds_max, settings, view_proj, params);
            const float light[4] = {l->position[0], l->position[1], l->position[2], 1.0f / params[3]};
            glUseProgram(s->distance_program);
            draw_layer(s, g, s->maps_2d, layer_of[m], (const float *)view_proj, light);
        } else {
            directional_map(l, bounds_min, bounds_max, settings, view_proj, params);
            const float light[4] = {0.0f, 0.0f, 0.0f, 0.0f};
            glUseProgram(s->depth_program);
            draw_layer(s, g, s->maps_2d, layer_of[m], (const float *)view_proj, light);
        }
        params[2] = (float)layer_of[m];
        memcpy(s->matrix[m], view_proj, sizeof s->matrix[m]);
        s->light_map[m] = m;
    }
    glBindVertexArray(0);
    glNamedFramebufferTexture(s->fbo, GL_DEPTH_ATTACHMENT, 0, 0);
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    glViewport(viewport[0], viewport[1], viewport[2], viewport[3]);
    if (!depth_test) glDisable(GL_DEPTH_TEST);

    /* The lookups (and the VSM pass) read what the depth pass rendered. */
    glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT | GL_FRAMEBUFFER_BARRIER_BIT);
    if (settings->method == OB_SHADOW_VSM && s->moment_layers > 0) blur_moments(s, settings->vsm_blur);

    s->method = settings->method;
    s->options[0] = (float)settings->method;
    s->options[1] = (float)settings->pcf_radius;
    s->options[2] = VSM_MIN_VARIANCE;
    s->options[3] = settings->vsm_bleed;
    if (timers) ob_timer_end(timers);
    s->key_valid = true;
    memcpy(s->key_lights, lights, (size_t)count * sizeof *lights);
    s->key_count = count;
    s->key_settings = *settings;
    memcpy(s->key_bounds, bounds_min, 3 * sizeof(float));
    memcpy(s->key_bounds + 3, bounds_max, 3 * sizeof(float));
    s->key_scene = g->scene_generation;
    return OB_OK;
}

void ob_shadows_fill(const ob_shadow_maps *s, ob_lighting_constants *c, ob_frame_constants *frame)
{
    bool on = s->method != OB_SHADOW_NONE;
    memcpy(c->shadow_matrix, s->matrix, sizeof c->shadow_matrix);
    memcpy(c->shadow_params, s->params, sizeof c->shadow_params);
    c->shadow_method = on ? (int)s->options[0] : OB_SHADOW_METHOD_NONE;
    c->pcf_radius = on ? (int)s->options[1] : 0;
    c->vsm_min_variance = on ? s->options[2] : 0.0f;
    c->vsm_bleed = on ? s->options[3] : 0.0f;
    for (int i = 0; i < OB_MAX_LIGHTS; ++i) frame->light_direction[i][3] = on ? (float)s->light_map[i] : -1.0f;
    /* A shadow sampler only sees a comparing texture: VSM's 2D depth (comparison off) stays
     * unbound, its lookups read the moments. */
    glBindTextureUnit(OB_UNIT_SHADOW_MAPS_2D, on && s->method != OB_SHADOW_VSM ? s->maps_2d : 0);
    glBindTextureUnit(OB_UNIT_SHADOW_MAPS_CUBE, on ? s->maps_cube : 0);
    glBindTextureUnit(OB_UNIT_SHADOW_MOMENTS, on && s->method == OB_SHADOW_VSM ? s->moments : 0);
}
