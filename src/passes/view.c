/* ob_present: the last frame, or one of its debug views mapped to display bytes by
 * shaders/view.glsl, blitted into the caller's framebuffer. Runs inside a caller's render loop
 * (the viewer's window), so everything it binds is put back as it was. */
#include <string.h>

#include "core/error.h"
#include "passes/passes.h"
#include "view_params.h"

enum { VIEW_UNITS = 2 }; /* texture units view.glsl samples */

/* What the compute pass changes; the blit itself binds nothing (DSA) and only obeys the scissor
 * test and GL_FRAMEBUFFER_SRGB among the fragment operations. */
typedef struct saved_state {
    GLint program;
    GLint active_texture;
    GLint textures[VIEW_UNITS];
    GLint ubo_generic, ubo;
    GLint64 ubo_start, ubo_size;
    GLint image, image_level, image_layered, image_layer, image_access, image_format;
} saved_state;

static void save_compute_state(saved_state *s)
{
    glGetIntegerv(GL_CURRENT_PROGRAM, &s->program);
    glGetIntegerv(GL_ACTIVE_TEXTURE, &s->active_texture);
    for (int i = 0; i < VIEW_UNITS; ++i) {
        glActiveTexture(GL_TEXTURE0 + (GLenum)i);
        glGetIntegerv(GL_TEXTURE_BINDING_2D, &s->textures[i]);
    }
    glGetIntegerv(GL_UNIFORM_BUFFER_BINDING, &s->ubo_generic);
    glGetIntegeri_v(GL_UNIFORM_BUFFER_BINDING, OB_BINDING_PASS, &s->ubo);
    glGetInteger64i_v(GL_UNIFORM_BUFFER_START, OB_BINDING_PASS, &s->ubo_start);
    glGetInteger64i_v(GL_UNIFORM_BUFFER_SIZE, OB_BINDING_PASS, &s->ubo_size);
    glGetIntegeri_v(GL_IMAGE_BINDING_NAME, 0, &s->image);
    glGetIntegeri_v(GL_IMAGE_BINDING_LEVEL, 0, &s->image_level);
    glGetIntegeri_v(GL_IMAGE_BINDING_LAYERED, 0, &s->image_layered);
    glGetIntegeri_v(GL_IMAGE_BINDING_LAYER, 0, &s->image_layer);
    glGetIntegeri_v(GL_IMAGE_BINDING_ACCESS, 0, &s->image_access);
    glGetIntegeri_v(GL_IMAGE_BINDING_FORMAT, 0, &s->image_format);
}

static void restore_compute_state(const saved_state *s)
{
    /* A program deleted while current lived on only as long as it stayed current: then there is
     * nothing to go back to. */
    glUseProgram(s->program && glIsProgram((GLuint)s->program) ? (GLuint)s->program : 0);
    /* glBindTexture on each unit, not glBindTextureUnit(unit, 0), which would also unbind the
     * caller's textures of other targets there. */
    for (int i = 0; i < VIEW_UNITS; ++i) {
        glActiveTexture(GL_TEXTURE0 + (GLenum)i);
        glBindTexture(GL_TEXTURE_2D, (GLuint)s->textures[i]);
    }
    glActiveTexture((GLenum)s->active_texture);
    if (s->ubo && s->ubo_size > 0)
        glBindBufferRange(GL_UNIFORM_BUFFER, OB_BINDING_PASS, (GLuint)s->ubo, (GLintptr)s->ubo_start,
                          (GLsizeiptr)s->ubo_size);
    else
        glBindBufferBase(GL_UNIFORM_BUFFER, OB_BINDING_PASS, (GLuint)s->ubo);
    glBindBuffer(GL_UNIFORM_BUFFER, (GLuint)s->ubo_generic); /* glBindBuffer{Base,Range} set it too */
    glBindImageTexture(0, (GLuint)s->image, s->image_level, (GLboolean)s->image_layered, s->image_layer,
                       (GLenum)s->image_access, (GLenum)s->image_format);
}

static ob_error run_view(ob_view_pass *v, const ob_view_inputs *in)
{
    if (!v->ready) {
        if (ob_compute_pass_init(&v->pass, "view.glsl", NULL, sizeof(ob_view_constants)) != OB_OK)
            return ob_peek_error(NULL);
        v->ready = true;
    }
    if (v->display && (v->width != in->width || v->height != in->height)) {
        glDeleteTextures(1, &v->display);
        v->display = 0;
    }
    if (!v->display) {
        v->display = ob_make_texture_2d(GL_RGBA8, in->width, in->height);
        v->width = in->width;
        v->height = in->height;
    }
    ob_view_constants k;
    memset(&k, 0, sizeof k);
    k.view_mode = (int)in->view;
    k.directional = in->directional ? 1 : 0;
    k.sample_count = in->samples;
    k.use_multiplier = in->multiplier ? 1 : 0;
    k.ao_k = in->grid_k > 0 ? in->grid_k : 1;
    k.far_z = in->far_z > 0.0f ? in->far_z : 1.0f;
    k.inv_max_samples = in->max_samples > 0 ? 1.0f / (float)in->max_samples : 0.0f;
    k.offset = in->offset;
    k.inv_history_frames = in->history_frames > 0 ? 1.0f / (float)in->history_frames : 0.0f;
    k.size[0] = in->width;
    k.size[1] = in->height;

    saved_state saved;
    memset(&saved, 0, sizeof saved);
    save_compute_state(&saved);
    ob_compute_pass_use(&v->pass, &k, sizeof k);
    const GLuint units[VIEW_UNITS] = {in->source, in->multiplier};
    for (int i = 0; i < VIEW_UNITS; ++i) {
        glActiveTexture(GL_TEXTURE0 + (GLenum)i);
        glBindTexture(GL_TEXTURE_2D, units[i]);
    }
    glBindImageTexture(0, v->display, 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA8);
    /* The frame's passes wrote their targets with image stores. */
    glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT | GL_SHADER_IMAGE_ACCESS_BARRIER_BIT);
    ob_dispatch_2d(in->width, in->height, OB_VIEW_GROUP_X, OB_VIEW_GROUP_Y);
    restore_compute_state(&saved);
    return OB_OK;
}

ob_error ob_view_render(ob_view_pass *v, const ob_view_inputs *in, GLuint *out)
{
    ob_error err = run_view(v, in);
    *out = err == OB_OK ? v->display : 0;
    return err;
}

ob_error ob_view_present(ob_view_pass *v, const ob_view_inputs *in, GLuint framebuffer, int x, int y, int w, int h)
{
    /* Errors raised before this call are not ours to report. */
    int drained = 0;
    while (drained++ < 64 && glGetError() != GL_NO_ERROR) continue; /* bounded: a lost context repeats */
    GLuint src = in->source;
    if (in->view != OB_VIEW_FINAL) {
        ob_error err = run_view(v, in);
        if (err != OB_OK) return err;
        src = v->display;
    }
    if (!v->read_fbo) glCreateFramebuffers(1, &v->read_fbo);
    glNamedFramebufferTexture(v->read_fbo, GL_COLOR_ATTACHMENT0, src, 0);
    glNamedFramebufferReadBuffer(v->read_fbo, GL_COLOR_ATTACHMENT0);
    /* The blit reads what the image stores (tone map or view pass) wrote. */
    glMemoryBarrier(GL_FRAMEBUFFER_BARRIER_BIT | GL_TEXTURE_UPDATE_BARRIER_BIT);
    /* The bytes are sRGB already: an sRGB-capable window with GL_FRAMEBUFFER_SRGB on would
     * encode them twice. A blit also obeys the scissor box, which a GUI may have left set. */
    GLboolean srgb = glIsEnabled(GL_FRAMEBUFFER_SRGB), scissor = glIsEnabled(GL_SCISSOR_TEST);
    if (srgb) glDisable(GL_FRAMEBUFFER_SRGB);
    if (scissor) glDisable(GL_SCISSOR_TEST);
    glBlitNamedFramebuffer(v->read_fbo, framebuffer, 0, 0, in->width, in->height, x, y, x + w, y + h,
                           GL_COLOR_BUFFER_BIT, GL_NEAREST);
    GLenum e = glGetError();
    if (srgb) glEnable(GL_FRAMEBUFFER_SRGB);
    if (scissor) glEnable(GL_SCISSOR_TEST);
    /* Detached, so a later resize can free the texture at once. */
    glNamedFramebufferTexture(v->read_fbo, GL_COLOR_ATTACHMENT0, 0, 0);
    if (e != GL_NO_ERROR)
        return ob_set_error(OB_ERR_GL, "OpenGL error 0x%x presenting the %s view into framebuffer %u", e,
                            ob_view_name(in->view), framebuffer);
    return OB_OK;
}

void ob_view_destroy(ob_view_pass *v)
{
    ob_compute_pass_destroy(&v->pass);
    if (v->display) glDeleteTextures(1, &v->display);
    if (v->read_fbo) glDeleteFramebuffers(1, &v->read_fbo);
    memset(v, 0, sizeof *v);
}

const char *ob_view_name(ob_view view)
{
    static const char *const names[OB_VIEW_COUNT] = {"final",    "ao",      "normals", "depth",
                                                     "shadow",   "radiance", "samples", "bounce",
                                                     "bent_normals", "luminance", "second_depth", "extra",
                                                     "history_age"};
    return (int)view >= 0 && view < OB_VIEW_COUNT ? names[view] : "";
}
