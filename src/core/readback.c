/* The last frame back to the CPU: every image kind of ob_read_image (the G-buffer, the direct
 * light, the AO before and after filtering, a directional method's M and bounce, the sample
 * counts) and the per-pass timings. */
#include <stdlib.h>
#include <string.h>

#include "base/error.h"
#include "core/renderer.h"

/* The visible frame of a target with the guard band (renderer.h): its rows from (guard, guard), the
 * visible size. Every read-back goes through here, so no caller ever sees the band. */
static void read_visible(const ob_renderer *r, GLuint tex, GLenum format, GLenum type, size_t bytes, void *dst)
{
    glGetTextureSubImage(tex, 0, r->guard, r->guard, 0, r->width, r->height, 1, format, type, (GLsizei)bytes, dst);
}

/* Per-pixel sample counts of the last frame at full resolution: the method's count, or under
 * adaptive sampling its base x the edge pass's multiplier. */
static ob_error read_sample_counts(ob_renderer *r, float *dst)
{
    const ao_targets *t = &r->scales[r->last.scale];
    if (!t->ready) return ob_set_error(OB_ERR_INVALID_ARGUMENT, "no frame rendered yet");
    const ob_method_impl *m = ob_method_impl_at(r->last.method);
    int samples = ob_method_samples(m, r->last.params);
    int bw = (t->grid.width + OB_EDGE_BLOCK - 1) / OB_EDGE_BLOCK, bh = (t->grid.height + OB_EDGE_BLOCK - 1) / OB_EDGE_BLOCK;
    float *mult = NULL;
    float *depth = malloc((size_t)r->width * (size_t)r->height * sizeof(float));
    if (!depth) return ob_set_error(OB_ERR_OUT_OF_MEMORY, "out of memory reading sample counts");
    read_visible(r, r->gbuffer.linear_depth, GL_RED, GL_FLOAT, (size_t)r->width * (size_t)r->height * sizeof(float),
                 depth);
    if (r->last.adaptive && m->adapts) {
        mult = malloc((size_t)bw * (size_t)bh * sizeof(float));
        if (!mult) {
            free(depth);
            return ob_set_error(OB_ERR_OUT_OF_MEMORY, "out of memory reading sample counts");
        }
        glGetTextureImage(t->multiplier, 0, GL_RED, GL_FLOAT, (GLsizei)((size_t)bw * (size_t)bh * sizeof(float)), mult);
    }
    for (int y = 0; y < r->height; ++y)
        for (int x = 0; x < r->width; ++x) {
            /* The multiplier's blocks cover the AO grid with the guard band. */
            int bx = ((x + r->guard) / t->grid.k) / OB_EDGE_BLOCK, by = ((y + r->guard) / t->grid.k) / OB_EDGE_BLOCK;
            size_t i = (size_t)y * (size_t)r->width + (size_t)x;
            float count = (float)samples;
            if (mult) count = (float)ob_adaptive_base(samples) * mult[(size_t)by * (size_t)bw + (size_t)bx];
            dst[i] = depth[i] > 0.0f ? count : 0.0f; /* the sky takes no samples */
        }
    free(mult);
    free(depth);
    return OB_OK;
}

/* The w x h pixels from (x0, y0) of an RGBA16F target as 3 floats per pixel, or (channels 1) the
 * average of its three channels: the AO views of a directional method show M's mean. */
static ob_error read_rgb(GLuint tex, int x0, int y0, int w, int h, float *dst, int channels)
{
    size_t n = (size_t)w * (size_t)h;
    float *rgba = malloc(n * 4 * sizeof(float));
    if (!rgba) return ob_set_error(OB_ERR_OUT_OF_MEMORY, "out of memory reading an image");
    glGetTextureSubImage(tex, 0, x0, y0, 0, w, h, 1, GL_RGBA, GL_FLOAT, (GLsizei)(n * 4 * sizeof(float)), rgba);
    for (size_t i = 0; i < n; ++i) {
        if (channels == 1) {
            dst[i] = (rgba[4 * i] + rgba[4 * i + 1] + rgba[4 * i + 2]) / 3.0f;
        } else {
            for (int c = 0; c < 3; ++c) dst[3 * i + (size_t)c] = rgba[4 * i + (size_t)c];
        }
    }
    free(rgba);
    GLenum e = glGetError();
    if (e != GL_NO_ERROR) return ob_set_error(OB_ERR_GL, "OpenGL error 0x%x reading an image", e);
    return OB_OK;
}

size_t ob_image_size(const ob_renderer *r, ob_image_kind kind)
{
    if (!r) return 0;
    size_t px = (size_t)r->width * (size_t)r->height;
    switch (kind) {
    case OB_IMAGE_FINAL_RGBA8: return px * 4;
    case OB_IMAGE_AO_RAW_F32: {
        /* The AO grid of the visible frame: the guard band is a multiple of k (ob_guard_pixels). */
        const ob_ao_grid *g = &r->scales[r->last.scale].grid;
        const ob_ao_grid v = ob_ao_grid_make(r->width, r->height, g->k > 0 ? g->k : 1);
        return (size_t)v.width * (size_t)v.height * sizeof(float);
    }
    case OB_IMAGE_SAMPLES_F32:
    case OB_IMAGE_AO_F32:
    case OB_IMAGE_DEPTH_F32: return px * sizeof(float);
    case OB_IMAGE_NORMAL_F32:
    case OB_IMAGE_RADIANCE_F32:
    case OB_IMAGE_AO_RGB_F32:
    case OB_IMAGE_BOUNCE_F32:
    case OB_IMAGE_BENT_NORMAL_F32:
    case OB_IMAGE_HDR_F32:
    case OB_IMAGE_ALBEDO_F32:
    case OB_IMAGE_EXTRA_RADIANCE_F32: return px * 3 * sizeof(float);
    case OB_IMAGE_SHADOW_F32:
    case OB_IMAGE_SECOND_DEPTH_F32: return px * sizeof(float);
    case OB_IMAGE_HISTORY_AGE_F32:
    case OB_IMAGE_MOTION_F32: {
        const ob_ao_grid *g = &r->scales[r->last.scale].grid;
        const ob_ao_grid v = ob_ao_grid_make(r->width, r->height, g->k > 0 ? g->k : 1);
        return (size_t)v.width * (size_t)v.height * sizeof(float) * (kind == OB_IMAGE_MOTION_F32 ? 2 : 1);
    }
    }
    return 0;
}

ob_error ob_read_image(ob_renderer *r, ob_image_kind kind, void *dst, size_t dst_size)
{
    size_t need = ob_image_size(r, kind);
    if (!r || !dst || need == 0) return ob_set_error(OB_ERR_INVALID_ARGUMENT, "ob_read_image: bad argument");
    if (dst_size < need) return ob_set_error(OB_ERR_INVALID_ARGUMENT, "ob_read_image: buffer of %zu bytes, need %zu", dst_size, need);
    ob_gl_drop_pending(); /* the reads are checked with glGetError */
    /* The targets hold a whole frame only after a frame that finished: not after a resize, a
     * failure half-way, or a host call, which overwrites some of them and writes its results
     * into the host's textures. */
    /* After a host call only the AO grid's own images are the call's (the motion's when its depth
     * went through the input pass into the G-buffer's target, which the read-back reprojects). */
    const bool grid_kind = kind == OB_IMAGE_AO_RAW_F32 || kind == OB_IMAGE_HISTORY_AGE_F32 ||
                           (kind == OB_IMAGE_MOTION_F32 && r->host_depth_in_gbuffer);
    if (!r->has_frame && !(r->has_host_chain && grid_kind))
        return ob_set_error(OB_ERR_INVALID_ARGUMENT, "ob_read_image: no frame to read (none rendered yet, or not since a "
                                                     "resize or a failed frame; after ob_host_ao only the raw AO, the "
                                                     "history age and, with a depth buffer, the motion)");
    glPixelStorei(GL_PACK_ALIGNMENT, 1);
    switch (kind) {
    case OB_IMAGE_FINAL_RGBA8: {
        /* final and radiance are the visible frame already (compose crops). */
        glGetTextureImage(r->final, 0, GL_RGBA, GL_UNSIGNED_BYTE, (GLsizei)need, dst);
        /* GL's rows run bottom to top; image files want top first. */
        size_t row = (size_t)r->width * 4;
        unsigned char *p = dst;
        unsigned char *tmp = malloc(row);
        if (!tmp) return ob_set_error(OB_ERR_OUT_OF_MEMORY, "out of memory reading the image");
        for (int y = 0; y < r->height / 2; ++y) {
            unsigned char *a = p + (size_t)y * row, *b = p + (size_t)(r->height - 1 - y) * row;
            memcpy(tmp, a, row);
            memcpy(a, b, row);
            memcpy(b, tmp, row);
        }
        free(tmp);
        break;
    }
    case OB_IMAGE_AO_F32:
        if (r->last.rgb) return read_rgb(r->ao_rgb, r->guard, r->guard, r->width, r->height, dst, 1);
        read_visible(r, r->ao, GL_RED, GL_FLOAT, need, dst);
        break;
    case OB_IMAGE_AO_RAW_F32: {
        const ao_targets *t = &r->scales[r->last.scale];
        if (!t->ready) return ob_set_error(OB_ERR_INVALID_ARGUMENT, "no frame rendered yet");
        /* AO pixel i of the visible grid is pixel i + guard / k of the enlarged one. */
        const ob_ao_grid v = ob_ao_grid_make(r->width, r->height, t->grid.k);
        const int o = r->guard / t->grid.k;
        if (r->last.rgb) return read_rgb(t->raw_rgb, o, o, v.width, v.height, dst, 1);
        glGetTextureSubImage(t->raw, 0, o, o, 0, v.width, v.height, 1, GL_RED, GL_FLOAT, (GLsizei)need, dst);
        break;
    }
    case OB_IMAGE_AO_RGB_F32:
        if (r->last.rgb) return read_rgb(r->ao_rgb, r->guard, r->guard, r->width, r->height, dst, 3);
        /* An AO method: its visibility in all three channels. */
        read_visible(r, r->ao, GL_RED, GL_FLOAT, need / 3, dst);
        for (size_t i = need / sizeof(float) / 3; i-- > 0;) {
            float v = ((float *)dst)[i];
            for (int c = 0; c < 3; ++c) ((float *)dst)[3 * i + (size_t)c] = v;
        }
        break;
    case OB_IMAGE_BOUNCE_F32:
        if (r->last.bounce) return read_rgb(r->bounce, r->guard, r->guard, r->width, r->height, dst, 3);
        memset(dst, 0, need);
        break;
    case OB_IMAGE_BENT_NORMAL_F32:
        if (r->last.bent) return read_rgb(r->bent, r->guard, r->guard, r->width, r->height, dst, 3);
        memset(dst, 0, need);
        break;
    case OB_IMAGE_SAMPLES_F32: {
        ob_error e = read_sample_counts(r, dst);
        if (e != OB_OK) return e;
        break;
    }
    case OB_IMAGE_DEPTH_F32: read_visible(r, r->gbuffer.linear_depth, GL_RED, GL_FLOAT, need, dst); break;
    case OB_IMAGE_NORMAL_F32: read_visible(r, r->gbuffer.normal, GL_RGB, GL_FLOAT, need, dst); break;
    case OB_IMAGE_RADIANCE_F32: read_visible(r, r->direct, GL_RGB, GL_FLOAT, need, dst); break;
    case OB_IMAGE_HDR_F32: glGetTextureImage(r->radiance, 0, GL_RGB, GL_FLOAT, (GLsizei)need, dst); break;
    case OB_IMAGE_ALBEDO_F32: read_visible(r, r->gbuffer.albedo, GL_RGB, GL_FLOAT, need, dst); break;
    case OB_IMAGE_EXTRA_RADIANCE_F32:
    case OB_IMAGE_SECOND_DEPTH_F32: {
        bool extra = kind == OB_IMAGE_EXTRA_RADIANCE_F32;
        GLuint tex = extra ? ob_renderer_extra_direct(r) : ob_renderer_second_layer(r);
        if (tex) read_visible(r, tex, extra ? GL_RGB : GL_RED, GL_FLOAT, need, dst);
        else memset(dst, 0, need);
        break;
    }
    case OB_IMAGE_HISTORY_AGE_F32:
    case OB_IMAGE_MOTION_F32: {
        const ao_targets *t = &r->scales[r->last.scale];
        if (!t->ready) return ob_set_error(OB_ERR_INVALID_ARGUMENT, "no frame rendered yet");
        if (!r->last.temporal || !t->temporal_ready) {
            memset(dst, 0, need);
            break;
        }
        /* The visible AO grid, as OB_IMAGE_AO_RAW_F32. The age is the R16F age texture (one value)
         * or the RGBA16F history's .a (core GL reads no .a alone, so through RGBA). */
        const ob_ao_grid v = ob_ao_grid_make(r->width, r->height, t->grid.k);
        const int o = r->guard / t->grid.k;
        if (kind == OB_IMAGE_MOTION_F32) {
            /* Made here: the accumulation writes no motion (passes.h). The frame block is the last
             * frame's (the frame binds it last, but a host may have bound its own since). */
            glBindBufferBase(GL_UNIFORM_BUFFER, OB_BINDING_FRAME, r->frame_ubo);
            ob_error e = ob_temporal_motion(&r->temporal, &t->grid, t->depth, t->motion);
            if (e != OB_OK) return e;
            glMemoryBarrier(GL_TEXTURE_UPDATE_BARRIER_BIT);
            glGetTextureSubImage(t->motion, 0, o, o, 0, v.width, v.height, 1, GL_RG, GL_FLOAT, (GLsizei)need, dst);
            break;
        }
        if (!r->last.rgb) {
            glGetTextureSubImage(t->history_age[t->history_index], 0, o, o, 0, v.width, v.height, 1, GL_RED, GL_FLOAT,
                                 (GLsizei)need, dst);
            break;
        }
        size_t n = (size_t)v.width * (size_t)v.height;
        float *rgba = malloc(n * 4 * sizeof(float));
        if (!rgba) return ob_set_error(OB_ERR_OUT_OF_MEMORY, "out of memory reading an image");
        glGetTextureSubImage(t->history_rgb[t->history_index], 0, o, o, 0, v.width, v.height, 1, GL_RGBA, GL_FLOAT,
                             (GLsizei)(n * 4 * sizeof(float)), rgba);
        float *out = dst;
        for (size_t i = 0; i < n; ++i) out[i] = rgba[4 * i + 3];
        free(rgba);
        break;
    }
    case OB_IMAGE_SHADOW_F32: {
        /* The key light's visibility is the direct-light target's alpha. */
        size_t n = (size_t)r->width * (size_t)r->height;
        float *rgba = malloc(n * 4 * sizeof(float));
        if (!rgba) return ob_set_error(OB_ERR_OUT_OF_MEMORY, "out of memory reading the shadow view");
        read_visible(r, r->direct, GL_RGBA, GL_FLOAT, n * 4 * sizeof(float), rgba);
        for (size_t i = 0; i < n; ++i) ((float *)dst)[i] = rgba[4 * i + 3];
        free(rgba);
        break;
    }
    }
    GLenum e = glGetError();
    if (e != GL_NO_ERROR) return ob_set_error(OB_ERR_GL, "OpenGL error 0x%x reading an image", e);
    return OB_OK;
}

int ob_query_timings(ob_renderer *r, ob_pass_timing *out, int max)
{
    if (!r || !out || max <= 0) return 0;
    int n = r->timers.count < max ? r->timers.count : max;
    for (int i = 0; i < n; ++i) {
        out[i].name = r->timers.names[i];
        out[i].ms = r->timers.ms[i];
        out[i].cpu_ms = r->timers.cpu_ms[i];
    }
    return n;
}

void ob_query_timings_frame(const ob_renderer *r, long long *timed, long long *rendered)
{
    if (timed) *timed = r ? r->timers.frame : -1;
    if (rendered) *rendered = r ? r->timers.frames - 1 : -1;
}

ob_error ob_wait_timings(ob_renderer *r)
{
    if (!r) return ob_set_error(OB_ERR_INVALID_ARGUMENT, "ob_wait_timings: NULL renderer");
    ob_gl_drop_pending();
    ob_timers_wait(&r->timers);
    GLenum e = glGetError();
    if (e != GL_NO_ERROR) return ob_set_error(OB_ERR_GL, "OpenGL error 0x%x reading the timer queries", e);
    return OB_OK;
}
