/* ob_present: the last frame, or one of its debug views mapped to display bytes by
 * shaders/view.glsl, blitted into the caller's framebuffer. Runs inside a caller's render loop
 * (the viewer's window), so everything it binds is put back as it was. */
#include <string.h>

#include "base/error.h"
#include "passes/passes.h"
#include "view_params.h"

enum { VIEW_UNITS = OB_UNIT_VIEW_MULTIPLIER + 1 }; /* texture units view.glsl samples: 0 and 1 */

/* The compute pass changes what ob_gl_state covers (gpu.h) on VIEW_UNITS texture units and image
 * unit 0; the blit itself binds nothing (DSA) and only obeys the scissor test and
 * GL_FRAMEBUFFER_SRGB among the fragment operations. */

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

    ob_gl_state saved;
    memset(&saved, 0, sizeof saved);
    ob_gl_state_save(&saved, VIEW_UNITS, 1);
    ob_compute_pass_use(&v->pass, &k, sizeof k);
    /* glBindTexture on the unit, not glBindTextureUnit: a 0 (no multiplier) must not unbind the
     * caller's textures of other targets there. */
    const GLuint units[2] = {OB_UNIT_VIEW_SOURCE, OB_UNIT_VIEW_MULTIPLIER};
    const GLuint textures[2] = {in->source, in->multiplier};
    for (int i = 0; i < 2; ++i) {
        glActiveTexture(GL_TEXTURE0 + units[i]);
        glBindTexture(GL_TEXTURE_2D, textures[i]);
    }
    glBindImageTexture(OB_IMAGE_UNIT_OUT, v->display, 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA8);
    /* The frame's passes wrote their targets with image stores. */
    glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT | GL_SHADER_IMAGE_ACCESS_BARRIER_BIT);
    ob_dispatch_2d(in->width, in->height, OB_VIEW_GROUP_X, OB_VIEW_GROUP_Y);
    ob_gl_state_restore(&saved);
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
    ob_gl_drop_pending(); /* errors raised before this call are not ours to report */
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
