/* The host path (obscura.h, "the host path"; docs/embedding.md): an engine's own depth, normals
 * and direct light through the same AO chain as ob_render_frame (chain.c), with
 *   1. every argument checked before anything is dispatched (target, format, size, levels), so a
 *      wrong texture is a one-line OB_ERR_INVALID_ARGUMENT naming it, never wrong AO;
 *   2. the input pass (passes/host.c) where the engine's textures are not what the chain reads
 *      (a depth buffer, packed or world-space normals, none at all);
 *   3. the output pass where the host's output is not the chain's own R32F at the visible size;
 *   4. the GL state the passes touch saved and put back, and no glGetError (gpu/state.c), so a
 *      host's pending error stays its own.
 * ob_compute_ao and ob_compute_ao_filtered are this path with linear depth, view normals, one R32F
 * output and the method's radius as set. */
#include <cglm/cglm.h>
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "base/error.h"
#include "core/renderer.h"

/* ---- what a texture is ------------------------------------------------------------------------ */

static const struct {
    GLenum value;
    const char *name;
} format_names[] = {
    {GL_DEPTH_COMPONENT16, "GL_DEPTH_COMPONENT16"}, {GL_DEPTH_COMPONENT24, "GL_DEPTH_COMPONENT24"},
    {GL_DEPTH_COMPONENT32, "GL_DEPTH_COMPONENT32"}, {GL_DEPTH_COMPONENT32F, "GL_DEPTH_COMPONENT32F"},
    {GL_DEPTH24_STENCIL8, "GL_DEPTH24_STENCIL8"},   {GL_DEPTH32F_STENCIL8, "GL_DEPTH32F_STENCIL8"},
    {GL_R8, "GL_R8"},                               {GL_R16, "GL_R16"},
    {GL_R16F, "GL_R16F"},                           {GL_R32F, "GL_R32F"},
    {GL_R32I, "GL_R32I"},                           {GL_R32UI, "GL_R32UI"},
    {GL_RG8, "GL_RG8"},                             {GL_RG16F, "GL_RG16F"},
    {GL_RG16_SNORM, "GL_RG16_SNORM"},               {GL_RG32F, "GL_RG32F"},
    {GL_RGB8, "GL_RGB8"},                           {GL_RGB16F, "GL_RGB16F"},
    {GL_RGB32F, "GL_RGB32F"},                       {GL_RGBA8, "GL_RGBA8"},
    {GL_SRGB8_ALPHA8, "GL_SRGB8_ALPHA8"},           {GL_RGB10_A2, "GL_RGB10_A2"},
    {GL_RGBA16, "GL_RGBA16"},                       {GL_RGBA16F, "GL_RGBA16F"},
    {GL_RGBA32F, "GL_RGBA32F"},                     {GL_R11F_G11F_B10F, "GL_R11F_G11F_B10F"},
    {GL_RGBA8_SNORM, "GL_RGBA8_SNORM"},             {GL_RGBA16_SNORM, "GL_RGBA16_SNORM"},
    {GL_RGBA16UI, "GL_RGBA16UI"},                   {GL_RGBA32UI, "GL_RGBA32UI"},
    {GL_RGBA8UI, "GL_RGBA8UI"},                     {GL_RG16UI, "GL_RG16UI"},
    {GL_RG32UI, "GL_RG32UI"},                       {GL_R8UI, "GL_R8UI"},
    {GL_R16UI, "GL_R16UI"},                         {GL_RGBA32I, "GL_RGBA32I"},
    {GL_STENCIL_INDEX8, "GL_STENCIL_INDEX8"},       {GL_SRGB8, "GL_SRGB8"},
    {GL_RG8_SNORM, "GL_RG8_SNORM"},                 {GL_R8_SNORM, "GL_R8_SNORM"},
    {GL_RG16, "GL_RG16"},                           {GL_RGB10_A2UI, "GL_RGB10_A2UI"},
    {GL_RGB9_E5, "GL_RGB9_E5"},                     {GL_RGB16_SNORM, "GL_RGB16_SNORM"},
};

static const char *format_name(GLint format, char *buf, size_t n)
{
    for (size_t i = 0; i < sizeof format_names / sizeof format_names[0]; ++i)
        if ((GLint)format_names[i].value == format) return format_names[i].name;
    snprintf(buf, n, "format 0x%x", (unsigned)format);
    return buf;
}

static const char *target_name(GLint target)
{
    switch (target) {
    case GL_TEXTURE_1D: return "GL_TEXTURE_1D";
    case GL_TEXTURE_2D: return "GL_TEXTURE_2D";
    case GL_TEXTURE_3D: return "GL_TEXTURE_3D";
    case GL_TEXTURE_1D_ARRAY: return "GL_TEXTURE_1D_ARRAY";
    case GL_TEXTURE_2D_ARRAY: return "GL_TEXTURE_2D_ARRAY";
    case GL_TEXTURE_RECTANGLE: return "GL_TEXTURE_RECTANGLE";
    case GL_TEXTURE_CUBE_MAP: return "GL_TEXTURE_CUBE_MAP";
    case GL_TEXTURE_CUBE_MAP_ARRAY: return "GL_TEXTURE_CUBE_MAP_ARRAY";
    case GL_TEXTURE_BUFFER: return "GL_TEXTURE_BUFFER";
    case GL_TEXTURE_2D_MULTISAMPLE: return "GL_TEXTURE_2D_MULTISAMPLE";
    case GL_TEXTURE_2D_MULTISAMPLE_ARRAY: return "GL_TEXTURE_2D_MULTISAMPLE_ARRAY";
    default: return "texture of an unknown target";
    }
}

typedef struct texture_info {
    GLint format, width, height;
    GLint stencil_mode; /* GL_DEPTH_STENCIL_TEXTURE_MODE of a depth-stencil texture */
    bool complete; /* level 0 is read or written as is, whatever the texture's own sampler state */
} texture_info;

/* One accepted set of formats for an argument, for the messages. */
typedef struct format_set {
    const GLenum *formats;
    int count;
} format_set;

static bool in_set(const format_set *set, GLint format)
{
    for (int i = 0; i < set->count; ++i)
        if ((GLint)set->formats[i] == format) return true;
    return false;
}

static void set_list(const format_set *set, char *buf, size_t n)
{
    buf[0] = '\0';
    for (int i = 0; i < set->count; ++i) {
        char tmp[32];
        size_t used = strlen(buf);
        snprintf(buf + used, n - used, "%s%s", i ? ", " : "", format_name((GLint)set->formats[i], tmp, sizeof tmp));
    }
}

/* Level 0 of a mutable texture with a mipmapping min filter is read only when every level down to
 * 1x1 (or GL_TEXTURE_MAX_LEVEL) is there in the same format (GL 4.5 §8.17, completeness):
 * otherwise texelFetch reads zeros and image stores are dropped. Immutable storage is complete. */
static bool mipmaps_complete(GLuint tex, const texture_info *ti)
{
    GLint max_level = 1000;
    glGetTextureParameteriv(tex, GL_TEXTURE_MAX_LEVEL, &max_level);
    int w = ti->width, h = ti->height;
    for (int level = 1; level <= max_level && (w > 1 || h > 1); ++level) {
        w = w > 1 ? w / 2 : 1;
        h = h > 1 ? h / 2 : 1;
        GLint lw = 0, lh = 0, lf = 0;
        glGetTextureLevelParameteriv(tex, level, GL_TEXTURE_WIDTH, &lw);
        glGetTextureLevelParameteriv(tex, level, GL_TEXTURE_HEIGHT, &lh);
        glGetTextureLevelParameteriv(tex, level, GL_TEXTURE_INTERNAL_FORMAT, &lf);
        if (lw != w || lh != h || lf != ti->format) return false;
    }
    return true;
}

/* The texture `what` (e.g. "normal") as the library will read or write it: a 2D texture with a
 * level 0 of width x height in one of `set`. Queries only (no glGetError: glIsTexture first, so no
 * query can raise one). */
static ob_error check_texture(GLuint tex, const char *what, const format_set *set, int width, int height,
                              texture_info *ti)
{
    char list[512], fmt[32];
    set_list(set, list, sizeof list);
    if (!tex) return ob_set_error(OB_ERR_INVALID_ARGUMENT, "%s texture is 0; expected a GL_TEXTURE_2D of %dx%d and one of %s", what, width, height, list);
    if (!glIsTexture(tex))
        return ob_set_error(OB_ERR_INVALID_ARGUMENT, "%s texture %u is not a texture name (made by glCreateTextures, or bound once)",
                            what, tex);
    GLint target = 0;
    glGetTextureParameteriv(tex, GL_TEXTURE_TARGET, &target);
    if (target != GL_TEXTURE_2D)
        return ob_set_error(OB_ERR_INVALID_ARGUMENT, "%s texture %u is a %s; expected GL_TEXTURE_2D", what, tex,
                            target_name(target));
    memset(ti, 0, sizeof *ti);
    GLint base = 0, immutable = 0, min_filter = 0;
    glGetTextureParameteriv(tex, GL_TEXTURE_BASE_LEVEL, &base);
    glGetTextureParameteriv(tex, GL_TEXTURE_IMMUTABLE_FORMAT, &immutable);
    glGetTextureParameteriv(tex, GL_TEXTURE_MIN_FILTER, &min_filter);
    glGetTextureLevelParameteriv(tex, 0, GL_TEXTURE_INTERNAL_FORMAT, &ti->format);
    glGetTextureLevelParameteriv(tex, 0, GL_TEXTURE_WIDTH, &ti->width);
    glGetTextureLevelParameteriv(tex, 0, GL_TEXTURE_HEIGHT, &ti->height);
    ti->stencil_mode = GL_DEPTH_COMPONENT;
    if (ti->format == GL_DEPTH24_STENCIL8 || ti->format == GL_DEPTH32F_STENCIL8)
        glGetTextureParameteriv(tex, GL_DEPTH_STENCIL_TEXTURE_MODE, &ti->stencil_mode);
    if (ti->width == 0 || ti->height == 0)
        return ob_set_error(OB_ERR_INVALID_ARGUMENT, "%s texture %u has no level 0 image; expected %dx%d and one of %s", what,
                            tex, width, height, list);
    if (!in_set(set, ti->format) || ti->width != width || ti->height != height)
        return ob_set_error(OB_ERR_INVALID_ARGUMENT, "%s texture %u is %dx%d %s; expected %dx%d and one of %s", what, tex,
                            ti->width, ti->height, format_name(ti->format, fmt, sizeof fmt), width, height, list);
    if (base != 0)
        return ob_set_error(OB_ERR_INVALID_ARGUMENT, "%s texture %u has GL_TEXTURE_BASE_LEVEL %d; the library reads and writes level 0",
                            what, tex, base);
    ti->complete = immutable || min_filter == GL_NEAREST || min_filter == GL_LINEAR || mipmaps_complete(tex, ti);
    return OB_OK;
}

/* A texture the chain reads or writes itself (not through the input pass's sampler object) must be
 * complete, or GL reads zeros and drops the stores without a word. */
static ob_error need_complete(GLuint tex, const char *what, const texture_info *ti)
{
    if (ti->complete) return OB_OK;
    return ob_set_error(OB_ERR_INVALID_ARGUMENT,
                        "%s texture %u is incomplete: a mipmapping GL_TEXTURE_MIN_FILTER without its MIP levels (GL would read "
                        "zeros or drop the writes); set GL_TEXTURE_MIN_FILTER to GL_NEAREST or GL_LINEAR, or make it with "
                        "glTextureStorage2D",
                        what, tex);
}

#define SET(name, ...)                                                                                        \
    static const GLenum name##_formats[] = {__VA_ARGS__};                                                  \
    static const format_set name = {name##_formats, (int)(sizeof name##_formats / sizeof name##_formats[0])}

SET(depth_set, GL_DEPTH_COMPONENT16, GL_DEPTH_COMPONENT24, GL_DEPTH_COMPONENT32F, GL_DEPTH24_STENCIL8,
    GL_DEPTH32F_STENCIL8, GL_R16F, GL_R32F);
SET(hardware_set, GL_DEPTH_COMPONENT16, GL_DEPTH_COMPONENT24, GL_DEPTH_COMPONENT32F, GL_DEPTH24_STENCIL8,
    GL_DEPTH32F_STENCIL8);
SET(linear_set, GL_R16F, GL_R32F);
SET(normal_set, GL_RGBA16F, GL_RGBA32F, GL_RGB10_A2, GL_RGBA8, GL_RG16F, GL_RG16_SNORM, GL_RG8);
SET(radiance_set, GL_RGBA16F, GL_RGBA32F, GL_R11F_G11F_B10F);
SET(albedo_set, GL_RGBA8, GL_SRGB8_ALPHA8, GL_RGBA16F);
SET(motion_set, GL_RG16F, GL_RG32F);
SET(ao_set, GL_R8, GL_R16F, GL_R32F, GL_RGBA8, GL_RGBA16F, GL_RGBA32F);
SET(bent_set, GL_RGBA16F, GL_RGBA32F);
SET(indirect_set, GL_RGBA16F, GL_RGBA32F, GL_R11F_G11F_B10F);

static bool is_hardware(GLint format) { return in_set(&hardware_set, format); }

static int normal_encoding(GLint format)
{
    switch (format) {
    case GL_RGBA16F:
    case GL_RGBA32F: return OB_HOST_NORMAL_RAW;
    case GL_RGB10_A2:
    case GL_RGBA8: return OB_HOST_NORMAL_UNORM;
    case GL_RG16F:
    case GL_RG16_SNORM: return OB_HOST_NORMAL_OCT;
    default: return OB_HOST_NORMAL_OCT_UNORM; /* GL_RG8 */
    }
}

/* ---- the call ----------------------------------------------------------------------------------- */

static bool finite16(const float *m)
{
    for (int i = 0; i < 16; ++i)
        if (!isfinite(m[i])) return false;
    return true;
}

static bool all_zero16(const float *m)
{
    for (int i = 0; i < 16; ++i)
        if (m[i] != 0.0f) return false;
    return true;
}

/* Everything one call resolved from its arguments, before anything is dispatched. */
typedef struct host_plan {
    ob_method_plan method;
    ao_targets *targets;
    int guard, in_width, in_height;
    texture_info depth, normal, second, ao, bent, indirect;
    bool hardware;              /* the depth is a depth buffer */
    bool orthographic;          /* the projection is orthographic (P23 = 0, P33 = 1) */
    bool input_pass;            /* depth and normals go through the input pass */
    bool second_pass;           /* the second layer goes through it too */
    bool ao_direct;             /* the chain writes the host's ao texture itself */
    float view[16], proj[16];   /* world -> view; the jittered projection at the input size */
    float unjittered_proj[16];  /* the same without the jitter (the accumulation's reprojection) */
} host_plan;

/* The settings and every argument, checked; fills the plan. `legacy`: ob_compute_ao's rules (the
 * radius as set, no temporal, AO scale or guard band: the caller cleared them). */
static ob_error check_call(ob_renderer *r, const ob_host_frame *f, const ob_settings *s, const ob_host_outputs *o,
                           bool legacy, host_plan *hp)
{
    if (!r || !f || !s || !o)
        return ob_set_error(OB_ERR_INVALID_ARGUMENT, "ob_host_ao: the %s is NULL",
                            !r ? "renderer" : !f ? "frame (ob_host_frame)" : !s ? "settings" : "outputs (ob_host_outputs)");
    if (ob_check_settings(s) != OB_OK) return ob_peek_error(NULL);
    memset(hp, 0, sizeof *hp);
    const ob_method_impl *m = ob_method_impl_at(s->method);
    const char *name = m->info.name;
    const int radius_at = ob_method_role(m, OB_ROLE_RADIUS);
    /* No scene to take R from: a host says it in its own units (a 0.5 default would be no AO at
     * all in a centimetre engine and everything occluded in a kilometre one). */
    if (!legacy && radius_at >= 0 && !(s->params_set & (1u << radius_at)))
        return ob_set_error(OB_ERR_INVALID_ARGUMENT,
                            "%s's radius is not set: give R in your world units (ob_host_settings.radius, or \"radius=R\" "
                            "in ob_settings_set; docs/embedding.md, \"Choosing R\")",
                            name);
    const uint32_t reads = ob_method_active_reads(m, s->params);
    if (reads & OB_READS_EXTRA_VIEW)
        return ob_set_error(OB_ERR_INVALID_ARGUMENT, "%s with extra_view = on renders a second camera of the scene: "
                            "ob_render_frame only (set extra_view=off)", name);
    ob_host_input_size(r, s, &hp->in_width, &hp->in_height, &hp->guard);
    const int w = hp->in_width, h = hp->in_height;
    if (w > r->ctx->max_texture_size || h > r->ctx->max_texture_size)
        return ob_set_error(OB_ERR_BAD_SIZE, "the guard band of %d px makes the input %dx%d, above GL_MAX_TEXTURE_SIZE %d",
                            hp->guard, w, h, r->ctx->max_texture_size);

    /* The camera. */
    const float *p = f->projection;
    if (!finite16(p) || !finite16(f->view) || !isfinite(f->jitter[0]) || !isfinite(f->jitter[1]) ||
        !isfinite(f->motion_scale[0]) || !isfinite(f->motion_scale[1]))
        return ob_set_error(OB_ERR_INVALID_ARGUMENT, "the projection, view, jitter or motion_scale is not finite");
    hp->orthographic = ob_projection_is_orthographic(p);
    if (hp->orthographic) {
        /* x and y scaled and offset, z scaled (its row linearises a depth buffer: P22 != 0), no
         * shear: the methods rebuild X = (ndc.x - P30) / P00 (common.glsl ob_view_position). */
        if (p[3] != 0.0f || p[7] != 0.0f || p[0] == 0.0f || p[5] == 0.0f || p[10] == 0.0f)
            return ob_set_error(OB_ERR_INVALID_ARGUMENT,
                                "the projection is orthographic (P23 = 0, P33 = 1) but not an OpenGL orthographic matrix "
                                "(column-major; P03 = %g, P13 = %g, P00 = %g, P11 = %g, P22 = %g; expected P03 = P13 = 0, "
                                "P00, P11, P22 non-zero)",
                                (double)p[3], (double)p[7], (double)p[0], (double)p[5], (double)p[10]);
        if (p[8] != 0.0f || p[9] != 0.0f)
            return ob_set_error(OB_ERR_INVALID_ARGUMENT,
                                "the projection is an oblique orthographic one (P20 = %g, P21 = %g): an orthographic "
                                "projection is taken with P20 = P21 = 0 (an off-centre one offsets P30, P31)",
                                (double)p[8], (double)p[9]);
    } else if (p[11] != -1.0f || p[15] != 0.0f || p[3] != 0.0f || p[7] != 0.0f || p[0] == 0.0f || p[5] == 0.0f ||
               p[14] == 0.0f) {
        return ob_set_error(OB_ERR_INVALID_ARGUMENT,
                            "the projection is neither an OpenGL perspective matrix nor an orthographic one (column-major; "
                            "P23 = %g, P33 = %g, P00 = %g, P11 = %g, P32 = %g; expected P23 = -1, P33 = 0, the rest "
                            "non-zero, or P23 = 0, P33 = 1)",
                            (double)p[11], (double)p[15], (double)p[0], (double)p[5], (double)p[14]);
    }
    memcpy(hp->proj, p, sizeof hp->proj);
    memcpy(hp->unjittered_proj, p, sizeof hp->unjittered_proj);
    if (hp->orthographic) {
        /* The same move of the image by -jitter pixels: ndc - 2 jitter / size, with w = 1. */
        hp->proj[12] -= 2.0f * f->jitter[0] / (float)w;
        hp->proj[13] -= 2.0f * f->jitter[1] / (float)h;
    } else {
        hp->proj[8] += 2.0f * f->jitter[0] / (float)w;
        hp->proj[9] += 2.0f * f->jitter[1] / (float)h;
    }
    if (all_zero16(f->view)) {
        mat4 identity = GLM_MAT4_IDENTITY_INIT;
        memcpy(hp->view, identity, sizeof hp->view);
    } else {
        mat4 v;
        memcpy(v, f->view, sizeof v);
        float det = glm_mat4_det(v);
        if (!(fabsf(det) > 1e-12f) || !isfinite(det))
            return ob_set_error(OB_ERR_INVALID_ARGUMENT, "the view matrix is singular (determinant %g)", (double)det);
        memcpy(hp->view, f->view, sizeof hp->view);
    }

    /* The inputs. */
    if (check_texture(f->depth, "depth", &depth_set, w, h, &hp->depth) != OB_OK) return ob_peek_error(NULL);
    hp->hardware = is_hardware(hp->depth.format);
    if (f->normal && check_texture(f->normal, "normal", &normal_set, w, h, &hp->normal) != OB_OK)
        return ob_peek_error(NULL);
    if (f->normal_space != OB_NORMALS_VIEW && f->normal_space != OB_NORMALS_WORLD)
        return ob_set_error(OB_ERR_INVALID_ARGUMENT, "normal_space %d is neither OB_NORMALS_VIEW (0) nor OB_NORMALS_WORLD (1)",
                            (int)f->normal_space);
    const bool depth_direct = !hp->hardware && hp->depth.complete && hp->depth.format == GL_R32F;
    const bool normal_direct = f->normal && hp->normal.complete && f->normal_space == OB_NORMALS_VIEW &&
                               normal_encoding(hp->normal.format) == OB_HOST_NORMAL_RAW;
    hp->input_pass = !depth_direct || !normal_direct;
    if (f->second_depth) {
        if (check_texture(f->second_depth, "second_depth", hp->hardware ? &hardware_set : &linear_set, w, h, &hp->second) !=
            OB_OK)
            return ob_peek_error(NULL);
        hp->second_pass = (reads & OB_READS_SECOND_LAYER) &&
                          (hp->hardware || !hp->second.complete || hp->second.format != GL_R32F);
    }
    texture_info ti;
    if (reads & OB_READS_RADIANCE) {
        if (!f->radiance)
            return ob_set_error(OB_ERR_INVALID_ARGUMENT, "%s reads the host's direct light: ob_host_frame.radiance is 0", name);
        if (check_texture(f->radiance, "radiance", &radiance_set, w, h, &ti) != OB_OK ||
            need_complete(f->radiance, "radiance", &ti) != OB_OK)
            return ob_peek_error(NULL);
    }
    if ((reads & OB_READS_ALBEDO) && !f->albedo)
        return ob_set_error(OB_ERR_INVALID_ARGUMENT, "%s reads the host's albedo: ob_host_frame.albedo is 0", name);
    if (f->albedo && (check_texture(f->albedo, "albedo", &albedo_set, w, h, &ti) != OB_OK ||
                      need_complete(f->albedo, "albedo", &ti) != OB_OK))
        return ob_peek_error(NULL);
    if (f->motion && (check_texture(f->motion, "motion", &motion_set, w, h, &ti) != OB_OK ||
                      need_complete(f->motion, "motion", &ti) != OB_OK))
        return ob_peek_error(NULL);

    /* The outputs, at the visible size. */
    if (check_texture(o->ao, "ao", &ao_set, r->width, r->height, &hp->ao) != OB_OK ||
        need_complete(o->ao, "ao", &hp->ao) != OB_OK)
        return ob_peek_error(NULL);
    if (o->bent_normal && (check_texture(o->bent_normal, "bent_normal", &bent_set, r->width, r->height, &hp->bent) != OB_OK ||
                           need_complete(o->bent_normal, "bent_normal", &hp->bent) != OB_OK))
        return ob_peek_error(NULL);
    if (o->indirect && (check_texture(o->indirect, "indirect", &indirect_set, r->width, r->height, &hp->indirect) != OB_OK ||
                        need_complete(o->indirect, "indirect", &hp->indirect) != OB_OK))
        return ob_peek_error(NULL);
    const GLuint names[3] = {o->ao, o->bent_normal, o->indirect};
    const GLuint inputs[6] = {f->depth, f->normal, f->second_depth, f->radiance, f->albedo, f->motion};
    for (int i = 0; i < 3; ++i)
        for (int k = 0; k < 6 && names[i]; ++k)
            if (names[i] == inputs[k])
                return ob_set_error(OB_ERR_INVALID_ARGUMENT, "output texture %u is also an input: the passes would read what they write",
                                    names[i]);
    const bool rgb = (m->writes & OB_WRITES_VISIBILITY_RGB) != 0;
    hp->ao_direct = !rgb && hp->guard == 0 && hp->ao.format == GL_R32F;
    return OB_OK;
}

/* The input pass's variant and constants: how to read the host's depth and normals. */
static void fill_input(const host_plan *hp, const ob_host_frame *f, ob_host_input_variant *v, ob_host_input_constants *c)
{
    *v = (ob_host_input_variant){.depth_kind = hp->hardware ? OB_HOST_DEPTH_WINDOW : OB_HOST_DEPTH_LINEAR,
                                 .normal_encoding = f->normal ? normal_encoding(hp->normal.format) : OB_HOST_NORMAL_NONE,
                                 .second = hp->second_pass};
    memset(c, 0, sizeof *c);
    mat4 to_view = GLM_MAT4_IDENTITY_INIT;
    if (f->normal_space == OB_NORMALS_WORLD) {
        /* Normals turn with the view's rotation; its inverse transpose for a view with scale. */
        mat4 view, inv;
        memcpy(view, hp->view, sizeof view);
        glm_mat4_inv(view, inv);
        glm_mat4_transpose_to(inv, to_view);
    }
    memcpy(c->normal_to_view, to_view, sizeof c->normal_to_view);
    c->size[0] = hp->in_width;
    c->size[1] = hp->in_height;
    c->ndc_scale = f->depth_zero_to_one ? 1.0f : 2.0f;
    c->ndc_bias = f->depth_zero_to_one ? 0.0f : -1.0f;
    c->p22 = f->projection[10];
    c->p32 = f->projection[14];
    c->orthographic = hp->orthographic ? 1 : 0;
    /* Window depth falls with distance when ndc does (reversed Z): perspective ndc = -P22 + P32 / d
     * when P32 > 0; orthographic ndc = P32 - P22 d when P22 > 0. */
    c->reversed = hp->orthographic ? f->projection[10] > 0.0f : f->projection[14] > 0.0f;
}

/* One output through the output pass: the chain's `source` at the enlarged size, cropped. */
static ob_error write_output(ob_renderer *r, const host_plan *hp, GLuint source, GLuint target, GLenum format, int mode,
                             const float turn[16])
{
    ob_host_output_constants c;
    memset(&c, 0, sizeof c);
    mat4 identity = GLM_MAT4_IDENTITY_INIT;
    memcpy(c.turn, turn ? turn : (const float *)identity, sizeof c.turn);
    c.size[0] = r->width;
    c.size[1] = r->height;
    c.offset[0] = c.offset[1] = hp->guard;
    c.mode = mode;
    return ob_host_output_run(&r->host, &c, source, target, format);
}

static bool one_channel(GLint format) { return format == GL_R8 || format == GL_R16F || format == GL_R32F; }

static ob_error run_call(ob_renderer *r, const ob_host_frame *f, const ob_settings *s, const ob_host_outputs *o,
                         host_plan *hp)
{
    const GLbitfield barrier = GL_TEXTURE_FETCH_BARRIER_BIT | GL_SHADER_IMAGE_ACCESS_BARRIER_BIT;
    /* The host's textures are the enlarged size: the renderer's targets follow its band. */
    ob_error err = ob_renderer_reshape(r, r->width, r->height, hp->guard);
    if (err != OB_OK) return err;
    err = ob_plan_method(r, s, 0.0f, &hp->method);
    if (err != OB_OK) return err;
    const int si = ob_scale_index(s->ao_divisor);
    hp->targets = ob_renderer_targets(r, si);
    r->last.scale = si;
    ob_frame_constants_fill(&r->frame_constants,
                            &(ob_frame_desc){.view = hp->view, .proj = hp->proj, .grid = &hp->targets->grid,
                                             .frame_index = r->frame++, .settings = s, .lights = s->lights,
                                             .light_count = s->light_count,
                                             .sh = (const float(*)[3])r->environment.sh});
    ob_ao_grid_projection(&hp->targets->grid, hp->unjittered_proj, r->ao_proj_unjittered);
    ob_upload_frame(r);
    r->has_frame = false; /* the renderer's own frame is being overwritten */
    r->has_host_chain = false;
    ob_chain_io io = {.depth = f->depth,
                      .normal = f->normal,
                      .radiance = f->radiance,
                      .albedo = f->albedo,
                      .second_depth = (hp->method.reads & OB_READS_SECOND_LAYER) ? f->second_depth : 0,
                      .ao = hp->ao_direct ? o->ao : r->ao,
                      .motion = f->motion,
                      .motion_scale = {f->motion_scale[0], f->motion_scale[1]}};
    if (hp->input_pass || hp->second_pass) {
        ob_timer_begin(&r->timers, "input");
        ob_host_input_variant v;
        ob_host_input_constants c;
        fill_input(hp, f, &v, &c);
        GLuint second_out = hp->second_pass ? ob_host_second_target(&r->host, hp->in_width, hp->in_height) : 0;
        /* A depth-stencil texture the host reads as stencil is read as depth here, then put back
         * (the dispatch keeps the mode it was issued with). */
        const GLuint stenciled[2] = {hp->depth.stencil_mode == GL_STENCIL_INDEX ? f->depth : 0,
                                     hp->second_pass && hp->second.stencil_mode == GL_STENCIL_INDEX ? f->second_depth : 0};
        for (int i = 0; i < 2; ++i)
            if (stenciled[i]) glTextureParameteri(stenciled[i], GL_DEPTH_STENCIL_TEXTURE_MODE, GL_DEPTH_COMPONENT);
        err = ob_host_input_run(&r->host, &v, &c, f->depth, f->normal, hp->second_pass ? f->second_depth : 0,
                                r->gbuffer.linear_depth, r->gbuffer.normal, second_out);
        for (int i = 0; i < 2; ++i)
            if (stenciled[i]) glTextureParameteri(stenciled[i], GL_DEPTH_STENCIL_TEXTURE_MODE, GL_STENCIL_INDEX);
        if (err != OB_OK) return err;
        glMemoryBarrier(barrier);
        io.depth = r->gbuffer.linear_depth;
        io.normal = r->gbuffer.normal;
        if (hp->second_pass) io.second_depth = second_out;
    }
    err = ob_run_ao_chain(r, s, &hp->method, hp->targets, &io);
    if (err != OB_OK) return err;
    glMemoryBarrier(barrier);
    /* The outputs the chain did not write itself. */
    if (!hp->ao_direct) {
        ob_timer_begin(&r->timers, "output");
        const bool rgb = r->last.rgb;
        const int mode = one_channel(hp->ao.format) ? (rgb ? OB_HOST_OUT_MEAN : OB_HOST_OUT_COPY)
                                                    : (rgb ? OB_HOST_OUT_COPY : OB_HOST_OUT_GREY);
        err = write_output(r, hp, rgb ? r->ao_rgb : r->ao, o->ao, (GLenum)hp->ao.format, mode, NULL);
        if (err != OB_OK) return err;
    }
    const float zero[4] = {0.0f, 0.0f, 0.0f, 0.0f};
    if (o->bent_normal) {
        if (r->last.bent) {
            /* Back into the host's normal space: the inverse of the view's normal matrix. */
            mat4 turn = GLM_MAT4_IDENTITY_INIT;
            if (f->normal_space == OB_NORMALS_WORLD) {
                mat4 v;
                memcpy(v, hp->view, sizeof v);
                glm_mat4_transpose_to(v, turn);
            }
            err = write_output(r, hp, r->bent, o->bent_normal, (GLenum)hp->bent.format, OB_HOST_OUT_NORMAL,
                               (const float *)turn);
            if (err != OB_OK) return err;
        } else {
            glClearTexImage(o->bent_normal, 0, GL_RGBA, GL_FLOAT, zero);
        }
    }
    if (o->indirect) {
        if (r->last.bounce) {
            err = write_output(r, hp, r->bounce, o->indirect, (GLenum)hp->indirect.format, OB_HOST_OUT_COPY, NULL);
            if (err != OB_OK) return err;
        } else {
            glClearTexImage(o->indirect, 0, GL_RGBA, GL_FLOAT, zero);
        }
    }
    /* The host reads what the passes wrote, by any means. */
    glMemoryBarrier(GL_ALL_BARRIER_BITS);
    r->has_host_chain = true;
    r->host_depth_in_gbuffer = io.depth == r->gbuffer.linear_depth;
    return OB_OK;
}

/* State saved, errors left alone, a debug group in a debug context, around one host-path call. */
typedef struct host_scope {
    ob_gl_state state;
    bool debug_group;
} host_scope;

static void enter(host_scope *sc)
{
    ob_gl_state_save(&sc->state, OB_HOST_TEXTURE_UNITS, OB_HOST_IMAGE_UNITS);
    ob_gl_set_quiet(true);
    GLint flags = 0;
    glGetIntegerv(GL_CONTEXT_FLAGS, &flags);
    sc->debug_group = (flags & GL_CONTEXT_FLAG_DEBUG_BIT) != 0;
    if (sc->debug_group) glPushDebugGroup(GL_DEBUG_SOURCE_THIRD_PARTY, 0, -1, "obscura");
}

static void leave(const host_scope *sc)
{
    if (sc->debug_group) glPopDebugGroup();
    ob_gl_state_restore(&sc->state);
    ob_gl_set_quiet(false);
}

static ob_error host_ao(ob_renderer *r, const ob_host_frame *f, const ob_settings *s, const ob_host_outputs *o,
                        bool legacy)
{
    host_plan hp;
    if (check_call(r, f, s, o, legacy, &hp) != OB_OK) return ob_peek_error(NULL);
    host_scope sc;
    enter(&sc);
    ob_timers_frame_begin(&r->timers);
    ob_error err = run_call(r, f, s, o, &hp);
    ob_timers_frame_end(&r->timers);
    leave(&sc);
    return err;
}

ob_error ob_host_ao(ob_renderer *r, const ob_host_frame *frame, const ob_settings *settings,
                    const ob_host_outputs *outputs)
{
    return host_ao(r, frame, settings, outputs, false);
}

void ob_host_input_size(const ob_renderer *r, const ob_settings *s, int *width, int *height, int *guard)
{
    int k = s && s->ao_divisor > 0 ? s->ao_divisor : 1;
    int g = r && s ? ob_guard_pixels(s->guard, k) : 0;
    if (width) *width = r ? r->width + 2 * g : 0;
    if (height) *height = r ? r->height + 2 * g : 0;
    if (guard) *guard = g;
}

static GLuint scratch_texture(GLenum format, int w, int h, const float value[4])
{
    GLuint t = ob_make_texture_2d(format, w, h);
    const bool depth = is_hardware((GLint)format);
    glClearTexImage(t, 0, depth ? GL_DEPTH_COMPONENT : GL_RGBA, GL_FLOAT, value);
    return t;
}

/* Calls on scratch textures of the formats hosts use most, so that every program these settings
 * need is compiled, and on a software rasteriser also specialised, before the first real frame
 * (a compute program's machine code is made at its first dispatch there, per texture format):
 * linear R32F depth and RGBA16F normals (the formats the chain reads whatever the host passes),
 * then a D32F depth buffer and RG16F octahedral normals through the input pass, with the outputs
 * in R8, R16F, R32F, RGBA8 and RGBA16F. The history and the frame count are forgotten after. */
ob_error ob_host_prepare(ob_renderer *r, const ob_settings *s)
{
    if (!r) return ob_set_error(OB_ERR_INVALID_ARGUMENT, "ob_host_prepare: NULL renderer");
    if (ob_check_settings(s) != OB_OK) return ob_peek_error(NULL);
    int w = 0, h = 0;
    ob_host_input_size(r, s, &w, &h, NULL);
    const float one[4] = {1.0f, 1.0f, 1.0f, 1.0f}, half[4] = {0.5f, 0.5f, 0.5f, 0.5f}, up[4] = {0.0f, 0.0f, 1.0f, 1.0f};
    enum { DEPTH, NORMAL, RADIANCE, ALBEDO, HARDWARE, OCTAHEDRAL, BENT, INDIRECT, AO_R8, AO_R16F, AO_R32F, AO_RGBA8,
           AO_RGBA16F, COUNT };
    GLuint t[COUNT];
    t[DEPTH] = scratch_texture(GL_R32F, w, h, one);
    t[NORMAL] = scratch_texture(GL_RGBA16F, w, h, up);
    t[RADIANCE] = scratch_texture(GL_RGBA16F, w, h, half);
    t[ALBEDO] = scratch_texture(GL_RGBA16F, w, h, half);
    t[HARDWARE] = scratch_texture(GL_DEPTH_COMPONENT32F, w, h, half);
    t[OCTAHEDRAL] = scratch_texture(GL_RG16F, w, h, up);
    t[BENT] = scratch_texture(GL_RGBA16F, r->width, r->height, up);
    t[INDIRECT] = scratch_texture(GL_RGBA16F, r->width, r->height, up);
    const GLenum ao_formats[5] = {GL_R8, GL_R16F, GL_R32F, GL_RGBA8, GL_RGBA16F};
    for (int i = 0; i < 5; ++i) t[AO_R8 + i] = scratch_texture(ao_formats[i], r->width, r->height, one);
    /* A perspective of 60 degrees from 0.1 to 100: what the programs see does not depend on it. */
    ob_host_frame f = {.depth = t[DEPTH], .normal = t[NORMAL], .radiance = t[RADIANCE], .albedo = t[ALBEDO]};
    mat4 proj;
    glm_perspective(glm_rad(60.0f), (float)w / (float)h, 0.1f, 100.0f, proj);
    memcpy(f.projection, proj, sizeof f.projection);
    const uint32_t frame = r->frame;
    ob_host_outputs o = {.ao = t[AO_R32F], .bent_normal = t[BENT], .indirect = t[INDIRECT]};
    ob_error err = host_ao(r, &f, s, &o, true);
    f.depth = t[HARDWARE];
    f.normal = t[OCTAHEDRAL];
    f.normal_space = OB_NORMALS_WORLD;
    for (int i = 0; i < 5 && err == OB_OK; ++i) {
        o.ao = t[AO_R8 + i];
        err = host_ao(r, &f, s, &o, true);
    }
    glDeleteTextures(COUNT, t);
    r->history_valid = false;
    r->frame = frame;
    return err;
}

/* ob_compute_ao and ob_compute_ao_filtered: the host path with the old arguments. */
static ob_error compute_ao(ob_renderer *r, uint32_t linear_depth_tex, uint32_t normal_tex, const float proj[16],
                           const ob_settings *s, uint32_t ao_out_tex, bool filtered)
{
    if (!r || !proj || !s) return ob_set_error(OB_ERR_INVALID_ARGUMENT, "ob_compute_ao: NULL argument");
    if (ob_check_settings(s) != OB_OK) return ob_peek_error(NULL);
    const ob_method_impl *m = ob_method_impl_at(s->method);
    if ((m->reads & (OB_READS_RADIANCE | OB_READS_ALBEDO)) || (m->writes & (OB_WRITES_VISIBILITY_RGB | OB_WRITES_BOUNCE)))
        return ob_set_error(OB_ERR_INVALID_ARGUMENT, "ob_compute_ao: %s needs the frame's direct light (ob_host_ao)",
                            m->info.name);
    /* As documented: no AO scale, adaptive sampling, temporal accumulation or guard band here. */
    ob_settings c = *s;
    c.ao_divisor = 1;
    c.adaptive = false;
    c.temporal = false;
    c.guard = 0;
    if (!filtered) ob_settings_set_filter(&c, "none");
    ob_host_frame f = {.depth = linear_depth_tex, .normal = normal_tex};
    memcpy(f.projection, proj, sizeof f.projection);
    const ob_host_outputs o = {.ao = ao_out_tex};
    return host_ao(r, &f, &c, &o, true);
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

/* ---- typed settings ------------------------------------------------------------------------------ */

/* Set the parameter of `role` to v, or fail naming what the method lacks. */
static ob_error set_role(ob_settings *s, ob_param_role role, const char *field, float v)
{
    const ob_method_impl *m = ob_method_impl_at(s->method);
    int i = ob_method_role(m, role);
    if (i < 0)
        return ob_set_error(OB_ERR_INVALID_ARGUMENT, "ob_host_settings.%s is set but %s has no %s parameter", field,
                            m->info.name, field);
    char assignment[128];
    snprintf(assignment, sizeof assignment, "%s=%.9g", m->info.params[i].name, (double)v);
    return ob_settings_set(s, assignment);
}

ob_error ob_settings_from_host(ob_settings *settings, const ob_host_settings *h)
{
    if (!settings || !h)
        return ob_set_error(OB_ERR_INVALID_ARGUMENT, "ob_settings_from_host: %s is NULL",
                            !settings ? "settings (the ob_settings to fill)" : "host (the ob_host_settings)");
    ob_settings s;
    if (ob_settings_init(&s, h->method) != OB_OK) return ob_peek_error(NULL);
    if (!(h->radius > 0.0f) || !isfinite(h->radius))
        return ob_set_error(OB_ERR_INVALID_ARGUMENT,
                            "ob_host_settings.radius is %g: give R > 0 in your world units (docs/embedding.md, \"Choosing R\")",
                            (double)h->radius);
    const ob_method_impl *m = ob_method_impl_at(s.method);
    if (ob_method_role(m, OB_ROLE_RADIUS) >= 0 && set_role(&s, OB_ROLE_RADIUS, "radius", h->radius) != OB_OK)
        return ob_peek_error(NULL);
    if (h->quality != OB_QUALITY_DEFAULT) {
        static const char *const names[] = {"", "low", "medium", "high", "ultra"};
        if ((int)h->quality < 0 || (int)h->quality > OB_QUALITY_ULTRA)
            return ob_set_error(OB_ERR_OUT_OF_RANGE, "ob_host_settings.quality %d is outside OB_QUALITY_DEFAULT..ULTRA",
                                (int)h->quality);
        if (ob_settings_set_samples(&s, ob_quality_samples(names[h->quality])) != OB_OK) return ob_peek_error(NULL);
    }
    if (h->intensity != 0.0f && set_role(&s, OB_ROLE_INTENSITY, "intensity", h->intensity) != OB_OK)
        return ob_peek_error(NULL);
    if (h->thickness != 0.0f && set_role(&s, OB_ROLE_THICKNESS, "thickness", h->thickness) != OB_OK)
        return ob_peek_error(NULL);
    if (h->falloff != 0.0f && set_role(&s, OB_ROLE_FALLOFF, "falloff", h->falloff) != OB_OK) return ob_peek_error(NULL);
    if (h->ao_divisor != 0 && h->ao_divisor != 1 && h->ao_divisor != 2 && h->ao_divisor != 4)
        return ob_set_error(OB_ERR_OUT_OF_RANGE, "ob_host_settings.ao_divisor %d is not 0 (the default), 1, 2 or 4",
                            h->ao_divisor);
    if (h->ao_divisor != 0 && ob_settings_set_ao_divisor(&s, h->ao_divisor) != OB_OK) return ob_peek_error(NULL);
    if (h->filter && ob_settings_set_filter(&s, h->filter) != OB_OK) return ob_peek_error(NULL);
    if (h->temporal_frames < 0 || h->temporal_frames > OB_TEMPORAL_FRAMES_MAX)
        return ob_set_error(OB_ERR_OUT_OF_RANGE, "ob_host_settings.temporal_frames %d is outside 0..%d", h->temporal_frames,
                            OB_TEMPORAL_FRAMES_MAX);
    if (h->guard < 0 || h->guard > OB_GUARD_MAX)
        return ob_set_error(OB_ERR_OUT_OF_RANGE, "ob_host_settings.guard %d px is outside 0..%d", h->guard, OB_GUARD_MAX);
    s.temporal = h->temporal;
    s.temporal_frames = h->temporal_frames;
    s.guard = h->guard;
    *settings = s;
    return OB_OK;
}
