/* The last frame on the GPU: ob_present draws it, or one of its debug views, into the caller's
 * framebuffer; ob_read_view reads the same view back as display bytes (the CLI's --view). The
 * mapping itself is src/passes/view.c with shaders/view.glsl. */
#include <limits.h>
#include <string.h>

#include "base/error.h"
#include "core/renderer.h"

/* The inputs of the view pass for the last frame's `view` (ob_present, ob_read_view). */
static ob_error view_inputs(ob_renderer *r, ob_view view, const char *who, ob_view_inputs *in)
{
    if (!r) return ob_set_error(OB_ERR_INVALID_ARGUMENT, "%s: NULL renderer", who);
    if ((int)view < 0 || view >= OB_VIEW_COUNT)
        return ob_set_error(OB_ERR_INVALID_ARGUMENT, "%s: view %d is not one of the %d views", who, (int)view,
                            (int)OB_VIEW_COUNT);
    if (!r->has_frame)
        return ob_set_error(OB_ERR_INVALID_ARGUMENT, "%s: no frame rendered yet (or since the last resize)", who);
    const ao_targets *t = &r->scales[r->last.scale];
    memset(in, 0, sizeof *in);
    in->view = view;
    in->directional = r->last.rgb;
    in->width = r->width;
    in->height = r->height;
    in->far_z = r->last.far;
    in->offset = r->guard; /* every source but final and the composed radiance carries the band */
    in->grid_k = t->grid.k;
    switch (view) {
    case OB_VIEW_FINAL:
        in->source = r->final;
        in->offset = 0;
        break;
    case OB_VIEW_AO: in->source = r->last.rgb ? r->ao_rgb : r->ao; break;
    case OB_VIEW_NORMALS: in->source = r->gbuffer.normal; break;
    case OB_VIEW_DEPTH: in->source = r->gbuffer.linear_depth; break;
    case OB_VIEW_SHADOW:
    case OB_VIEW_RADIANCE: in->source = r->direct; break;
    case OB_VIEW_BOUNCE:
        /* The view pass shows black without one (directional = 0). */
        in->source = r->last.bounce ? r->bounce : r->gbuffer.linear_depth;
        in->directional = r->last.bounce;
        break;
    case OB_VIEW_BENT_NORMALS:
        /* The view pass shows black without one (directional = 0, as for the bounce). */
        in->source = r->last.bent ? r->bent : r->gbuffer.linear_depth;
        in->directional = r->last.bent;
        break;
    case OB_VIEW_LUMINANCE:
        in->source = r->radiance;
        in->offset = 0;
        break;
    /* Both at the G-buffer's (enlarged) size, so they carry the band like the main targets; the
     * view pass shows black without one (directional = 0). */
    case OB_VIEW_EXTRA: {
        GLuint extra = ob_renderer_extra_direct(r);
        in->source = extra ? extra : r->direct;
        in->directional = extra != 0;
        break;
    }
    case OB_VIEW_SECOND_DEPTH: {
        GLuint layer = ob_renderer_second_layer(r);
        in->source = layer ? layer : r->gbuffer.linear_depth;
        in->directional = layer != 0;
        break;
    }
    case OB_VIEW_SAMPLES: {
        /* The counts of read_sample_counts, over the most a pixel could take (multiplier <= 3). */
        in->source = r->gbuffer.linear_depth;
        const ob_method_impl *m = ob_method_impl_at(r->last.method);
        int samples = ob_method_samples(m, r->last.params);
        bool adaptive = r->last.adaptive && m->adapts;
        in->samples = adaptive ? ob_adaptive_base(samples) : samples;
        in->multiplier = adaptive ? t->multiplier : 0;
        in->max_samples = adaptive ? 3 * in->samples : samples;
        break;
    }
    case OB_VIEW_HISTORY_AGE:
        /* Black (no history frames) when the last frame did not accumulate. */
        if (r->last.temporal && t->temporal_ready) {
            in->source = r->last.rgb ? t->history_rgb[t->history_index] : t->history_age[t->history_index];
            in->history_frames = r->last.temporal_frames;
        } else {
            in->source = r->gbuffer.linear_depth;
        }
        in->offset = r->guard;
        break;
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
    ob_gl_drop_pending(); /* the read is checked with glGetError */
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
