/* The GL state a pass may change, saved and put back, for the calls that run inside a host's
 * frame (ob_host_ao, ob_present): the program, the active unit, the 2D texture and the sampler
 * object of texture units 0..count-1, image units 0..count-1 and the uniform buffer bindings
 * OB_BINDING_PASS and OB_BINDING_FRAME with the generic binding. Queries only: a pending GL error
 * of the host's stays pending (glGet* of valid enums raises none). */
#include "gpu/gpu.h"
#include "ob_shared.h"

static const GLenum unpack_names[6] = {GL_UNPACK_ALIGNMENT,   GL_UNPACK_ROW_LENGTH, GL_UNPACK_IMAGE_HEIGHT,
                                       GL_UNPACK_SKIP_PIXELS, GL_UNPACK_SKIP_ROWS,  GL_UNPACK_SKIP_IMAGES};

void ob_gl_state_save(ob_gl_state *s, int texture_units, int image_units)
{
    s->texture_units = texture_units < OB_GL_STATE_TEXTURES ? texture_units : OB_GL_STATE_TEXTURES;
    s->image_units = image_units < OB_GL_STATE_IMAGES ? image_units : OB_GL_STATE_IMAGES;
    glGetIntegerv(GL_CURRENT_PROGRAM, &s->program);
    glGetIntegerv(GL_ACTIVE_TEXTURE, &s->active_texture);
    for (int i = 0; i < s->texture_units; ++i) {
        glActiveTexture(GL_TEXTURE0 + (GLenum)i);
        glGetIntegerv(GL_TEXTURE_BINDING_2D, &s->textures[i]);
        glGetIntegerv(GL_TEXTURE_BINDING_2D_ARRAY, &s->arrays[i]);
        glGetIntegerv(GL_SAMPLER_BINDING, &s->samplers[i]);
    }
    glActiveTexture((GLenum)s->active_texture);
    for (int i = 0; i < s->image_units; ++i) {
        ob_gl_image_binding *b = &s->images[i];
        glGetIntegeri_v(GL_IMAGE_BINDING_NAME, (GLuint)i, &b->name);
        glGetIntegeri_v(GL_IMAGE_BINDING_LEVEL, (GLuint)i, &b->level);
        glGetIntegeri_v(GL_IMAGE_BINDING_LAYERED, (GLuint)i, &b->layered);
        glGetIntegeri_v(GL_IMAGE_BINDING_LAYER, (GLuint)i, &b->layer);
        glGetIntegeri_v(GL_IMAGE_BINDING_ACCESS, (GLuint)i, &b->access);
        glGetIntegeri_v(GL_IMAGE_BINDING_FORMAT, (GLuint)i, &b->format);
    }
    glGetIntegerv(GL_UNIFORM_BUFFER_BINDING, &s->ubo_generic);
    const GLuint points[2] = {OB_BINDING_PASS, OB_BINDING_FRAME};
    for (int i = 0; i < 2; ++i) {
        glGetIntegeri_v(GL_UNIFORM_BUFFER_BINDING, points[i], &s->ubo[i]);
        glGetInteger64i_v(GL_UNIFORM_BUFFER_START, points[i], &s->ubo_start[i]);
        glGetInteger64i_v(GL_UNIFORM_BUFFER_SIZE, points[i], &s->ubo_size[i]);
    }
    glGetIntegerv(GL_PIXEL_UNPACK_BUFFER_BINDING, &s->unpack_buffer);
    glGetIntegerv(GL_QUERY_BUFFER_BINDING, &s->query_buffer);
    for (int i = 0; i < 6; ++i) glGetIntegerv(unpack_names[i], &s->unpack[i]);
    glGetBooleanv(GL_UNPACK_SWAP_BYTES, &s->unpack_swap);
    glGetBooleanv(GL_UNPACK_LSB_FIRST, &s->unpack_lsb);
    /* GL's defaults, which the passes' uploads and timer reads assume. */
    glBindBuffer(GL_PIXEL_UNPACK_BUFFER, 0);
    glBindBuffer(GL_QUERY_BUFFER, 0);
    for (int i = 0; i < 6; ++i) glPixelStorei(unpack_names[i], i == 0 ? 4 : 0);
    glPixelStorei(GL_UNPACK_SWAP_BYTES, GL_FALSE);
    glPixelStorei(GL_UNPACK_LSB_FIRST, GL_FALSE);
}

void ob_gl_state_restore(const ob_gl_state *s)
{
    /* A program deleted while current lived on only as long as it stayed current: then there is
     * nothing to go back to. */
    glUseProgram(s->program && glIsProgram((GLuint)s->program) ? (GLuint)s->program : 0);
    /* glBindTexture on each unit, not glBindTextureUnit(unit, 0), which would also unbind the
     * caller's textures of other targets there. */
    for (int i = 0; i < s->texture_units; ++i) {
        glActiveTexture(GL_TEXTURE0 + (GLenum)i);
        glBindTexture(GL_TEXTURE_2D, (GLuint)s->textures[i]);
        glBindTexture(GL_TEXTURE_2D_ARRAY, (GLuint)s->arrays[i]);
        glBindSampler((GLuint)i, (GLuint)s->samplers[i]);
    }
    glActiveTexture((GLenum)s->active_texture);
    for (int i = 0; i < s->image_units; ++i) {
        const ob_gl_image_binding *b = &s->images[i];
        /* An unbound unit reads back format GL_R8 on some drivers and 0 on others; 0 is not a
         * format glBindImageTexture takes, so an empty unit is put back with one it does. */
        glBindImageTexture((GLuint)i, (GLuint)b->name, b->level, (GLboolean)b->layered, b->layer, (GLenum)b->access,
                           b->format ? (GLenum)b->format : GL_R8);
    }
    const GLuint points[2] = {OB_BINDING_PASS, OB_BINDING_FRAME};
    for (int i = 0; i < 2; ++i) {
        if (s->ubo[i] && s->ubo_size[i] > 0)
            glBindBufferRange(GL_UNIFORM_BUFFER, points[i], (GLuint)s->ubo[i], (GLintptr)s->ubo_start[i],
                              (GLsizeiptr)s->ubo_size[i]);
        else
            glBindBufferBase(GL_UNIFORM_BUFFER, points[i], (GLuint)s->ubo[i]);
    }
    glBindBuffer(GL_UNIFORM_BUFFER, (GLuint)s->ubo_generic); /* glBindBuffer{Base,Range} set it too */
    glBindBuffer(GL_PIXEL_UNPACK_BUFFER, (GLuint)s->unpack_buffer);
    glBindBuffer(GL_QUERY_BUFFER, (GLuint)s->query_buffer);
    for (int i = 0; i < 6; ++i) glPixelStorei(unpack_names[i], s->unpack[i]);
    glPixelStorei(GL_UNPACK_SWAP_BYTES, s->unpack_swap);
    glPixelStorei(GL_UNPACK_LSB_FIRST, s->unpack_lsb);
}

/* The host path reads no GL error: one the host left pending is the host's to read, and
 * glGetError would take it (ob_host_ao checks its arguments before it dispatches instead). */
static _Thread_local bool quiet;

void ob_gl_set_quiet(bool on) { quiet = on; }

GLenum ob_gl_error(void) { return quiet ? GL_NO_ERROR : glGetError(); }

void ob_gl_drop_pending(void)
{
    for (int drained = 0; !quiet && drained < 64 && glGetError() != GL_NO_ERROR; ++drained) continue;
}
