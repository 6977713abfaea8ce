/* HDR tone mapping, SSDO thesis §2.2 and §5.5, with the automatic key of §6.5: drives the luminance,
 * bloom and tone-map passes (no shader of its own), and holds the CPU versions of their formulas
 * (obscura.h) that the tests hold the shaders to.
 *
 *   radiance -> luminance: L_avg (eq. 2.1) and alpha -> GPU buffer (exposure alpha / L_avg)
 *            -> bloom: excess over the threshold at 1/4 resolution, Gaussian x then y
 *            -> tonemap: scale (eq. 2.2) + bloom, Reinhard (eq. 2.4), sRGB -> final RGBA8
 *
 * Exposure is a compensation on top of the key: the log-average is of the radiance as given, and
 * the tone map scales by exposure alpha / L_avg. Measuring L_avg after the exposure would cancel
 * it (eq. 2.2 divides it out again), leaving exposure a knob that only matters with HDR off. */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "base/error.h"
#include "hdr_shared.h"
#include "passes/passes.h"

double ob_hdr_log_average(const float *luminance, size_t n)
{
    if (!luminance || n == 0) return 0.0;
    /* Eq. 2.1 less delta afterwards, as shaders/luminance.glsl: a constant image averages to
     * itself. Non-finite or negative values are clamped as ob_hdr_sanitize does on the GPU. */
    double sum = 0.0;
    for (size_t i = 0; i < n; ++i) {
        double l = luminance[i];
        if (isnan(l)) l = 0.0;
        l = l < 0.0 ? 0.0 : (l > 65504.0 ? 65504.0 : l);
        sum += log(OB_HDR_DELTA + l);
    }
    double avg = exp(sum / (double)n) - OB_HDR_DELTA;
    return avg > 0.0 ? avg : 0.0;
}

float ob_hdr_reinhard(float scaled_luminance, float l_white)
{
    float l = scaled_luminance > 0.0f ? scaled_luminance : 0.0f;
    /* Eq. 2.4: L_d = L (1 + L / L_white^2) / (1 + L), exactly 1 at L = L_white; eq. 2.3 when
     * l_white <= 0. */
    float burn = l_white > 0.0f ? 1.0f + l / (l_white * l_white) : 1.0f;
    return l * burn / (1.0f + l);
}

float ob_hdr_auto_key(float log_average)
{
    /* Krawczyk, Myszkowski, Seidel 2005, eq. 11 (SSDO thesis §6.5 gives no formula), with radiance
     * 1 taken as 100 cd/m^2 (shaders/hdr_shared.h): rises from 0.03 for black through 0.53 at
     * L_avg = 1. */
    float l = log_average > 0.0f ? log_average * (float)OB_HDR_NITS_PER_UNIT : 0.0f;
    return 1.03f - 2.0f / (2.0f + log10f(l + 1.0f));
}

ob_error ob_hdr_init(ob_hdr_pass *h, int width, int height)
{
    if (!h) return ob_set_error(OB_ERR_INVALID_ARGUMENT, "ob_hdr_init: NULL pass");
    memset(h, 0, sizeof *h);
    if (width <= 0 || height <= 0) return ob_set_error(OB_ERR_BAD_SIZE, "ob_hdr_init: size %dx%d", width, height);
    h->width = width;
    h->height = height;
    ob_error err = ob_luminance_init(&h->luminance, width, height);
    if (err == OB_OK) err = ob_bloom_init(&h->bloom, width, height);
    if (err == OB_OK) err = ob_tonemap_init(&h->tonemap);
    if (err != OB_OK) {
        ob_hdr_destroy(h);
        return err;
    }
    GLenum e = glGetError();
    if (e != GL_NO_ERROR) {
        ob_hdr_destroy(h);
        return ob_set_error(OB_ERR_GL, "OpenGL error 0x%x making the %dx%d HDR targets", e, width, height);
    }
    return OB_OK;
}

ob_error ob_hdr_resize(ob_hdr_pass *h, int width, int height)
{
    if (!h) return ob_set_error(OB_ERR_INVALID_ARGUMENT, "ob_hdr_resize: NULL pass");
    if (width <= 0 || height <= 0) return ob_set_error(OB_ERR_BAD_SIZE, "ob_hdr_resize: size %dx%d", width, height);
    int old_w = h->width, old_h = h->height;
    ob_error err = ob_luminance_resize(&h->luminance, width, height);
    if (err != OB_OK) return err;
    err = ob_bloom_resize(&h->bloom, width, height);
    if (err != OB_OK) {
        /* Keep the pass whole at its old size; the bloom error is the one to report. */
        const char *msg = NULL;
        ob_peek_error(&msg);
        char keep[1024] = "";
        snprintf(keep, sizeof keep, "%s", msg);
        ob_luminance_resize(&h->luminance, old_w, old_h);
        return ob_set_error(err, "%s", keep);
    }
    h->width = width;
    h->height = height;
    return OB_OK;
}

void ob_hdr_run(ob_hdr_pass *h, GLuint radiance, const ob_hdr_settings *s, GLuint final, ob_timer_set *timers)
{
    if (!h || !s || !radiance || !final) return;
    const GLbitfield images = GL_TEXTURE_FETCH_BARRIER_BIT | GL_SHADER_IMAGE_ACCESS_BARRIER_BIT;
    /* The radiance was most likely written with imageStore by the compose pass. */
    glMemoryBarrier(images);
    bool bloom = s->enabled && s->bloom_strength > 0.0f;
    if (s->enabled) {
        if (timers) ob_timer_begin(timers, "luminance");
        ob_luminance_run(&h->luminance, radiance, s->exposure, s->key);
        /* Bloom's bright pass and the tone map read the scale the reduction just stored. */
        glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
    } else {
        /* Nothing to measure with HDR off; ob_hdr_query then reads 0s, not a stale frame's values. */
        glClearNamedBufferSubData(h->luminance.result, GL_R32F, 0, OB_HDR_RESULT_BYTES, GL_RED, GL_FLOAT, NULL);
    }
    if (bloom) {
        if (timers) ob_timer_begin(timers, "bloom");
        ob_bloom_run(&h->bloom, radiance, h->luminance.result, s->bloom_threshold);
        glMemoryBarrier(images);
    }
    if (timers) ob_timer_begin(timers, "tonemap");
    const ob_tonemap_inputs in = {
        .radiance = radiance,
        .result = h->luminance.result,
        .bloom = bloom ? h->bloom.bloom : 0,
        .width = h->width,
        .height = h->height,
        .bloom_width = h->bloom.bloom_width,
        .bloom_height = h->bloom.bloom_height,
    };
    ob_tonemap_run(&h->tonemap, &in, s, final);
    if (timers) ob_timer_end(timers);
    glMemoryBarrier(images | GL_TEXTURE_UPDATE_BARRIER_BIT | GL_PIXEL_BUFFER_BARRIER_BIT);
}

void ob_hdr_query(ob_hdr_pass *h, float *log_average, float *key)
{
    float r[4] = {0.0f, 0.0f, 0.0f, 0.0f};
    if (h && h->luminance.result) {
        glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
        glGetNamedBufferSubData(h->luminance.result, 0, sizeof r, r);
    }
    if (log_average) *log_average = r[0];
    if (key) *key = r[1];
}

void ob_hdr_destroy(ob_hdr_pass *h)
{
    if (!h) return;
    ob_luminance_destroy(&h->luminance);
    ob_bloom_destroy(&h->bloom);
    ob_tonemap_destroy(&h->tonemap);
    memset(h, 0, sizeof *h);
}
