/* The floor (issue 18, docs/architecture.md "Performance method"): a bare N-tap compute kernel that bench
 * times beside each AO pass, so that "AO pass / floor" says how far a method is from the least any
 * method at N taps must cost on the machine at hand. shaders/floor.glsl says what the kernel does
 * and does not do; this file builds its tap table and dispatches it. */
#include <math.h>
#include <string.h>

#include "base/error.h"
#include "floor_params.h"
#include "passes/passes.h"

/* The 4x4 Bayer order: neighbouring pixels get far-apart rotations, as with the noise tile, so
 * that neighbours do not fetch the same texels (which would flatter the floor's cache hits). */
static const int BAYER[OB_FLOOR_ROTATIONS] = {0, 8, 2, 10, 12, 4, 14, 6, 3, 11, 1, 9, 15, 7, 13, 5};

ob_error ob_floor_fill(const ob_floor_desc *d, int width, int height, ob_floor_constants *c, float *table)
{
    if (!d || !c || !table) return ob_set_error(OB_ERR_INVALID_ARGUMENT, "ob_floor_fill: NULL");
    if (width <= 0 || height <= 0) return ob_set_error(OB_ERR_BAD_SIZE, "ob_floor_fill: size %dx%d", width, height);
    if (d->taps < 1 || d->taps > OB_FLOOR_MAX_TAPS)
        return ob_set_error(OB_ERR_INVALID_ARGUMENT, "floor: %d taps (1..%d)", d->taps, OB_FLOOR_MAX_TAPS);
    if (d->rays < 0 || (d->rays > 0 && d->taps % d->rays))
        return ob_set_error(OB_ERR_INVALID_ARGUMENT, "floor: %d taps do not make %d rays of equal steps", d->taps,
                            d->rays);
    if (!(d->radius > 0.0f) || !(d->px_per_unit > 0.0f) || !(d->max_radius_px >= 0.0f))
        return ob_set_error(OB_ERR_INVALID_ARGUMENT, "floor: radius %g, %g px per unit, clamp %g px",
                            (double)d->radius, (double)d->px_per_unit, (double)d->max_radius_px);
    memset(c, 0, sizeof *c);
    c->size[0] = width;
    c->size[1] = height;
    c->taps = d->taps;
    c->radius = d->radius;
    c->px_per_unit = d->px_per_unit;
    c->max_radius_px = d->max_radius_px > 0.0f ? d->max_radius_px : 1e30f;
    const double two_pi = 6.283185307179586;
    for (int t = 0; t < OB_FLOOR_ROTATIONS; ++t) {
        double a = two_pi * BAYER[t] / OB_FLOOR_ROTATIONS;
        c->rotation[t][0] = (float)cos(a);
        c->rotation[t][1] = (float)sin(a);
    }
    if (d->rays == 0) {
        /* A golden-angle spiral, sqrt-spaced so the taps cover the disk of R_px evenly (alchemy's
         * spiral; ssao's, crytek's and ssdo's projected kernels scatter over the same disk). */
        const double golden = 2.399963229728653;
        for (int i = 0; i < d->taps; ++i) {
            float *k = table + 4 * i;
            k[0] = (float)cos(golden * i);
            k[1] = (float)sin(golden * i);
            k[2] = 0.0f;
            k[3] = (float)sqrt((i + 0.5) / d->taps);
        }
    } else {
        /* D rays evenly over the circle, S steps each from 1.5 px to R_px (slice_march.glsl
         * ob_slice_step_px with the jitter at 1/2; gtao's and vbao's two sides of a slice are two
         * rays): distance 1.5 (1 - t) + t R_px, t = (j + 1/2) / S. */
        int steps = d->taps / d->rays;
        for (int ray = 0; ray < d->rays; ++ray)
            for (int j = 0; j < steps; ++j) {
                float *k = table + 4 * (ray * steps + j);
                double a = two_pi * ray / d->rays, t = (j + 0.5) / steps;
                k[0] = (float)cos(a);
                k[1] = (float)sin(a);
                k[2] = (float)(1.5 * (1.0 - t));
                k[3] = (float)t;
            }
    }
    return OB_OK;
}

ob_error ob_floor_init(ob_floor *f)
{
    if (!f) return ob_set_error(OB_ERR_INVALID_ARGUMENT, "ob_floor_init: NULL");
    memset(f, 0, sizeof *f);
    ob_error err = ob_compute_pass_init(&f->pass, "floor.glsl", NULL, sizeof(ob_floor_constants));
    if (err != OB_OK) return err;
    glCreateBuffers(1, &f->taps_buffer);
    glNamedBufferStorage(f->taps_buffer, (GLsizeiptr)(OB_FLOOR_MAX_TAPS * 4 * sizeof(float)), NULL,
                         GL_DYNAMIC_STORAGE_BIT);
    return OB_OK;
}

ob_error ob_floor_run(ob_floor *f, const ob_floor_desc *d, GLuint linear_depth, GLuint view_normal, int width,
                      int height)
{
    if (!f || !f->pass.program) return ob_set_error(OB_ERR_INVALID_ARGUMENT, "ob_floor_run: pass not initialised");
    if (!linear_depth || !view_normal) return ob_set_error(OB_ERR_INVALID_ARGUMENT, "ob_floor_run: no input texture");
    static float table[OB_FLOOR_MAX_TAPS * 4];
    ob_floor_constants c;
    ob_error err = ob_floor_fill(d, width, height, &c, table);
    if (err != OB_OK) return err;
    if (!f->texture || f->width != width || f->height != height) {
        GLuint tex = ob_make_texture_2d(GL_R32F, width, height);
        GLenum e = glGetError();
        if (!tex || e != GL_NO_ERROR) {
            if (tex) glDeleteTextures(1, &tex);
            return ob_set_error(OB_ERR_GL, "OpenGL error 0x%x making the %dx%d floor target", e, width, height);
        }
        if (f->texture) glDeleteTextures(1, &f->texture);
        f->texture = tex;
        f->width = width;
        f->height = height;
    }
    glNamedBufferSubData(f->taps_buffer, 0, (GLsizeiptr)((size_t)d->taps * 4 * sizeof(float)), table);
    ob_compute_pass_use(&f->pass, &c, sizeof c);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, OB_FLOOR_TAPS_BINDING, f->taps_buffer);
    glBindTextureUnit(OB_UNIT_DEPTH, linear_depth);
    glBindTextureUnit(OB_UNIT_NORMAL, view_normal);
    glBindImageTexture(OB_IMAGE_UNIT_OUT, f->texture, 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_R32F);
    ob_dispatch_2d(width, height, OB_FLOOR_GROUP_X, OB_FLOOR_GROUP_Y);
    glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT | GL_SHADER_IMAGE_ACCESS_BARRIER_BIT | GL_TEXTURE_UPDATE_BARRIER_BIT);
    return OB_OK;
}

void ob_floor_destroy(ob_floor *f)
{
    if (!f) return;
    ob_compute_pass_destroy(&f->pass);
    if (f->taps_buffer) glDeleteBuffers(1, &f->taps_buffer);
    if (f->texture) glDeleteTextures(1, &f->texture);
    memset(f, 0, sizeof *f);
}
