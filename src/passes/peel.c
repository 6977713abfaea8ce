/* The second depth layer (shaders/peel.frag.glsl): one more raster pass over the G-buffer's
 * meshes, made and run only for a method that reads OB_READS_SECOND_LAYER. It writes the layer's
 * linear depth and its own triangles' planes (their normals, which second_back.glsl reads). Its
 * targets follow the G-buffer's size, so a resize (or a guard band) remakes them on the next run. */
#include <string.h>

#include "base/error.h"
#include "gbuffer_params.h"
#include "passes/passes.h"

static void release_targets(ob_peel *p)
{
    GLuint tex[3] = {p->depth, p->linear_depth, p->plane};
    glDeleteTextures(3, tex);
    p->depth = p->linear_depth = p->plane = 0;
    p->width = p->height = 0;
}

ob_error ob_peel_init(ob_peel *p)
{
    memset(p, 0, sizeof *p);
    p->program = ob_make_raster_program("gbuffer.vert.glsl", "peel.frag.glsl", NULL);
    if (!p->program) return ob_peek_error(NULL);
    glCreateBuffers(1, &p->ubo);
    glNamedBufferStorage(p->ubo, sizeof(ob_gbuffer_constants), NULL, GL_DYNAMIC_STORAGE_BIT);
    glCreateFramebuffers(1, &p->fbo);
    const GLenum draw[2] = {GL_COLOR_ATTACHMENT0, GL_COLOR_ATTACHMENT1};
    glNamedFramebufferDrawBuffers(p->fbo, 2, draw);
    return OB_OK;
}

static ob_error make_targets(ob_peel *p, int width, int height)
{
    release_targets(p);
    p->depth = ob_make_texture_2d(GL_DEPTH_COMPONENT32F, width, height);
    p->linear_depth = ob_make_texture_2d(GL_R32F, width, height);
    p->plane = ob_make_texture_2d(GL_RG16F, width, height);
    glNamedFramebufferTexture(p->fbo, GL_DEPTH_ATTACHMENT, p->depth, 0);
    glNamedFramebufferTexture(p->fbo, GL_COLOR_ATTACHMENT0, p->linear_depth, 0);
    glNamedFramebufferTexture(p->fbo, GL_COLOR_ATTACHMENT1, p->plane, 0);
    GLenum status = glCheckNamedFramebufferStatus(p->fbo, GL_FRAMEBUFFER);
    GLenum e = glGetError();
    if (e != GL_NO_ERROR || status != GL_FRAMEBUFFER_COMPLETE) {
        release_targets(p);
        return ob_set_error(OB_ERR_GL, "second depth layer: OpenGL error 0x%x, framebuffer 0x%x at %dx%d", e, status,
                            width, height);
    }
    p->width = width;
    p->height = height;
    return OB_OK;
}

ob_error ob_peel_run(ob_peel *p, const ob_gbuffer *g, const float *view, const float *proj)
{
    if (p->width != g->width || p->height != g->height) {
        ob_error err = make_targets(p, g->width, g->height);
        if (err != OB_OK) return err;
    }
    ob_gbuffer_constants c;
    memset(&c, 0, sizeof c);
    memcpy(c.view, view, sizeof c.view);
    memcpy(c.proj, proj, sizeof c.proj);
    memcpy(c.normal_matrix, view, sizeof c.normal_matrix); /* unused: no normal is written */
    glNamedBufferSubData(p->ubo, 0, sizeof c, &c);

    glBindFramebuffer(GL_FRAMEBUFFER, p->fbo);
    glViewport(0, 0, p->width, p->height);
    const float zero[4] = {0.0f, 0.0f, 0.0f, 0.0f};
    const float one = 1.0f;
    glClearNamedFramebufferfv(p->fbo, GL_COLOR, 0, zero);
    glClearNamedFramebufferfv(p->fbo, GL_COLOR, 1, zero);
    glClearNamedFramebufferfv(p->fbo, GL_DEPTH, 0, &one);
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_LESS);
    glDisable(GL_CULL_FACE); /* back faces included: they close an object behind its front */
    glDisable(GL_BLEND);
    glUseProgram(p->program);
    glBindBufferBase(GL_UNIFORM_BUFFER, OB_BINDING_PASS, p->ubo);
    glBindTextureUnit(OB_UNIT_FIRST_LAYER, g->linear_depth);
    glBindTextureUnit(OB_UNIT_FIRST_FACING, g->normal);
    for (int i = 0; i < g->mesh_count; ++i) {
        glBindVertexArray(g->meshes[i].vao);
        glDrawElements(GL_TRIANGLES, g->meshes[i].index_count, GL_UNSIGNED_INT, NULL);
    }
    glBindVertexArray(0);
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    return OB_OK;
}

void ob_peel_destroy(ob_peel *p)
{
    release_targets(p);
    glDeleteProgram(p->program);
    glDeleteBuffers(1, &p->ubo);
    glDeleteFramebuffers(1, &p->fbo);
    memset(p, 0, sizeof *p);
}
