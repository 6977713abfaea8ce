/* G-buffer: hardware depth, linear view depth (R32F), view-space normal, albedo.
 * The only raster pass: every pass after it is a compute shader. */
#include <cglm/cglm.h>
#include <stdlib.h>
#include <string.h>

#include "base/error.h"
#include "gbuffer_params.h"
#include "passes/passes.h"

_Static_assert(OB_PART_SHEET == OB_PART_SHEET_FLAG, "the sheet flag of scene/parts.c and the G-buffer's shaders");

#define TARGETS 5

/* The targets in the order of ob_gbuffer's members: depth, linear depth, normal, albedo, facet. */
static void make_targets(GLuint tex[TARGETS], int width, int height)
{
    tex[0] = ob_make_texture_2d(GL_DEPTH_COMPONENT32F, width, height);
    tex[1] = ob_make_texture_2d(GL_R32F, width, height);
    tex[2] = ob_make_texture_2d(GL_RGBA16F, width, height);
    tex[3] = ob_make_texture_2d(GL_RGBA16F, width, height);
    tex[4] = ob_make_texture_2d(GL_RG16F, width, height);
}

static GLenum attach(GLuint fbo, const GLuint tex[TARGETS])
{
    glNamedFramebufferTexture(fbo, GL_DEPTH_ATTACHMENT, tex[0], 0);
    for (int i = 1; i < TARGETS; ++i) glNamedFramebufferTexture(fbo, GL_COLOR_ATTACHMENT0 + (GLenum)(i - 1), tex[i], 0);
    return glCheckNamedFramebufferStatus(fbo, GL_FRAMEBUFFER);
}

ob_error ob_gbuffer_init(ob_gbuffer *g, int width, int height)
{
    memset(g, 0, sizeof *g);
    g->width = width;
    g->height = height;
    g->program = ob_make_raster_program("gbuffer.vert.glsl", "gbuffer.frag.glsl", NULL);
    if (!g->program) return ob_peek_error(NULL);
    glCreateBuffers(1, &g->ubo);
    glNamedBufferStorage(g->ubo, sizeof(ob_gbuffer_constants), NULL, GL_DYNAMIC_STORAGE_BIT);
    GLuint tex[TARGETS] = {0, 0, 0, 0, 0};
    make_targets(tex, width, height);
    g->depth = tex[0];
    g->linear_depth = tex[1];
    g->normal = tex[2];
    g->albedo = tex[3];
    g->facet = tex[4];
    glCreateFramebuffers(1, &g->fbo);
    const GLenum draw[TARGETS - 1] = {GL_COLOR_ATTACHMENT0, GL_COLOR_ATTACHMENT1, GL_COLOR_ATTACHMENT2,
                                      GL_COLOR_ATTACHMENT3};
    glNamedFramebufferDrawBuffers(g->fbo, TARGETS - 1, draw);
    GLenum status = attach(g->fbo, tex);
    if (status != GL_FRAMEBUFFER_COMPLETE)
        return ob_set_error(OB_ERR_GL, "G-buffer framebuffer incomplete (0x%x) at %dx%d", status, width, height);
    return OB_OK;
}

ob_error ob_gbuffer_resize(ob_gbuffer *g, int width, int height)
{
    GLuint made[TARGETS] = {0, 0, 0, 0, 0};
    make_targets(made, width, height);
    GLenum e = ob_gl_error();
    GLenum status = e == GL_NO_ERROR ? attach(g->fbo, made) : GL_FRAMEBUFFER_COMPLETE;
    if (e != GL_NO_ERROR || status != GL_FRAMEBUFFER_COMPLETE) {
        /* Back to the old targets, which still work at the old size. */
        const GLuint old[TARGETS] = {g->depth, g->linear_depth, g->normal, g->albedo, g->facet};
        attach(g->fbo, old);
        glDeleteTextures(TARGETS, made);
        if (e != GL_NO_ERROR)
            return ob_set_error(OB_ERR_GL, "OpenGL error 0x%x making %dx%d G-buffer targets", e, width, height);
        return ob_set_error(OB_ERR_GL, "G-buffer framebuffer incomplete (0x%x) at %dx%d", status, width, height);
    }
    GLuint old[TARGETS] = {g->depth, g->linear_depth, g->normal, g->albedo, g->facet};
    glDeleteTextures(TARGETS, old);
    g->depth = made[0];
    g->linear_depth = made[1];
    g->normal = made[2];
    g->albedo = made[3];
    g->facet = made[4];
    g->width = width;
    g->height = height;
    return OB_OK;
}

static void release_scene(ob_gbuffer *g)
{
    for (int i = 0; i < g->mesh_count; ++i) {
        glDeleteVertexArrays(1, &g->meshes[i].vao);
        glDeleteBuffers(5, g->meshes[i].buffers);
    }
    if (g->textures) {
        /* Materials that share an image share its texture: delete each name once. */
        for (int i = 0; i < g->material_count; ++i)
            for (int j = 0; j < i && g->textures[i]; ++j)
                if (g->textures[j] == g->textures[i]) g->textures[i] = 0;
        glDeleteTextures(g->material_count, g->textures);
    }
    free(g->meshes);
    free(g->textures);
    free(g->diffuse);
    g->meshes = NULL;
    g->textures = NULL;
    g->diffuse = NULL;
    g->mesh_count = g->material_count = 0;
}

/* Each mesh's per-vertex part labels (scene/parts.c), numbered across the meshes (a part never
 * spans two), with the sheets settled over the whole scene (scene/sheets.c). NULL when out of
 * memory. */
static float **scene_part_labels(const ob_scene *scene)
{
    float **labels = calloc((size_t)scene->mesh_count + 1, sizeof *labels);
    ob_holes *holes = calloc((size_t)scene->mesh_count + 1, sizeof *holes);
    uint32_t parts = 0;
    bool ok = labels != NULL && holes != NULL;
    for (int i = 0; ok && i < scene->mesh_count; ++i) {
        labels[i] = malloc((size_t)scene->meshes[i].vertex_count * sizeof(float) + 1);
        int64_t found = labels[i] ? ob_mesh_part_labels(&scene->meshes[i], parts, labels[i], &holes[i]) : -1;
        ok = found >= 0;
        if (ok) parts += (uint32_t)(found % OB_PART_LABELS);
    }
    if (ok) ok = ob_scene_settle_sheets(scene, labels, holes) >= 0;
    for (int i = 0; holes && i < scene->mesh_count; ++i) free(holes[i].items);
    free(holes);
    if (!ok && labels) {
        for (int i = 0; i < scene->mesh_count; ++i) free(labels[i]);
        free(labels);
        return NULL;
    }
    return labels;
}

ob_error ob_gbuffer_set_scene(ob_gbuffer *g, const ob_scene *scene)
{
    /* Before anything is given up: a texture the GL cannot hold would be incomplete, and sampling
     * an incomplete texture gives black, which would draw the model black without a word. */
    GLint max_size = 0;
    glGetIntegerv(GL_MAX_TEXTURE_SIZE, &max_size);
    for (int i = 0; i < scene->material_count; ++i) {
        const ob_material *m = &scene->materials[i];
        if (m->texture && (m->tex_width > max_size || m->tex_height > max_size))
            return ob_set_error(OB_ERR_MODEL,
                                "texture '%s' (material '%s' of scene '%s') is %dx%d, larger than GL_MAX_TEXTURE_SIZE "
                                "%d of %s: scale the image down to fit",
                                m->texture_name, m->name, scene->name, m->tex_width, m->tex_height, (int)max_size,
                                (const char *)glGetString(GL_RENDERER));
    }
    release_scene(g);
    g->meshes = calloc((size_t)scene->mesh_count + 1, sizeof *g->meshes);
    g->textures = calloc((size_t)scene->material_count + 1, sizeof *g->textures);
    g->diffuse = calloc((size_t)scene->material_count + 1, sizeof *g->diffuse);
    if (!g->meshes || !g->textures || !g->diffuse) {
        release_scene(g);
        return ob_set_error(OB_ERR_OUT_OF_MEMORY, "out of memory uploading the scene");
    }
    g->material_count = scene->material_count;
    ++g->scene_generation;
    for (int i = 0; i < scene->material_count; ++i) {
        const ob_material *m = &scene->materials[i];
        memcpy(g->diffuse[i], m->diffuse, sizeof g->diffuse[i]);
        if (!m->texture) continue;
        if (m->texture_shared) {
            for (int j = 0; j < i && !g->textures[i]; ++j)
                if (scene->materials[j].texture == m->texture) g->textures[i] = g->textures[j];
            if (g->textures[i]) continue;
        }
        GLuint tex = 0;
        glCreateTextures(GL_TEXTURE_2D, 1, &tex);
        int levels = 1;
        for (int s = m->tex_width > m->tex_height ? m->tex_width : m->tex_height; s > 1; s >>= 1) ++levels;
        /* sRGB storage: the sampler returns linear albedo. */
        glTextureStorage2D(tex, levels, GL_SRGB8_ALPHA8, m->tex_width, m->tex_height);
        glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
        glTextureSubImage2D(tex, 0, 0, 0, m->tex_width, m->tex_height, GL_RGBA, GL_UNSIGNED_BYTE, m->texture);
        glGenerateTextureMipmap(tex);
        glTextureParameteri(tex, GL_TEXTURE_MIN_FILTER, GL_LINEAR_MIPMAP_LINEAR);
        glTextureParameteri(tex, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
        glTextureParameteri(tex, GL_TEXTURE_WRAP_S, GL_REPEAT);
        glTextureParameteri(tex, GL_TEXTURE_WRAP_T, GL_REPEAT);
        g->textures[i] = tex;
    }
    float **part_labels = scene_part_labels(scene);
    if (!part_labels) {
        release_scene(g);
        return ob_set_error(OB_ERR_OUT_OF_MEMORY, "out of memory uploading the scene");
    }
    for (int i = 0; i < scene->mesh_count; ++i) {
        const ob_mesh *src = &scene->meshes[i];
        float *labels = part_labels[i];
        ob_gpu_mesh *dst = &g->meshes[g->mesh_count++];
        dst->index_count = (GLsizei)src->index_count;
        dst->material = src->material;
        glCreateVertexArrays(1, &dst->vao);
        glCreateBuffers(5, dst->buffers);
        size_t vn = (size_t)src->vertex_count;
        glNamedBufferStorage(dst->buffers[0], (GLsizeiptr)(vn * 3 * sizeof(float)), src->positions, 0);
        glNamedBufferStorage(dst->buffers[1], (GLsizeiptr)(vn * 3 * sizeof(float)), src->normals, 0);
        if (src->uvs) glNamedBufferStorage(dst->buffers[2], (GLsizeiptr)(vn * 2 * sizeof(float)), src->uvs, 0);
        glNamedBufferStorage(dst->buffers[3], (GLsizeiptr)(src->index_count * sizeof(uint32_t)), src->indices, 0);
        glNamedBufferStorage(dst->buffers[4], (GLsizeiptr)(vn * sizeof(float)), labels, 0);
        free(labels);
        part_labels[i] = NULL;
        glVertexArrayVertexBuffer(dst->vao, 3, dst->buffers[4], 0, sizeof(float));
        glEnableVertexArrayAttrib(dst->vao, 3);
        glVertexArrayAttribFormat(dst->vao, 3, 1, GL_FLOAT, GL_FALSE, 0);
        glVertexArrayAttribBinding(dst->vao, 3, 3);
        glVertexArrayVertexBuffer(dst->vao, 0, dst->buffers[0], 0, 3 * sizeof(float));
        glVertexArrayVertexBuffer(dst->vao, 1, dst->buffers[1], 0, 3 * sizeof(float));
        glVertexArrayElementBuffer(dst->vao, dst->buffers[3]);
        for (GLuint a = 0; a < 2; ++a) {
            glEnableVertexArrayAttrib(dst->vao, a);
            glVertexArrayAttribFormat(dst->vao, a, 3, GL_FLOAT, GL_FALSE, 0);
            glVertexArrayAttribBinding(dst->vao, a, a);
        }
        if (src->uvs) {
            glVertexArrayVertexBuffer(dst->vao, 2, dst->buffers[2], 0, 2 * sizeof(float));
            glEnableVertexArrayAttrib(dst->vao, 2);
            glVertexArrayAttribFormat(dst->vao, 2, 2, GL_FLOAT, GL_FALSE, 0);
            glVertexArrayAttribBinding(dst->vao, 2, 2);
        } /* else: a disabled attribute reads (0, 0, 0, 1), and no texture is bound anyway */
    }
    free(part_labels);
    return OB_OK;
}

void ob_gbuffer_run(ob_gbuffer *g, const float *view, const float *proj, bool textures)
{
    ob_gbuffer_run_from(g, g, view, proj, textures);
}

void ob_gbuffer_run_from(ob_gbuffer *g, const ob_gbuffer *scene, const float *view, const float *proj, bool textures)
{
    ob_gbuffer_constants c;
    memset(&c, 0, sizeof c);
    memcpy(c.view, view, sizeof c.view);
    memcpy(c.proj, proj, sizeof c.proj);
    /* Normals go to view space with the inverse-transpose of the view's 3x3 (a rigid view makes
     * it equal to the 3x3 itself, but a scaled camera does not). */
    mat4 v4, nm;
    memcpy(v4, view, sizeof v4);
    glm_mat4_inv(v4, nm);
    glm_mat4_transpose(nm);
    memcpy(c.normal_matrix, nm, sizeof c.normal_matrix);

    glBindFramebuffer(GL_FRAMEBUFFER, g->fbo);
    glViewport(0, 0, g->width, g->height);
    const float zero[4] = {0.0f, 0.0f, 0.0f, 0.0f};
    const float one = 1.0f;
    glClearNamedFramebufferfv(g->fbo, GL_COLOR, 0, zero);
    glClearNamedFramebufferfv(g->fbo, GL_COLOR, 1, zero);
    glClearNamedFramebufferfv(g->fbo, GL_COLOR, 2, zero);
    glClearNamedFramebufferfv(g->fbo, GL_COLOR, 3, zero);
    glClearNamedFramebufferfv(g->fbo, GL_DEPTH, 0, &one);
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_LESS);
    glDisable(GL_CULL_FACE); /* two-sided: the fragment shader flips back-facing normals */
    glDisable(GL_BLEND);
    glUseProgram(g->program);
    glBindBufferBase(GL_UNIFORM_BUFFER, OB_BINDING_PASS, g->ubo);
    int last_material = -2;
    for (int i = 0; i < scene->mesh_count; ++i) {
        const ob_gpu_mesh *m = &scene->meshes[i];
        if (m->material != last_material) {
            int mi = m->material >= 0 && m->material < scene->material_count ? m->material : -1;
            c.diffuse[0] = mi >= 0 ? scene->diffuse[mi][0] : 0.8f;
            c.diffuse[1] = mi >= 0 ? scene->diffuse[mi][1] : 0.8f;
            c.diffuse[2] = mi >= 0 ? scene->diffuse[mi][2] : 0.8f;
            c.textured = textures && mi >= 0 && scene->textures[mi] ? 1 : 0;
            glNamedBufferSubData(g->ubo, 0, sizeof c, &c);
            glBindTextureUnit(OB_UNIT_DIFFUSE_MAP, c.textured ? scene->textures[mi] : 0);
            last_material = m->material;
        }
        glBindVertexArray(m->vao);
        glDrawElements(GL_TRIANGLES, m->index_count, GL_UNSIGNED_INT, NULL);
    }
    glBindVertexArray(0);
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
}

void ob_gbuffer_destroy(ob_gbuffer *g)
{
    release_scene(g);
    glDeleteProgram(g->program);
    glDeleteBuffers(1, &g->ubo);
    glDeleteFramebuffers(1, &g->fbo);
    GLuint tex[TARGETS] = {g->depth, g->linear_depth, g->normal, g->albedo, g->facet};
    glDeleteTextures(TARGETS, tex);
    memset(g, 0, sizeof *g);
}
