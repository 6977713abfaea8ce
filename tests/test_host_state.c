/* The host path leaves the host's GL state alone (issue 45, item 4; obscura.h, "the host path").
 *
 * The test is an engine: its own EGL context (a debug context with its own KHR_debug callback),
 * adopted with ob_context_desc.use_current, and its own objects bound everywhere a library could
 * touch: a program, a program pipeline, a VAO with an element buffer, a 2D texture and a sampler
 * on every texture unit 0..OB_HOST_TEXTURE_UNITS+3 (a cube map and a 2D array on two of them),
 * images on every image unit 0..OB_HOST_IMAGE_UNITS+1 (levels, layers, access and formats of
 * their own), indexed uniform, storage and atomic-counter buffers (ranges on some) and the generic
 * bindings, every other buffer target (pixel pack and unpack, query, indirect, copy, texture
 * buffer), draw and read framebuffers, a renderbuffer, a transform feedback object, an active
 * GL_TIME_ELAPSED query, viewport, scissor, enables, reversed-Z (glClipControl(GL_LOWER_LEFT,
 * GL_ZERO_TO_ONE), GL_GREATER), pixel-store state, a uniform of its program and the parameters of
 * its own textures. Before each library call it reads all of that (some 300 pieces), leaves a GL
 * error pending (GL_INVALID_ENUM, _OPERATION, _VALUE, or none, in turn), calls, and checks:
 *   - every piece reads the same after the call;
 *   - glGetError returns the host's pending error, and then GL_NO_ERROR (no glGetError inside);
 *   - the library raised no GL error of its own (the host's debug callback saw none) and, for a
 *     call that ran, its commands sat in a balanced KHR_debug group "obscura".
 * The calls: ob_host_ao for every method (AO methods with linear R32F depth and with reversed-Z
 * D32F depth and octahedral world-space normals; the indirect-light methods the same, given
 * radiance and albedo) and every filter, method variants with passes of their own (deinterleave,
 * depth MIPs, bent normals, a second layer, packed), ob_host_prepare, the old ob_compute_ao and
 * ob_compute_ao_filtered, AO at 1/2 and 1/4, temporal accumulation with jitter and motion, a
 * guard band, and refused calls (state must be restored on failure too). Last, the AO computed
 * under all of the host's state equals the AO of a renderer made and run in a clean context.
 * The state table printed at the end has a row per kind of state and a column per call family. */
#include <epoxy/egl.h>
#include <epoxy/gl.h>
#include <math.h>
#include <stdarg.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "check.h"
#include "obscura/eval.h"
#include "host_scene.h"

enum { W = 64, H = 48 };
#define EXTRA_TEX_UNITS 4
#define EXTRA_IMAGE_UNITS 2
#define NTEX (OB_HOST_TEXTURE_UNITS + EXTRA_TEX_UNITS)
#define NIMG (OB_HOST_IMAGE_UNITS + EXTRA_IMAGE_UNITS)
/* The image units the test binds and reads: NIMG where the driver has them. OB_HOST_IMAGE_UNITS is
 * GL 4.5's minimum GL_MAX_IMAGE_UNITS (8), which NVIDIA's driver has exactly: there the units past
 * the library's do not exist, and binding one is GL_INVALID_VALUE. */
static int image_units(void)
{
    GLint max = 0;
    glGetIntegerv(GL_MAX_IMAGE_UNITS, &max);
    return max < NIMG ? max : NIMG;
}
#define NBUF 8 /* indexed uniform and storage buffer bindings checked */
#define CUBE_UNIT 3
#define ARRAY_UNIT 6
#define HOST_ACTIVE_UNIT 9 /* the host's active texture unit: neither 0 nor the last */
#define MAX_PIECES 640

/* The host's debug callback: GL errors, and the library's KHR_debug group. */
static struct {
    int errors, pushes, pops, depth_max, depth;
    char first_error[256];
} dbg;

static void GLAPIENTRY on_debug(GLenum source, GLenum type, GLuint id, GLenum severity, GLsizei length,
                                const GLchar *message, const void *user)
{
    (void)source, (void)id, (void)severity, (void)length, (void)user;
    if (type == GL_DEBUG_TYPE_ERROR) {
        if (!dbg.errors++) snprintf(dbg.first_error, sizeof dbg.first_error, "%s", message);
    } else if (type == GL_DEBUG_TYPE_PUSH_GROUP) {
        if (!strcmp(message, "obscura")) ++dbg.pushes;
        if (++dbg.depth > dbg.depth_max) dbg.depth_max = dbg.depth;
    } else if (type == GL_DEBUG_TYPE_POP_GROUP) {
        if (!strcmp(message, "obscura")) ++dbg.pops;
        --dbg.depth;
    }
}

/* ---- the host's GL state -------------------------------------------------------------------------- */
typedef struct host_objects {
    GLuint tex[NTEX], samplers[NTEX], cube, array2d, img2d, img_array;
    GLuint ubo[NBUF], ubo_generic, ssbo[NBUF], ssbo_generic, acbo, array_buf, element_buf, pack_buf, unpack_buf,
        query_buf, dispatch_buf, draw_indirect_buf, copy_read_buf, copy_write_buf, texture_buf;
    GLuint vao, program, pipeline, fbo_draw, fbo_read, rbo, tfo, time_query;
    GLint uniform_loc;
    GLint ubo_align, ssbo_align;
    /* The host's own textures handed to the library, whose parameters are checked too. */
    GLuint watched[8];
    int watched_count;
} host_objects;

static GLuint compile_program(void)
{
    static const char *vs = "#version 450 core\nlayout(location = 0) in vec3 p;\nuniform float u_host;\n"
                            "void main() { gl_Position = vec4(p * u_host, 1.0); }\n";
    static const char *fs = "#version 450 core\nout vec4 c;\nvoid main() { c = vec4(1.0); }\n";
    GLuint prog = glCreateProgram(), sh[2] = {glCreateShader(GL_VERTEX_SHADER), glCreateShader(GL_FRAGMENT_SHADER)};
    glShaderSource(sh[0], 1, &vs, NULL);
    glShaderSource(sh[1], 1, &fs, NULL);
    for (int i = 0; i < 2; ++i) glCompileShader(sh[i]), glAttachShader(prog, sh[i]);
    glLinkProgram(prog);
    GLint ok = 0;
    glGetProgramiv(prog, GL_LINK_STATUS, &ok);
    CHECK(ok, "the host's program links");
    for (int i = 0; i < 2; ++i) glDeleteShader(sh[i]);
    return prog;
}

static void make_host_objects(host_objects *h)
{
    memset(h, 0, sizeof *h);
    glCreateTextures(GL_TEXTURE_2D, NTEX, h->tex);
    for (int i = 0; i < NTEX; ++i) glTextureStorage2D(h->tex[i], 1, GL_RGBA8, 4, 4);
    glCreateSamplers(NTEX, h->samplers);
    for (int i = 0; i < NTEX; ++i) glSamplerParameteri(h->samplers[i], GL_TEXTURE_MIN_FILTER, GL_LINEAR);
    glCreateTextures(GL_TEXTURE_CUBE_MAP, 1, &h->cube);
    glTextureStorage2D(h->cube, 1, GL_RGBA8, 4, 4);
    glCreateTextures(GL_TEXTURE_2D_ARRAY, 1, &h->array2d);
    glTextureStorage3D(h->array2d, 1, GL_RGBA8, 4, 4, 3);
    glCreateTextures(GL_TEXTURE_2D, 1, &h->img2d);
    glTextureStorage2D(h->img2d, 2, GL_RGBA8, 8, 8);
    glCreateTextures(GL_TEXTURE_2D_ARRAY, 1, &h->img_array);
    glTextureStorage3D(h->img_array, 2, GL_R32F, 8, 8, 3);
    glGetIntegerv(GL_UNIFORM_BUFFER_OFFSET_ALIGNMENT, &h->ubo_align);
    glGetIntegerv(GL_SHADER_STORAGE_BUFFER_OFFSET_ALIGNMENT, &h->ssbo_align);
    GLuint *bufs[] = {h->ubo, h->ssbo};
    for (int b = 0; b < 2; ++b) {
        glCreateBuffers(NBUF, bufs[b]);
        for (int i = 0; i < NBUF; ++i) glNamedBufferData(bufs[b][i], 4 * 1024, NULL, GL_DYNAMIC_DRAW);
    }
    GLuint *singles[] = {&h->ubo_generic, &h->ssbo_generic, &h->acbo, &h->array_buf, &h->element_buf, &h->pack_buf,
                         &h->unpack_buf, &h->query_buf, &h->dispatch_buf, &h->draw_indirect_buf, &h->copy_read_buf,
                         &h->copy_write_buf, &h->texture_buf};
    for (size_t i = 0; i < sizeof singles / sizeof singles[0]; ++i) {
        glCreateBuffers(1, singles[i]);
        /* Small on purpose: a library that uploads through the host's unpack buffer, or reads a
         * query into its query buffer, reads or writes out of range (a GL error). */
        glNamedBufferData(*singles[i], 64, NULL, GL_DYNAMIC_DRAW);
    }
    glCreateVertexArrays(1, &h->vao);
    glVertexArrayElementBuffer(h->vao, h->element_buf);
    glVertexArrayVertexBuffer(h->vao, 0, h->array_buf, 0, 12);
    glVertexArrayAttribFormat(h->vao, 0, 3, GL_FLOAT, GL_FALSE, 0);
    glVertexArrayAttribBinding(h->vao, 0, 0);
    glEnableVertexArrayAttrib(h->vao, 0);
    h->program = compile_program();
    h->uniform_loc = glGetUniformLocation(h->program, "u_host");
    glProgramUniform1f(h->program, h->uniform_loc, 3.5f);
    glCreateProgramPipelines(1, &h->pipeline);
    glCreateRenderbuffers(1, &h->rbo);
    glNamedRenderbufferStorage(h->rbo, GL_DEPTH_COMPONENT32F, 16, 16);
    GLuint colour = 0;
    glCreateTextures(GL_TEXTURE_2D, 1, &colour);
    glTextureStorage2D(colour, 1, GL_RGBA8, 16, 16);
    glCreateFramebuffers(1, &h->fbo_draw);
    glNamedFramebufferTexture(h->fbo_draw, GL_COLOR_ATTACHMENT0, colour, 0);
    glNamedFramebufferRenderbuffer(h->fbo_draw, GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER, h->rbo);
    glCreateFramebuffers(1, &h->fbo_read);
    glNamedFramebufferTexture(h->fbo_read, GL_COLOR_ATTACHMENT0, h->tex[0], 0);
    glNamedFramebufferReadBuffer(h->fbo_read, GL_COLOR_ATTACHMENT0);
    glCreateTransformFeedbacks(1, &h->tfo);
    glCreateQueries(GL_TIME_ELAPSED, 1, &h->time_query);
}

/* Bind all of the host's state (again before every call, so that one call's damage is not the
 * next call's "before"). The test's own uploads happen before this, with GL's defaults. */
static void bind_host_state(const host_objects *h)
{
    glUseProgram(h->program);
    glBindProgramPipeline(h->pipeline);
    glBindVertexArray(h->vao);
    for (int u = 0; u < NTEX; ++u) {
        glBindTextureUnit((GLuint)u, h->tex[u]);
        glBindSampler((GLuint)u, h->samplers[u]);
    }
    glActiveTexture(GL_TEXTURE0 + CUBE_UNIT);
    glBindTexture(GL_TEXTURE_CUBE_MAP, h->cube);
    glActiveTexture(GL_TEXTURE0 + ARRAY_UNIT);
    glBindTexture(GL_TEXTURE_2D_ARRAY, h->array2d);
    glActiveTexture(GL_TEXTURE0 + HOST_ACTIVE_UNIT);
    for (int i = 0, n = image_units(); i < n; ++i) {
        if (i % 2 == 0) glBindImageTexture((GLuint)i, h->img2d, i % 4 == 0 ? 0 : 1, GL_FALSE, 0, GL_READ_ONLY, GL_RGBA8);
        else glBindImageTexture((GLuint)i, h->img_array, 1, i % 3 == 0, i % 3, i % 4 == 1 ? GL_WRITE_ONLY : GL_READ_WRITE,
                                GL_R32F);
    }
    for (int i = 0; i < NBUF; ++i) {
        if (i % 2) {
            glBindBufferRange(GL_UNIFORM_BUFFER, (GLuint)i, h->ubo[i], (GLintptr)h->ubo_align * i, 64 + 16 * i);
            glBindBufferRange(GL_SHADER_STORAGE_BUFFER, (GLuint)i, h->ssbo[i], (GLintptr)h->ssbo_align * (i + 1), 32 * i);
        } else {
            glBindBufferBase(GL_UNIFORM_BUFFER, (GLuint)i, h->ubo[i]);
            glBindBufferBase(GL_SHADER_STORAGE_BUFFER, (GLuint)i, h->ssbo[i]);
        }
    }
    glBindBufferBase(GL_ATOMIC_COUNTER_BUFFER, 0, h->acbo);
    glBindBuffer(GL_UNIFORM_BUFFER, h->ubo_generic);
    glBindBuffer(GL_SHADER_STORAGE_BUFFER, h->ssbo_generic);
    glBindBuffer(GL_ARRAY_BUFFER, h->array_buf);
    glBindBuffer(GL_PIXEL_PACK_BUFFER, h->pack_buf);
    glBindBuffer(GL_PIXEL_UNPACK_BUFFER, h->unpack_buf);
    glBindBuffer(GL_QUERY_BUFFER, h->query_buf);
    glBindBuffer(GL_DISPATCH_INDIRECT_BUFFER, h->dispatch_buf);
    glBindBuffer(GL_DRAW_INDIRECT_BUFFER, h->draw_indirect_buf);
    glBindBuffer(GL_COPY_READ_BUFFER, h->copy_read_buf);
    glBindBuffer(GL_COPY_WRITE_BUFFER, h->copy_write_buf);
    glBindBuffer(GL_TEXTURE_BUFFER, h->texture_buf);
    glBindFramebuffer(GL_DRAW_FRAMEBUFFER, h->fbo_draw);
    glBindFramebuffer(GL_READ_FRAMEBUFFER, h->fbo_read);
    glBindRenderbuffer(GL_RENDERBUFFER, h->rbo);
    glBindTransformFeedback(GL_TRANSFORM_FEEDBACK, h->tfo);
    glViewport(3, 5, 41, 29);
    glScissor(1, 2, 30, 20);
    const GLenum on[] = {GL_DEPTH_TEST, GL_BLEND, GL_CULL_FACE, GL_SCISSOR_TEST, GL_FRAMEBUFFER_SRGB, GL_STENCIL_TEST,
                         GL_PRIMITIVE_RESTART, GL_PRIMITIVE_RESTART_FIXED_INDEX, GL_RASTERIZER_DISCARD,
                         GL_POLYGON_OFFSET_FILL, GL_DEPTH_CLAMP, GL_PROGRAM_POINT_SIZE, GL_TEXTURE_CUBE_MAP_SEAMLESS,
                         GL_SAMPLE_ALPHA_TO_COVERAGE, GL_CLIP_DISTANCE0, GL_DEBUG_OUTPUT_SYNCHRONOUS};
    const GLenum off[] = {GL_DITHER, GL_MULTISAMPLE};
    for (size_t i = 0; i < sizeof on / sizeof on[0]; ++i) glEnable(on[i]);
    for (size_t i = 0; i < sizeof off / sizeof off[0]; ++i) glDisable(off[i]);
    glDepthFunc(GL_GREATER);
    glClipControl(GL_LOWER_LEFT, GL_ZERO_TO_ONE);
    glDepthMask(GL_FALSE);
    glColorMask(GL_TRUE, GL_FALSE, GL_TRUE, GL_FALSE);
    glBlendFunc(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA);
    glBlendEquation(GL_FUNC_REVERSE_SUBTRACT);
    glCullFace(GL_FRONT);
    glFrontFace(GL_CW);
    glPolygonMode(GL_FRONT_AND_BACK, GL_LINE);
    glPolygonOffset(1.5f, 2.0f);
    glClearColor(0.1f, 0.2f, 0.3f, 0.4f);
    glClearDepth(0.0);
    glStencilFunc(GL_EQUAL, 3, 0x7f);
    glStencilOp(GL_KEEP, GL_INCR, GL_REPLACE);
    glPointSize(3.0f);
    glPrimitiveRestartIndex(0xfffe);
    glPixelStorei(GL_PACK_ALIGNMENT, 1);
    glPixelStorei(GL_UNPACK_ALIGNMENT, 2);
    glPixelStorei(GL_PACK_ROW_LENGTH, 13);
    glPixelStorei(GL_UNPACK_ROW_LENGTH, 7);
    glPixelStorei(GL_UNPACK_SKIP_ROWS, 1);
    glPixelStorei(GL_UNPACK_SKIP_PIXELS, 2);
    glPixelStorei(GL_PACK_SKIP_PIXELS, 3);
    glPixelStorei(GL_UNPACK_IMAGE_HEIGHT, 5);
    glPatchParameteri(GL_PATCH_VERTICES, 4);
    glProvokingVertex(GL_FIRST_VERTEX_CONVENTION);
}

/* GL's defaults for all of that (the clean context of the comparison at the end). */
static void unbind_host_state(void)
{
    glUseProgram(0);
    glBindProgramPipeline(0);
    glBindVertexArray(0);
    for (int u = 0; u < NTEX; ++u) {
        glBindTextureUnit((GLuint)u, 0);
        glBindSampler((GLuint)u, 0);
    }
    glActiveTexture(GL_TEXTURE0 + CUBE_UNIT);
    glBindTexture(GL_TEXTURE_CUBE_MAP, 0);
    glActiveTexture(GL_TEXTURE0 + ARRAY_UNIT);
    glBindTexture(GL_TEXTURE_2D_ARRAY, 0);
    glActiveTexture(GL_TEXTURE0);
    for (int i = 0, n = image_units(); i < n; ++i) glBindImageTexture((GLuint)i, 0, 0, GL_FALSE, 0, GL_READ_ONLY, GL_R8);
    for (int i = 0; i < NBUF; ++i) {
        glBindBufferBase(GL_UNIFORM_BUFFER, (GLuint)i, 0);
        glBindBufferBase(GL_SHADER_STORAGE_BUFFER, (GLuint)i, 0);
    }
    glBindBufferBase(GL_ATOMIC_COUNTER_BUFFER, 0, 0);
    const GLenum targets[] = {GL_UNIFORM_BUFFER, GL_SHADER_STORAGE_BUFFER, GL_ATOMIC_COUNTER_BUFFER, GL_ARRAY_BUFFER,
                              GL_PIXEL_PACK_BUFFER, GL_PIXEL_UNPACK_BUFFER, GL_QUERY_BUFFER, GL_DISPATCH_INDIRECT_BUFFER,
                              GL_DRAW_INDIRECT_BUFFER, GL_COPY_READ_BUFFER, GL_COPY_WRITE_BUFFER, GL_TEXTURE_BUFFER};
    for (size_t i = 0; i < sizeof targets / sizeof targets[0]; ++i) glBindBuffer(targets[i], 0);
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    glBindRenderbuffer(GL_RENDERBUFFER, 0);
    glBindTransformFeedback(GL_TRANSFORM_FEEDBACK, 0);
    const GLenum off[] = {GL_DEPTH_TEST, GL_BLEND, GL_CULL_FACE, GL_SCISSOR_TEST, GL_FRAMEBUFFER_SRGB, GL_STENCIL_TEST,
                          GL_PRIMITIVE_RESTART, GL_PRIMITIVE_RESTART_FIXED_INDEX, GL_RASTERIZER_DISCARD,
                          GL_POLYGON_OFFSET_FILL, GL_DEPTH_CLAMP, GL_PROGRAM_POINT_SIZE, GL_TEXTURE_CUBE_MAP_SEAMLESS,
                          GL_SAMPLE_ALPHA_TO_COVERAGE, GL_CLIP_DISTANCE0};
    for (size_t i = 0; i < sizeof off / sizeof off[0]; ++i) glDisable(off[i]);
    glEnable(GL_DITHER);
    glEnable(GL_MULTISAMPLE);
    glDepthFunc(GL_LESS);
    glClipControl(GL_LOWER_LEFT, GL_NEGATIVE_ONE_TO_ONE);
    glDepthMask(GL_TRUE);
    glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
    glBlendFunc(GL_ONE, GL_ZERO);
    glBlendEquation(GL_FUNC_ADD);
    glCullFace(GL_BACK);
    glFrontFace(GL_CCW);
    glPolygonMode(GL_FRONT_AND_BACK, GL_FILL);
    glPixelStorei(GL_PACK_ALIGNMENT, 4);
    glPixelStorei(GL_UNPACK_ALIGNMENT, 4);
    glPixelStorei(GL_PACK_ROW_LENGTH, 0);
    glPixelStorei(GL_UNPACK_ROW_LENGTH, 0);
    glPixelStorei(GL_UNPACK_SKIP_ROWS, 0);
    glPixelStorei(GL_UNPACK_SKIP_PIXELS, 0);
    glPixelStorei(GL_PACK_SKIP_PIXELS, 0);
    glPixelStorei(GL_UNPACK_IMAGE_HEIGHT, 0);
}

/* ---- reading the state ---------------------------------------------------------------------------- */
typedef struct piece {
    const char *group; /* a row of the table */
    char name[72];
    int64_t v[4];
    int n;
} piece;

typedef struct snapshot {
    piece p[MAX_PIECES];
    int count;
} snapshot;

static piece *add_piece(snapshot *s, const char *group, int n, const char *fmt, ...)
{
    if (s->count >= MAX_PIECES) {
        CHECK(false, "more than %d pieces of state", MAX_PIECES);
        s->count = MAX_PIECES - 1;
    }
    piece *p = &s->p[s->count++];
    memset(p, 0, sizeof *p);
    p->group = group;
    p->n = n;
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(p->name, sizeof p->name, fmt, ap);
    va_end(ap);
    return p;
}

#define NAMED(e) e, #e

static void get_ints(snapshot *s, const char *group, GLenum pname, const char *name, int n)
{
    GLint v[4] = {0};
    glGetIntegerv(pname, v);
    piece *p = add_piece(s, group, n, "%s", name);
    for (int i = 0; i < n; ++i) p->v[i] = v[i];
}

static void get_floats(snapshot *s, const char *group, GLenum pname, const char *name, int n)
{
    GLfloat v[4] = {0};
    glGetFloatv(pname, v);
    piece *p = add_piece(s, group, n, "%s", name);
    for (int i = 0; i < n; ++i) {
        uint32_t bits;
        memcpy(&bits, &v[i], sizeof bits);
        p->v[i] = bits;
    }
}

static void get_enabled(snapshot *s, GLenum cap, const char *name)
{
    add_piece(s, "enables", 1, "glIsEnabled(%s)", name)->v[0] = glIsEnabled(cap);
}

static void get_indexed(snapshot *s, const char *group, GLenum pname, const char *name, GLuint index)
{
    GLint64 v = 0;
    glGetInteger64i_v(pname, index, &v);
    add_piece(s, group, 1, "%s[%u]", name, index)->v[0] = v;
}

static void get_tex_params(snapshot *s, GLuint tex, const char *what)
{
    static const struct { GLenum e; const char *n; } params[] = {
        {NAMED(GL_TEXTURE_MIN_FILTER)}, {NAMED(GL_TEXTURE_MAG_FILTER)}, {NAMED(GL_TEXTURE_WRAP_S)},
        {NAMED(GL_TEXTURE_WRAP_T)}, {NAMED(GL_TEXTURE_COMPARE_MODE)}, {NAMED(GL_TEXTURE_COMPARE_FUNC)},
        {NAMED(GL_DEPTH_STENCIL_TEXTURE_MODE)}, {NAMED(GL_TEXTURE_BASE_LEVEL)}, {NAMED(GL_TEXTURE_MAX_LEVEL)},
        {NAMED(GL_TEXTURE_SWIZZLE_R)}, {NAMED(GL_TEXTURE_SWIZZLE_A)}};
    for (size_t i = 0; i < sizeof params / sizeof params[0]; ++i) {
        GLint v = 0;
        glGetTextureParameteriv(tex, params[i].e, &v);
        add_piece(s, "the host's input/output textures' parameters", 1, "%s texture %u: %s", what, tex, params[i].n)->v[0] = v;
    }
}

/* Everything the test watches, without changing any of it (the active texture unit is put back). */
static void take_snapshot(snapshot *s, const host_objects *h)
{
    s->count = 0;
    get_ints(s, "program, pipeline, VAO", NAMED(GL_CURRENT_PROGRAM), 1);
    get_ints(s, "program, pipeline, VAO", NAMED(GL_PROGRAM_PIPELINE_BINDING), 1);
    get_ints(s, "program, pipeline, VAO", NAMED(GL_VERTEX_ARRAY_BINDING), 1);
    get_ints(s, "program, pipeline, VAO", NAMED(GL_ELEMENT_ARRAY_BUFFER_BINDING), 1); /* the VAO's */
    GLfloat u = 0.0f;
    glGetUniformfv(h->program, h->uniform_loc, &u);
    add_piece(s, "program, pipeline, VAO", 1, "the host program's uniform u_host")->v[0] = (int64_t)(u * 1000.0f);
    get_ints(s, "active texture unit", NAMED(GL_ACTIVE_TEXTURE), 1);
    GLint active = 0;
    glGetIntegerv(GL_ACTIVE_TEXTURE, &active);
    for (int unit = 0; unit < NTEX; ++unit) {
        glActiveTexture(GL_TEXTURE0 + (GLenum)unit);
        GLint v[5] = {0};
        glGetIntegerv(GL_TEXTURE_BINDING_2D, &v[0]);
        glGetIntegerv(GL_SAMPLER_BINDING, &v[1]);
        glGetIntegerv(GL_TEXTURE_BINDING_CUBE_MAP, &v[2]);
        glGetIntegerv(GL_TEXTURE_BINDING_2D_ARRAY, &v[3]);
        glGetIntegerv(GL_TEXTURE_BINDING_2D_MULTISAMPLE, &v[4]);
        add_piece(s, "texture units: GL_TEXTURE_2D binding", 1, "unit %d GL_TEXTURE_BINDING_2D", unit)->v[0] = v[0];
        add_piece(s, "texture units: sampler binding", 1, "unit %d GL_SAMPLER_BINDING", unit)->v[0] = v[1];
        add_piece(s, "texture units: cube, 2D array, 2D MS bindings", 3,
                  "unit %d GL_TEXTURE_BINDING_CUBE_MAP/_2D_ARRAY/_2D_MULTISAMPLE", unit);
        s->p[s->count - 1].v[0] = v[2], s->p[s->count - 1].v[1] = v[3], s->p[s->count - 1].v[2] = v[4];
    }
    glActiveTexture((GLenum)active);
    for (GLuint i = 0, n = (GLuint)image_units(); i < n; ++i) {
        static const struct { GLenum e; const char *n; } img[] = {
            {NAMED(GL_IMAGE_BINDING_NAME)}, {NAMED(GL_IMAGE_BINDING_LEVEL)}, {NAMED(GL_IMAGE_BINDING_LAYERED)},
            {NAMED(GL_IMAGE_BINDING_LAYER)}, {NAMED(GL_IMAGE_BINDING_ACCESS)}, {NAMED(GL_IMAGE_BINDING_FORMAT)}};
        for (size_t k = 0; k < sizeof img / sizeof img[0]; ++k) get_indexed(s, "image units: name, level, layered, layer, access, format", img[k].e, img[k].n, i);
    }
    for (GLuint i = 0; i < NBUF; ++i) {
        get_indexed(s, "indexed uniform buffers (binding, start, size)", NAMED(GL_UNIFORM_BUFFER_BINDING), i);
        get_indexed(s, "indexed uniform buffers (binding, start, size)", NAMED(GL_UNIFORM_BUFFER_START), i);
        get_indexed(s, "indexed uniform buffers (binding, start, size)", NAMED(GL_UNIFORM_BUFFER_SIZE), i);
        get_indexed(s, "indexed storage buffers (binding, start, size)", NAMED(GL_SHADER_STORAGE_BUFFER_BINDING), i);
        get_indexed(s, "indexed storage buffers (binding, start, size)", NAMED(GL_SHADER_STORAGE_BUFFER_START), i);
        get_indexed(s, "indexed storage buffers (binding, start, size)", NAMED(GL_SHADER_STORAGE_BUFFER_SIZE), i);
    }
    get_indexed(s, "indexed atomic counter buffer 0", NAMED(GL_ATOMIC_COUNTER_BUFFER_BINDING), 0);
    get_ints(s, "generic uniform/storage buffer bindings", NAMED(GL_UNIFORM_BUFFER_BINDING), 1);
    get_ints(s, "generic uniform/storage buffer bindings", NAMED(GL_SHADER_STORAGE_BUFFER_BINDING), 1);
    get_ints(s, "generic uniform/storage buffer bindings", NAMED(GL_ATOMIC_COUNTER_BUFFER_BINDING), 1);
    get_ints(s, "array buffer", NAMED(GL_ARRAY_BUFFER_BINDING), 1);
    get_ints(s, "pixel pack/unpack buffers", NAMED(GL_PIXEL_PACK_BUFFER_BINDING), 1);
    get_ints(s, "pixel pack/unpack buffers", NAMED(GL_PIXEL_UNPACK_BUFFER_BINDING), 1);
    get_ints(s, "other buffer targets", NAMED(GL_QUERY_BUFFER_BINDING), 1);
    get_ints(s, "other buffer targets", NAMED(GL_DISPATCH_INDIRECT_BUFFER_BINDING), 1);
    get_ints(s, "other buffer targets", NAMED(GL_DRAW_INDIRECT_BUFFER_BINDING), 1);
    get_ints(s, "other buffer targets", NAMED(GL_COPY_READ_BUFFER_BINDING), 1);
    get_ints(s, "other buffer targets", NAMED(GL_COPY_WRITE_BUFFER_BINDING), 1);
    get_ints(s, "other buffer targets", NAMED(GL_TEXTURE_BUFFER_BINDING), 1);
    get_ints(s, "framebuffers, renderbuffer", NAMED(GL_DRAW_FRAMEBUFFER_BINDING), 1);
    get_ints(s, "framebuffers, renderbuffer", NAMED(GL_READ_FRAMEBUFFER_BINDING), 1);
    get_ints(s, "framebuffers, renderbuffer", NAMED(GL_RENDERBUFFER_BINDING), 1);
    get_ints(s, "framebuffers, renderbuffer", NAMED(GL_DRAW_BUFFER0), 1);
    get_ints(s, "framebuffers, renderbuffer", NAMED(GL_READ_BUFFER), 1);
    get_ints(s, "viewport, scissor box", NAMED(GL_VIEWPORT), 4);
    get_ints(s, "viewport, scissor box", NAMED(GL_SCISSOR_BOX), 4);
    static const struct { GLenum e; const char *n; } caps[] = {
        {NAMED(GL_DEPTH_TEST)}, {NAMED(GL_BLEND)}, {NAMED(GL_CULL_FACE)}, {NAMED(GL_SCISSOR_TEST)},
        {NAMED(GL_FRAMEBUFFER_SRGB)}, {NAMED(GL_STENCIL_TEST)}, {NAMED(GL_PRIMITIVE_RESTART)},
        {NAMED(GL_PRIMITIVE_RESTART_FIXED_INDEX)}, {NAMED(GL_RASTERIZER_DISCARD)}, {NAMED(GL_POLYGON_OFFSET_FILL)},
        {NAMED(GL_DEPTH_CLAMP)}, {NAMED(GL_PROGRAM_POINT_SIZE)}, {NAMED(GL_TEXTURE_CUBE_MAP_SEAMLESS)},
        {NAMED(GL_SAMPLE_ALPHA_TO_COVERAGE)}, {NAMED(GL_CLIP_DISTANCE0)}, {NAMED(GL_DITHER)}, {NAMED(GL_MULTISAMPLE)},
        {NAMED(GL_DEBUG_OUTPUT)}, {NAMED(GL_DEBUG_OUTPUT_SYNCHRONOUS)}};
    for (size_t i = 0; i < sizeof caps / sizeof caps[0]; ++i) get_enabled(s, caps[i].e, caps[i].n);
    get_ints(s, "depth, clip control", NAMED(GL_DEPTH_FUNC), 1);
    get_ints(s, "depth, clip control", NAMED(GL_CLIP_ORIGIN), 1);
    get_ints(s, "depth, clip control", NAMED(GL_CLIP_DEPTH_MODE), 1);
    get_ints(s, "depth, clip control", NAMED(GL_DEPTH_WRITEMASK), 1);
    get_floats(s, "depth, clip control", NAMED(GL_DEPTH_RANGE), 2);
    get_floats(s, "depth, clip control", NAMED(GL_DEPTH_CLEAR_VALUE), 1);
    get_ints(s, "raster state (masks, blend, faces, polygon, stencil)", NAMED(GL_COLOR_WRITEMASK), 4);
    get_ints(s, "raster state (masks, blend, faces, polygon, stencil)", NAMED(GL_BLEND_SRC_RGB), 1);
    get_ints(s, "raster state (masks, blend, faces, polygon, stencil)", NAMED(GL_BLEND_DST_ALPHA), 1);
    get_ints(s, "raster state (masks, blend, faces, polygon, stencil)", NAMED(GL_BLEND_EQUATION_RGB), 1);
    get_ints(s, "raster state (masks, blend, faces, polygon, stencil)", NAMED(GL_CULL_FACE_MODE), 1);
    get_ints(s, "raster state (masks, blend, faces, polygon, stencil)", NAMED(GL_FRONT_FACE), 1);
    get_ints(s, "raster state (masks, blend, faces, polygon, stencil)", NAMED(GL_POLYGON_MODE), 1);
    get_floats(s, "raster state (masks, blend, faces, polygon, stencil)", NAMED(GL_POLYGON_OFFSET_FACTOR), 1);
    get_floats(s, "raster state (masks, blend, faces, polygon, stencil)", NAMED(GL_COLOR_CLEAR_VALUE), 4);
    get_ints(s, "raster state (masks, blend, faces, polygon, stencil)", NAMED(GL_STENCIL_FUNC), 1);
    get_ints(s, "raster state (masks, blend, faces, polygon, stencil)", NAMED(GL_STENCIL_REF), 1);
    get_ints(s, "raster state (masks, blend, faces, polygon, stencil)", NAMED(GL_STENCIL_PASS_DEPTH_PASS), 1);
    get_floats(s, "raster state (masks, blend, faces, polygon, stencil)", NAMED(GL_POINT_SIZE), 1);
    get_ints(s, "raster state (masks, blend, faces, polygon, stencil)", NAMED(GL_PRIMITIVE_RESTART_INDEX), 1);
    get_ints(s, "raster state (masks, blend, faces, polygon, stencil)", NAMED(GL_PATCH_VERTICES), 1);
    get_ints(s, "raster state (masks, blend, faces, polygon, stencil)", NAMED(GL_PROVOKING_VERTEX), 1);
    static const struct { GLenum e; const char *n; } store[] = {
        {NAMED(GL_PACK_ALIGNMENT)}, {NAMED(GL_UNPACK_ALIGNMENT)}, {NAMED(GL_PACK_ROW_LENGTH)},
        {NAMED(GL_UNPACK_ROW_LENGTH)}, {NAMED(GL_UNPACK_SKIP_ROWS)}, {NAMED(GL_UNPACK_SKIP_PIXELS)},
        {NAMED(GL_PACK_SKIP_PIXELS)}, {NAMED(GL_UNPACK_IMAGE_HEIGHT)}};
    for (size_t i = 0; i < sizeof store / sizeof store[0]; ++i) get_ints(s, "pixel store", store[i].e, store[i].n, 1);
    get_ints(s, "transform feedback, queries", NAMED(GL_TRANSFORM_FEEDBACK_BINDING), 1);
    static const struct { GLenum e; const char *n; } queries[] = {
        {NAMED(GL_TIME_ELAPSED)}, {NAMED(GL_SAMPLES_PASSED)}, {NAMED(GL_ANY_SAMPLES_PASSED)},
        {NAMED(GL_PRIMITIVES_GENERATED)}};
    for (size_t i = 0; i < sizeof queries / sizeof queries[0]; ++i) {
        GLint q = 0;
        glGetQueryiv(queries[i].e, GL_CURRENT_QUERY, &q);
        add_piece(s, "transform feedback, queries", 1, "glGetQueryiv(%s, GL_CURRENT_QUERY)", queries[i].n)->v[0] = q;
    }
    get_ints(s, "KHR_debug: group depth, callback", NAMED(GL_DEBUG_GROUP_STACK_DEPTH), 1);
    void *fn = NULL, *user = NULL;
    glGetPointerv(GL_DEBUG_CALLBACK_FUNCTION, &fn);
    glGetPointerv(GL_DEBUG_CALLBACK_USER_PARAM, &user);
    add_piece(s, "KHR_debug: group depth, callback", 1, "GL_DEBUG_CALLBACK_FUNCTION")->v[0] = (int64_t)(intptr_t)fn;
    add_piece(s, "KHR_debug: group depth, callback", 1, "GL_DEBUG_CALLBACK_USER_PARAM")->v[0] = (int64_t)(intptr_t)user;
    for (int i = 0; i < h->watched_count; ++i) get_tex_params(s, h->watched[i], "host");
}

/* ---- the calls, their families and the table -------------------------------------------------- */
enum family {
    F_MAKE, F_AO_LIN, F_AO_HW, F_GI_LIN, F_GI_HW, F_FILTER, F_VARIANT, F_PREPARE, F_OLD_AO, F_OLD_FILTERED,
    F_DIVISOR, F_TEMPORAL, F_GUARD, F_REFUSED, F_COUNT
};
static const char *const family_name[F_COUNT] = {
    "make", "ao/lin", "ao/hw", "gi/lin", "gi/hw", "filter", "variant", "prepare", "old_ao", "old_filt",
    "divisor", "temporal", "guard", "refused"};
static const char *const family_help[F_COUNT] = {
    "ob_make_context(use_current) + ob_make_renderer (informational: not a host-path call)",
    "ob_host_ao, every AO method, R32F linear depth + RGBA16F view normals, R16F AO",
    "ob_host_ao, every AO method, reversed-Z infinite D32F [0,1] + RG16F octahedral world normals",
    "ob_host_ao, indirect-light methods + radiance RGBA16F + albedo RGBA8, RGBA16F AO + indirect, linear depth",
    "the same with the reversed-Z D32F depth and octahedral world normals",
    "ob_host_ao, vbao + every filter (crease in each of its programs)",
    "ob_host_ao, variants with passes of their own: deinterleave, depth MIPs, bent normals, 2 layers, packed",
    "ob_host_prepare for several settings",
    "ob_compute_ao (the old entry point), R32F depth + RGBA16F normals -> R32F",
    "ob_compute_ao_filtered (the old entry point)",
    "ob_host_ao at ao_divisor 2 and 4",
    "ob_host_ao, temporal accumulation over 3 frames (moving camera, jitter, a motion texture)",
    "ob_host_ao with a guard band (inputs at ob_host_input_size, output cropped)",
    "calls refused with OB_ERR_INVALID_ARGUMENT (state restored on failure too)"};

typedef enum call_kind { CALL_HOST_AO, CALL_PREPARE, CALL_COMPUTE_AO, CALL_COMPUTE_AO_FILTERED, CALL_MAKE } call_kind;

typedef struct call {
    call_kind kind;
    ob_renderer *r;
    const ob_settings *settings;
    const ob_host_frame *frame;
    const ob_host_outputs *outputs;
    GLuint depth, normal, out; /* the old entry points */
    const float *proj;
    ob_error expect;
} call;

static struct {
    host_objects host;
    snapshot before, after;
    int calls[F_COUNT];
    /* per family and table row: 0 not read, 1 all equal, 2 a change */
    const char *rows[64];
    int row_count;
    unsigned char cell[64][F_COUNT];
    int pending_ok[F_COUNT], pending_bad[F_COUNT], clean_ok[F_COUNT], clean_bad[F_COUNT], own_errors[F_COUNT], group_ok[F_COUNT], group_bad[F_COUNT];
    int rc_bad[F_COUNT];
    bool debug_context;
    ob_context *ctx;
    int pieces;
} T;

static int row_of(const char *group)
{
    for (int i = 0; i < T.row_count; ++i)
        if (!strcmp(T.rows[i], group)) return i;
    if (T.row_count == 64) return 63;
    T.rows[T.row_count] = group;
    return T.row_count++;
}

static GLenum raise_pending_error(int which)
{
    switch (which % 4) {
    case 0: glEnable(0xFFFF); return GL_INVALID_ENUM;
    case 1: glBindTexture(GL_TEXTURE_2D, T.host.cube); return GL_INVALID_OPERATION; /* a cube map on the 2D target */
    case 2: glViewport(0, 0, -1, -1); return GL_INVALID_VALUE;
    default: return GL_NO_ERROR;
    }
}

static ob_error do_call(const call *c)
{
    switch (c->kind) {
    case CALL_HOST_AO: return ob_host_ao(c->r, c->frame, c->settings, c->outputs);
    case CALL_PREPARE: return ob_host_prepare(c->r, c->settings);
    case CALL_COMPUTE_AO: return ob_compute_ao(c->r, c->depth, c->normal, c->proj, c->settings, c->out);
    case CALL_COMPUTE_AO_FILTERED: return ob_compute_ao_filtered(c->r, c->depth, c->normal, c->proj, c->settings, c->out);
    case CALL_MAKE: break;
    }
    return OB_OK;
}

static const char *error_name(GLenum e)
{
    switch (e) {
    case GL_NO_ERROR: return "GL_NO_ERROR";
    case GL_INVALID_ENUM: return "GL_INVALID_ENUM";
    case GL_INVALID_VALUE: return "GL_INVALID_VALUE";
    case GL_INVALID_OPERATION: return "GL_INVALID_OPERATION";
    case GL_INVALID_FRAMEBUFFER_OPERATION: return "GL_INVALID_FRAMEBUFFER_OPERATION";
    case GL_OUT_OF_MEMORY: return "GL_OUT_OF_MEMORY";
    default: return "another error";
    }
}

static void print_values(const piece *p, char *out, size_t size)
{
    size_t used = 0;
    for (int i = 0; i < p->n && used < size; ++i)
        used += (size_t)snprintf(out + used, size - used, "%s%lld", i ? "," : "", (long long)p->v[i]);
}

/* Compare, count into the table; a changed piece is a failure naming the piece and the call
 * (informational families print it without failing). */
static void compare_snapshots(int family, const char *label, bool informational)
{
    CHECK(T.before.count == T.after.count, "%s: the snapshots read %d and %d pieces", label, T.before.count,
          T.after.count);
    T.pieces = T.before.count;
    for (int i = 0; i < T.before.count && i < T.after.count; ++i) {
        const piece *b = &T.before.p[i], *a = &T.after.p[i];
        int row = row_of(b->group);
        bool same = !memcmp(b->v, a->v, sizeof b->v);
        if (T.cell[row][family] == 0) T.cell[row][family] = 1;
        if (same) continue;
        T.cell[row][family] = 2;
        char bv[96], av[96];
        print_values(b, bv, sizeof bv);
        print_values(a, av, sizeof av);
        if (informational) {
            printf("  note: %s changed %s: before %s, after %s\n", label, b->name, bv, av);
        } else {
            CHECK(false, "%s changed %s: before %s, after %s", label, b->name, bv, av);
        }
    }
}

/* One library call as the host makes it: its state bound, a snapshot, a pending error (or none),
 * the call, the host's glGetError twice, a second snapshot. */
static ob_error run_call(int family, const char *label, const call *c)
{
    bind_host_state(&T.host);
    glBeginQuery(GL_TIME_ELAPSED, T.host.time_query);
    take_snapshot(&T.before, &T.host);
    GLenum clean = glGetError();
    CHECK(clean == GL_NO_ERROR, "before %s: the test's own setup left %s", label, error_name(clean));
    GLenum pending = raise_pending_error(T.calls[family] + 3); /* each family: none, then ENUM, OPERATION, VALUE */
    memset(&dbg, 0, sizeof dbg);
    ob_clear_error();
    ob_error rc = do_call(c);
    const char *msg = "";
    if (rc != OB_OK) ob_get_error(&msg);
    GLenum first = glGetError(), second = glGetError();
    take_snapshot(&T.after, &T.host);
    glEndQuery(GL_TIME_ELAPSED);
    ++T.calls[family];
    bool informational = c->kind == CALL_MAKE;
    compare_snapshots(family, label, informational);
    if (c->kind != CALL_MAKE) {
        bool rc_ok = c->expect == OB_OK ? rc == OB_OK : rc == c->expect;
        if (!rc_ok) ++T.rc_bad[family];
        CHECK(rc_ok, "%s returned %s (%s), expected %s", label, ob_error_name(rc), msg, ob_error_name(c->expect));
    }
    bool kept = first == pending && second == GL_NO_ERROR;
    if (pending != GL_NO_ERROR) ++(kept ? T.pending_ok : T.pending_bad)[family];
    else ++(kept ? T.clean_ok : T.clean_bad)[family];
    if (!informational)
        CHECK(kept, "%s: the host left %s pending; after the call glGetError reads %s, then %s (want %s, then GL_NO_ERROR)",
              label, error_name(pending), error_name(first), error_name(second), error_name(pending));
    if (dbg.errors) ++T.own_errors[family];
    if (!informational)
        CHECK(dbg.errors == 0, "%s raised %d GL error(s) of its own, the first: %s", label, dbg.errors, dbg.first_error);
    if (T.debug_context && c->kind != CALL_MAKE && rc == OB_OK) {
        bool grouped = dbg.pushes >= 1 && dbg.pushes == dbg.pops;
        if (grouped) ++T.group_ok[family];
        else ++T.group_bad[family];
        CHECK(grouped, "%s in a debug context: KHR_debug group \"obscura\" pushed %d, popped %d times", label, dbg.pushes,
              dbg.pops);
    }
    return rc;
}

static void print_table(void)
{
    printf("\nGL state read before and after every call (%d pieces; '=' all equal after every call of the family, "
           "'X' changed, '.' not run):\n",
           T.pieces);
    printf("%-58s", "piece of state");
    for (int f = 0; f < F_COUNT; ++f) printf(" %8s", family_name[f]);
    printf("\n");
    for (int r = 0; r < T.row_count; ++r) {
        printf("%-58.58s", T.rows[r]);
        for (int f = 0; f < F_COUNT; ++f) printf(" %8s", T.cell[r][f] == 0 ? "." : T.cell[r][f] == 1 ? "=" : "X");
        printf("\n");
    }
    printf("%-58s", "host's pending GL error read back by the host, then none");
    for (int f = 0; f < F_COUNT; ++f)
        printf(" %8s", !(T.pending_ok[f] + T.pending_bad[f]) ? "." : T.pending_bad[f] ? "X" : "=");
    printf("\n%-58s", "none pending: glGetError reads GL_NO_ERROR after the call");
    for (int f = 0; f < F_COUNT; ++f) printf(" %8s", !(T.clean_ok[f] + T.clean_bad[f]) ? "." : T.clean_bad[f] ? "X" : "=");
    printf("\n%-58s", "GL errors of the library's own (debug callback)");
    for (int f = 0; f < F_COUNT; ++f) printf(" %8s", !T.calls[f] ? "." : T.own_errors[f] ? "X" : "=");
    if (T.debug_context) {
        printf("\n%-58s", "KHR_debug group \"obscura\" pushed and popped");
        for (int f = 0; f < F_COUNT; ++f) printf(" %8s", !(T.group_ok[f] + T.group_bad[f]) ? "." : T.group_bad[f] ? "X" : "=");
    }
    printf("\n%-58s", "return code as expected");
    for (int f = 0; f < F_COUNT; ++f) printf(" %8s", !T.calls[f] ? "." : T.rc_bad[f] ? "X" : "=");
    printf("\n%-58s", "calls");
    for (int f = 0; f < F_COUNT; ++f) printf(" %8d", T.calls[f]);
    printf("\n\ncall families:\n");
    for (int f = 0; f < F_COUNT; ++f) printf("  %-9s %s\n", family_name[f], family_help[f]);
}

/* ---- the host's inputs ---------------------------------------------------------------------------- */
typedef struct inputs {
    host_view v;
    int w, h;
    GLuint linear, normal_view, hw_depth, normal_oct_world, radiance, albedo, second, motion;
    float proj_hw[16];
} inputs;

static const float cam_eye[3] = {0.6f, 2.3f, 4.6f}, cam_target[3] = {0.3f, 0.6f, -1.0f};
static const float fov_y = 0.87266f; /* 50 degrees */

/* The host's G-buffer of w x h: a projection (possibly widened for a guard band and jittered) for
 * the linear depth, and its reversed-Z infinite twin for the D32F depth. */
static void make_inputs(inputs *in, int w, int h, const float proj[16], const float eye[3])
{
    unbind_host_state(); /* the test's own uploads: GL's default unpack state */
    memset(in, 0, sizeof *in);
    in->w = w, in->h = h;
    make_view(&in->v, w, h, proj, eye, cam_target);
    memcpy(in->proj_hw, proj, sizeof in->proj_hw);
    in->proj_hw[10] = 0.0f, in->proj_hw[14] = 0.1f; /* reversed-Z, infinite far, near 0.1, [0, 1] */
    size_t n = (size_t)w * (size_t)h;
    float *depth = malloc(n * sizeof(float)), *vn = malloc(4 * n * sizeof(float)), *wn = malloc(4 * n * sizeof(float));
    float *hw = malloc(n * sizeof(float)), *oct = malloc(2 * n * sizeof(float)), *rad = malloc(4 * n * sizeof(float));
    float *alb = malloc(4 * n * sizeof(float)), *second = malloc(n * sizeof(float));
    raycast(&in->v, depth, vn, wn);
    for (size_t i = 0; i < n; ++i) {
        hw[i] = window_depth(in->proj_hw, depth[i], true, 0.0f);
        oct_encode(&wn[4 * i], &oct[2 * i]);
        float lit = depth[i] > 0.0f ? fmaxf(0.0f, 0.3f * wn[4 * i] + 0.9f * wn[4 * i + 1] + 0.3f * wn[4 * i + 2]) : 0.0f;
        for (int k = 0; k < 4; ++k) rad[4 * i + k] = k < 3 ? lit * (0.6f + 0.2f * (float)k) : 1.0f;
        for (int k = 0; k < 4; ++k) alb[4 * i + k] = k == 3 ? 1.0f : 0.5f + 0.1f * (float)k;
        second[i] = depth[i] > 0.0f ? depth[i] + 0.5f : 0.0f;
    }
    in->linear = make_tex(GL_R32F, w, h);
    glTextureSubImage2D(in->linear, 0, 0, 0, w, h, GL_RED, GL_FLOAT, depth);
    in->second = make_tex(GL_R32F, w, h);
    glTextureSubImage2D(in->second, 0, 0, 0, w, h, GL_RED, GL_FLOAT, second);
    in->normal_view = make_tex(GL_RGBA16F, w, h);
    glTextureSubImage2D(in->normal_view, 0, 0, 0, w, h, GL_RGBA, GL_FLOAT, vn);
    in->hw_depth = make_tex(GL_DEPTH_COMPONENT32F, w, h);
    glTextureSubImage2D(in->hw_depth, 0, 0, 0, w, h, GL_DEPTH_COMPONENT, GL_FLOAT, hw);
    in->normal_oct_world = make_tex(GL_RG16F, w, h);
    glTextureSubImage2D(in->normal_oct_world, 0, 0, 0, w, h, GL_RG, GL_FLOAT, oct);
    in->radiance = make_tex(GL_RGBA16F, w, h);
    glTextureSubImage2D(in->radiance, 0, 0, 0, w, h, GL_RGBA, GL_FLOAT, rad);
    in->albedo = make_tex(GL_RGBA8, w, h);
    glTextureSubImage2D(in->albedo, 0, 0, 0, w, h, GL_RGBA, GL_FLOAT, alb);
    in->motion = make_tex(GL_RG16F, w, h);
    const float zero[2] = {0.0f, 0.0f};
    glClearTexImage(in->motion, 0, GL_RG, GL_FLOAT, zero);
    free(depth), free(vn), free(wn), free(hw), free(oct), free(rad), free(alb), free(second);
    GLenum e = glGetError();
    CHECK(e == GL_NO_ERROR, "the host's G-buffer uploads: %s", error_name(e));
}

static ob_host_frame linear_frame(const inputs *in)
{
    ob_host_frame f = {.depth = in->linear, .normal = in->normal_view, .normal_space = OB_NORMALS_VIEW};
    memcpy(f.projection, in->v.proj, sizeof f.projection);
    memcpy(f.view, in->v.view, sizeof f.view);
    return f;
}

static ob_host_frame hardware_frame(const inputs *in)
{
    ob_host_frame f = {.depth = in->hw_depth, .normal = in->normal_oct_world, .normal_space = OB_NORMALS_WORLD,
                       .depth_zero_to_one = true};
    memcpy(f.projection, in->proj_hw, sizeof f.projection);
    memcpy(f.view, in->v.view, sizeof f.view);
    return f;
}

/* Settings through the typed path, else (a method without a radius) the string path. */
static bool host_settings(ob_settings *s, const char *method, const char *filter)
{
    ob_host_settings hs = {.method = method, .radius = 1.0f, .filter = filter};
    if (ob_settings_from_host(s, &hs) == OB_OK) return true;
    ob_clear_error();
    return ob_settings_init(s, method) == OB_OK && ob_settings_set_filter(s, filter ? filter : "crease") == OB_OK;
}

static bool set(ob_settings *s, const char *assignment)
{
    ob_error e = ob_settings_set(s, assignment);
    const char *msg = "";
    if (e != OB_OK) ob_get_error(&msg);
    CHECK(e == OB_OK, "ob_settings_set(%s): %s", assignment, msg);
    return e == OB_OK;
}

/* ---- the test ------------------------------------------------------------------------------------- */
typedef struct outputs_set {
    GLuint r16f, rgba16f, indirect, bent, r32f;
} outputs_set;

/* Read back with GL's defaults (the host's pack buffer and pixel store unbound first). */
static void read_r(GLuint tex, float *dst, int w, int h)
{
    unbind_host_state();
    glGetTextureImage(tex, 0, GL_RED, GL_FLOAT, (GLsizei)((size_t)w * (size_t)h * sizeof(float)), dst);
}

static void run_all(ob_renderer *r)
{
    float proj[16];
    perspective(proj, fov_y, (float)W / (float)H, 0.1, 100.0, false, false);
    static inputs in;
    make_inputs(&in, W, H, proj, cam_eye);
    outputs_set o = {make_tex(GL_R16F, W, H), make_tex(GL_RGBA16F, W, H), make_tex(GL_RGBA16F, W, H),
                     make_tex(GL_RGBA16F, W, H), make_tex(GL_R32F, W, H)};
    T.host.watched[T.host.watched_count++] = in.linear;
    T.host.watched[T.host.watched_count++] = in.hw_depth;
    T.host.watched[T.host.watched_count++] = in.normal_oct_world;
    T.host.watched[T.host.watched_count++] = o.r16f;
    /* The host's own texture parameters on what it hands over (a library must read through its own
     * samplers, not by changing these). */
    glTextureParameteri(in.linear, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
    glTextureParameteri(in.linear, GL_TEXTURE_WRAP_S, GL_MIRRORED_REPEAT);
    glTextureParameteri(in.hw_depth, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    glTextureParameteri(in.normal_oct_world, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
    glTextureParameteri(o.r16f, GL_TEXTURE_WRAP_T, GL_REPEAT);

    char label[160];
    ob_settings s;
    const ob_host_frame lin = linear_frame(&in), hw = hardware_frame(&in);
    const ob_host_outputs out_ao = {.ao = o.r16f};

    /* First of all, under the host's state: the AO that is compared with a clean context's. */
    static float hostile_ao[W * H];
    host_settings(&s, "vbao", "crease");
    ob_renderer_reset_history(r);
    run_call(F_AO_LIN, "ob_host_ao(vbao, crease, first call of the renderer)",
             &(call){.kind = CALL_HOST_AO, .r = r, .settings = &s, .frame = &lin, .outputs = &out_ao});
    read_r(o.r16f, hostile_ao, W, H);

    for (int m = 0; m < ob_method_count(); ++m) {
        const ob_method_info *info = ob_method_at(m);
        if (!host_settings(&s, info->name, "none")) {
            CHECK(false, "settings for %s", info->name);
            continue;
        }
        for (int depth_kind = 0; depth_kind < 2; ++depth_kind) {
            ob_host_frame f = depth_kind ? hw : lin;
            ob_host_outputs out = out_ao;
            int family = depth_kind ? F_AO_HW : F_AO_LIN;
            if (info->directional) {
                f.radiance = in.radiance, f.albedo = in.albedo;
                out = (ob_host_outputs){.ao = o.rgba16f, .indirect = o.indirect};
                family = depth_kind ? F_GI_HW : F_GI_LIN;
            }
            snprintf(label, sizeof label, "ob_host_ao(%s, %s depth)", info->name, depth_kind ? "D32F reversed-Z" : "R32F linear");
            ob_renderer_reset_history(r);
            run_call(family, label, &(call){.kind = CALL_HOST_AO, .r = r, .settings = &s, .frame = &f, .outputs = &out});
        }
    }

    for (int i = 0; i < ob_filter_count(); ++i) {
        const ob_filter_info *info = ob_filter_at(i);
        const char *const tiled[] = {NULL, "tiled=on", "tiled=off", "tiled=block"};
        for (int k = 0; k < (strcmp(info->name, "crease") ? 1 : 4); ++k) {
            host_settings(&s, "vbao", info->name);
            if (tiled[k]) {
                char a[64];
                snprintf(a, sizeof a, "crease.%s", tiled[k]);
                if (!set(&s, a)) continue;
            }
            snprintf(label, sizeof label, "ob_host_ao(vbao, filter %s%s%s)", info->name, tiled[k] ? " " : "",
                     tiled[k] ? tiled[k] : "");
            run_call(F_FILTER, label, &(call){.kind = CALL_HOST_AO, .r = r, .settings = &s, .frame = &lin, .outputs = &out_ao});
        }
    }

    static const struct { const char *method, *assignment; bool bent, second, gi; } variants[] = {
        {"ssao", "deinterleave=on", false, false, false}, {"hbao", "depth_mips=on", false, false, false},
        {"gtao", "bent_normals=on", true, false, false},  {"gtao", "layers=2", false, true, false},
        {"vbao", "layers=2", false, true, false},         {"vbao", "depth_mips=on", false, false, false},
        {"vbgi", "packed=on", false, false, true},        {"ssdo", "fused=off", false, false, true},
        {"ssdo_merged", "packed=on", false, false, true}};
    for (size_t v = 0; v < sizeof variants / sizeof variants[0]; ++v) {
        host_settings(&s, variants[v].method, "crease");
        if (!set(&s, variants[v].assignment)) continue;
        ob_host_frame f = hw;
        ob_host_outputs out = out_ao;
        if (variants[v].bent) out.bent_normal = o.bent;
        if (variants[v].second) f = lin, f.second_depth = in.second;
        if (variants[v].gi) {
            f.radiance = in.radiance, f.albedo = in.albedo;
            out = (ob_host_outputs){.ao = o.rgba16f, .indirect = o.indirect};
        }
        snprintf(label, sizeof label, "ob_host_ao(%s %s)", variants[v].method, variants[v].assignment);
        run_call(F_VARIANT, label, &(call){.kind = CALL_HOST_AO, .r = r, .settings = &s, .frame = &f, .outputs = &out});
    }

    static const char *const prepared[] = {"vbao", "gtao", "vbgi", "ssao"};
    for (size_t i = 0; i < sizeof prepared / sizeof prepared[0]; ++i) {
        host_settings(&s, prepared[i], "crease");
        if (i == 1) set(&s, "temporal=on");
        if (i == 3) ob_settings_set_ao_divisor(&s, 2);
        snprintf(label, sizeof label, "ob_host_prepare(%s%s)", prepared[i], i == 1 ? ", temporal" : i == 3 ? ", 1/2" : "");
        run_call(F_PREPARE, label, &(call){.kind = CALL_PREPARE, .r = r, .settings = &s});
    }

    /* The old entry points on the host's R32F linear depth and RGBA16F normals, into R32F. */
    static const char *const old_methods[] = {"ssao", "gtao", "vbao", "hbao"};
    for (size_t i = 0; i < sizeof old_methods / sizeof old_methods[0]; ++i) {
        ob_settings_init(&s, old_methods[i]);
        set(&s, "radius=1");
        ob_settings_set_filter(&s, i % 2 ? "geometry" : "crease");
        snprintf(label, sizeof label, "ob_compute_ao(%s)", old_methods[i]);
        run_call(F_OLD_AO, label,
                 &(call){.kind = CALL_COMPUTE_AO, .r = r, .settings = &s, .depth = in.linear, .normal = in.normal_view,
                         .out = o.r32f, .proj = in.v.proj});
        snprintf(label, sizeof label, "ob_compute_ao_filtered(%s, %s)", old_methods[i], i % 2 ? "geometry" : "crease");
        run_call(F_OLD_FILTERED, label,
                 &(call){.kind = CALL_COMPUTE_AO_FILTERED, .r = r, .settings = &s, .depth = in.linear,
                         .normal = in.normal_view, .out = o.r32f, .proj = in.v.proj});
    }

    static const struct { const char *method; int divisor; bool hw; } divisors[] = {
        {"vbao", 2, false}, {"gtao", 2, true}, {"ssao", 4, false}, {"vbgi", 2, false}};
    for (size_t i = 0; i < sizeof divisors / sizeof divisors[0]; ++i) {
        host_settings(&s, divisors[i].method, "crease");
        ob_settings_set_ao_divisor(&s, divisors[i].divisor);
        ob_host_frame f = divisors[i].hw ? hw : lin;
        ob_host_outputs out = out_ao;
        if (ob_method_at(s.method)->directional) {
            f.radiance = in.radiance, f.albedo = in.albedo;
            out = (ob_host_outputs){.ao = o.rgba16f, .indirect = o.indirect};
        }
        snprintf(label, sizeof label, "ob_host_ao(%s, ao_divisor %d)", divisors[i].method, divisors[i].divisor);
        run_call(F_DIVISOR, label, &(call){.kind = CALL_HOST_AO, .r = r, .settings = &s, .frame = &f, .outputs = &out});
    }

    /* Temporal: three frames of a camera moving sideways, with a TAA jitter; the last with a
     * motion texture. */
    {
        ob_host_settings hs = {.method = "gtao", .radius = 1.0f, .temporal = true, .ao_divisor = 2};
        ob_error e = ob_settings_from_host(&s, &hs);
        CHECK(e == OB_OK, "ob_settings_from_host(gtao, temporal, 1/2)");
        ob_renderer_reset_history(r);
        static inputs moved[3];
        for (int frame = 0; frame < 3; ++frame) {
            const float eye[3] = {cam_eye[0] + 0.05f * (float)frame, cam_eye[1], cam_eye[2]};
            const float jitter[3][2] = {{0.25f, -0.25f}, {-0.25f, 0.25f}, {0.125f, 0.375f}};
            float jittered[16];
            memcpy(jittered, proj, sizeof jittered);
            jittered[8] += 2.0f * jitter[frame][0] / (float)W, jittered[9] += 2.0f * jitter[frame][1] / (float)H;
            make_inputs(&moved[frame], W, H, jittered, eye);
            ob_host_frame f = hardware_frame(&moved[frame]);
            memcpy(f.projection, moved[frame].proj_hw, sizeof f.projection);
            f.projection[8] = proj[8], f.projection[9] = proj[9]; /* before the jitter */
            f.jitter[0] = jitter[frame][0], f.jitter[1] = jitter[frame][1];
            if (frame == 2) f.motion = moved[frame].motion;
            snprintf(label, sizeof label, "ob_host_ao(gtao, temporal, frame %d%s)", frame, frame == 2 ? ", motion" : "");
            run_call(F_TEMPORAL, label, &(call){.kind = CALL_HOST_AO, .r = r, .settings = &s, .frame = &f, .outputs = &out_ao});
        }
    }

    /* A guard band: the host renders ob_host_input_size with the widened projection. */
    {
        host_settings(&s, "vbao", "crease");
        set(&s, "guard=6");
        int gw = 0, gh = 0, g = 0;
        ob_host_input_size(r, &s, &gw, &gh, &g);
        CHECK(g >= 6 && g % 4 == 0 && gw == W + 2 * g && gh == H + 2 * g, "ob_host_input_size with guard=6: %dx%d, %d px",
              gw, gh, g);
        if (gw > 0 && gh > 0 && gw <= 4 * W && gh <= 4 * H) {
            float wide[16];
            memcpy(wide, proj, sizeof wide);
            ob_guard_projection(wide, W, H, g);
            static inputs band;
            make_inputs(&band, gw, gh, wide, cam_eye);
            ob_host_frame f = linear_frame(&band);
            run_call(F_GUARD, "ob_host_ao(vbao, guard 6, linear)",
                     &(call){.kind = CALL_HOST_AO, .r = r, .settings = &s, .frame = &f, .outputs = &out_ao});
            f = hardware_frame(&band);
            run_call(F_GUARD, "ob_host_ao(vbao, guard 6, D32F)",
                     &(call){.kind = CALL_HOST_AO, .r = r, .settings = &s, .frame = &f, .outputs = &out_ao});
        }
    }

    /* Refused calls restore too (validated before anything is bound, or after: either way). */
    {
        host_settings(&s, "vbao", "crease");
        GLuint rgb8 = make_tex(GL_RGB8, W, H), half = make_tex(GL_RGBA16F, W / 2, H / 2);
        ob_host_frame f = lin;
        f.normal = rgb8;
        run_call(F_REFUSED, "ob_host_ao(normal GL_RGB8)",
                 &(call){.kind = CALL_HOST_AO, .r = r, .settings = &s, .frame = &f, .outputs = &out_ao,
                         .expect = OB_ERR_INVALID_ARGUMENT});
        f = lin;
        f.depth = 12345;
        run_call(F_REFUSED, "ob_host_ao(depth 12345, no such texture)",
                 &(call){.kind = CALL_HOST_AO, .r = r, .settings = &s, .frame = &f, .outputs = &out_ao,
                         .expect = OB_ERR_INVALID_ARGUMENT});
        f = lin;
        f.radiance = 0;
        host_settings(&s, "vbgi", "crease");
        const ob_host_outputs gi_out = {.ao = o.rgba16f, .indirect = o.indirect};
        run_call(F_REFUSED, "ob_host_ao(vbgi without radiance)",
                 &(call){.kind = CALL_HOST_AO, .r = r, .settings = &s, .frame = &f, .outputs = &gi_out,
                         .expect = OB_ERR_INVALID_ARGUMENT});
        ob_settings_init(&s, "ssao");
        run_call(F_REFUSED, "ob_compute_ao_filtered(normal at half size)",
                 &(call){.kind = CALL_COMPUTE_AO_FILTERED, .r = r, .settings = &s, .depth = in.linear, .normal = half,
                         .out = o.r32f, .proj = in.v.proj, .expect = OB_ERR_INVALID_ARGUMENT});
        glDeleteTextures(1, &rgb8);
        glDeleteTextures(1, &half);
    }

    /* The same first call in a clean context: a second renderer made and run with GL's defaults
     * everywhere gives the same AO (nothing of the host's state leaks into the library's work:
     * uploads through the host's unpack buffer, its pixel store, its samplers). */
    unbind_host_state();
    ob_renderer *clean = ob_make_renderer(T.ctx, &(ob_renderer_desc){.width = W, .height = H});
    CHECK(clean != NULL, "a second renderer");
    if (clean) {
        host_settings(&s, "vbao", "crease");
        GLuint fresh = make_tex(GL_R16F, W, H);
        ob_error e = ob_host_ao(clean, &lin, &s, &(ob_host_outputs){.ao = fresh});
        CHECK(e == OB_OK, "ob_host_ao in a clean context");
        static float clean_ao[W * H];
        read_r(fresh, clean_ao, W, H);
        double worst = 0.0;
        int worst_i = 0;
        for (int i = 0; i < W * H; ++i) {
            double d = fabs((double)clean_ao[i] - (double)hostile_ao[i]);
            if (!(d <= worst)) worst = d, worst_i = i;
        }
        printf("\nvbao + crease, the renderer's first call under all of the host's state vs a new renderer in a clean "
               "context: worst |difference| %.3g (at %d, %d: %.4f vs %.4f)\n",
               worst, worst_i % W, worst_i / W, (double)hostile_ao[worst_i], (double)clean_ao[worst_i]);
        CHECK(worst <= 1e-6, "the AO under the host's state differs from a clean context's by %.3g at (%d, %d)", worst,
              worst_i % W, worst_i / W);
        glDeleteTextures(1, &fresh);
        ob_destroy_renderer(clean);
    }
}

#ifndef HOST_STATE_NO_MAIN
/* False, with the step and the driver's own message, when the test's set-up left a GL error. */
static bool setup_clean(const char *step)
{
    GLenum e = glGetError();
    if (e == GL_NO_ERROR && !dbg.errors) return true;
    fprintf(stderr, "test_host_state: %s raised %s (the test's own GL calls, before any library call)%s%s\n", step,
            error_name(e), dbg.errors ? ": " : "", dbg.errors ? dbg.first_error : "");
    return false;
}

int main(void)
{
    if (!make_host_context(true)) {
        fprintf(stderr, "no EGL device gives an OpenGL 4.5 core context\n");
        return 1;
    }
    GLint flags = 0;
    glGetIntegerv(GL_CONTEXT_FLAGS, &flags);
    T.debug_context = (flags & GL_CONTEXT_FLAG_DEBUG_BIT) != 0;
    glDebugMessageCallback(on_debug, &T);
    glEnable(GL_DEBUG_OUTPUT);
    /* The groups' own messages, whatever the driver's default for notifications. */
    glDebugMessageControl(GL_DONT_CARE, GL_DEBUG_TYPE_PUSH_GROUP, GL_DONT_CARE, 0, NULL, GL_TRUE);
    glDebugMessageControl(GL_DONT_CARE, GL_DEBUG_TYPE_POP_GROUP, GL_DONT_CARE, 0, NULL, GL_TRUE);
    printf("host context: %s, %s, %s context\n", (const char *)glGetString(GL_RENDERER),
           (const char *)glGetString(GL_VERSION), T.debug_context ? "debug" : "no debug");
    /* The test's own set-up must raise no GL error: one left pending would be read by the
     * library's first glGetError and blamed on it (NVIDIA's driver refuses calls llvmpipe takes). */
    memset(&dbg, 0, sizeof dbg);
    make_host_objects(&T.host);
    T.host.watched_count = 0;
    if (!setup_clean("making the host's objects")) return 1;

    /* The library adopts the context and makes its renderer with the host's state bound. */
    bind_host_state(&T.host);
    if (!setup_clean("binding the host's state")) return 1;
    take_snapshot(&T.before, &T.host);
    if (!setup_clean("reading the host's state (the snapshot)")) return 1;
    T.ctx = ob_make_context(&(ob_context_desc){.use_current = true});
    /* An engine's stale GL error, left pending: the renderer is made all the same (it reads and
     * drops it rather than blaming its own targets for it). */
    glViewport(0, 0, -1, -1);
    memset(&dbg, 0, sizeof dbg);
    ob_renderer *r = T.ctx ? ob_make_renderer(T.ctx, &(ob_renderer_desc){.width = W, .height = H}) : NULL;
    CHECK(r != NULL, "ob_make_renderer with the host's GL_INVALID_VALUE pending: no renderer");
    CHECK(dbg.errors == 0, "ob_make_renderer raised %d GL error(s) of its own, the first: %s", dbg.errors,
          dbg.first_error);
    take_snapshot(&T.after, &T.host);
    ++T.calls[F_MAKE];
    compare_snapshots(F_MAKE, "ob_make_context + ob_make_renderer", true);
    (void)glGetError();
    if (!r) {
        const char *msg = "";
        ob_get_error(&msg);
        fprintf(stderr, "libobscura: %s%s%s\n", msg, dbg.errors ? "; the driver's first error message: " : "",
                dbg.errors ? dbg.first_error : "");
        return 1;
    }
    run_all(r);
    print_table();
    ob_destroy_renderer(r);
    ob_destroy_context(T.ctx);
    destroy_host_context();
    return check_finish("host_state");
}
#endif
