/* The environment map: equirectangular radiance for the background, SSDO's incoming radiance and,
 * through nine spherical harmonics, the diffuse ambient (Ramamoorthi & Hanrahan 2001, "An
 * Efficient Representation for Irradiance Environment Maps"). */
#include <math.h>
#include <stdbool.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "base/error.h"
#include "passes/passes.h"

#define OB_PI 3.14159265358979323846

void ob_environment_sh(const float *rgb, int w, int h, float out[9][3])
{
    double acc[9][3];
    memset(acc, 0, sizeof acc);
    for (int j = 0; j < h; ++j) {
        /* Row 0 is the top (+Y); the same mapping as ob_environment_radiance in compose.glsl. */
        double theta = ((double)j + 0.5) / (double)h * OB_PI;
        double st = sin(theta), ct = cos(theta);
        double d_omega = (2.0 * OB_PI / (double)w) * (OB_PI / (double)h) * st;
        for (int i = 0; i < w; ++i) {
            double phi = (((double)i + 0.5) / (double)w - 0.5) * 2.0 * OB_PI;
            double x = st * sin(phi), y = ct, z = -st * cos(phi);
            /* The real SH basis, l <= 2, in the order the shader evaluates it. */
            const double basis[9] = {0.282095,           0.488603 * y,      0.488603 * z,
                                     0.488603 * x,       1.092548 * x * y,  1.092548 * y * z,
                                     0.315392 * (3.0 * z * z - 1.0), 1.092548 * x * z, 0.546274 * (x * x - y * y)};
            const float *px = rgb + 3 * ((size_t)j * (size_t)w + (size_t)i);
            for (int k = 0; k < 9; ++k)
                for (int c = 0; c < 3; ++c) acc[k][c] += (double)px[c] * basis[k] * d_omega;
        }
    }
    /* E = sum A_l L_lm Y_lm with A = (pi, 2pi/3, pi/4) (eq. 8); the shader adds the basis's
     * polynomials, so fold the Y constants in here, and divide by pi: Lambert's radiance factor. */
    const double a[9] = {OB_PI, 2.0 * OB_PI / 3.0, 2.0 * OB_PI / 3.0, 2.0 * OB_PI / 3.0, OB_PI / 4.0,
                         OB_PI / 4.0, OB_PI / 4.0, OB_PI / 4.0, OB_PI / 4.0};
    const double y[9] = {0.282095, 0.488603, 0.488603, 0.488603, 1.092548, 1.092548, 0.315392, 1.092548, 0.546274};
    for (int k = 0; k < 9; ++k)
        for (int c = 0; c < 3; ++c) out[k][c] = (float)(a[k] * acc[k][c] * y[k] / OB_PI);
}

ob_error ob_environment_upload(ob_environment *e, const float *rgb, int w, int h, const char *what)
{
    if (!e || !rgb || !what) return ob_set_error(OB_ERR_INVALID_ARGUMENT, "ob_environment_upload: NULL argument");
    GLint max_texture = 0;
    glGetIntegerv(GL_MAX_TEXTURE_SIZE, &max_texture);
    if (max_texture <= 0) max_texture = 16384; /* no answer: GL 4.5's minimum is 16384 */
    if (w < 2 || h < 1) return ob_set_error(OB_ERR_IO, "environment map %s is %dx%d: too small", what, w, h);
    if (w > max_texture || h > max_texture)
        return ob_set_error(OB_ERR_IO, "environment map %s is %dx%d, larger than this GPU's largest texture (%d): scale it down",
                            what, w, h, max_texture);
    for (size_t i = 0; i < (size_t)w * (size_t)h * 3; ++i)
        if (!isfinite(rgb[i]) || rgb[i] < 0.0f)
            return ob_set_error(OB_ERR_IO, "environment map %s holds negative or non-finite radiance", what);
    ob_environment_destroy(e);
    ob_environment_sh(rgb, w, h, e->sh);
    ob_gl_drop_pending(); /* an earlier call's error is not this upload's */
    int levels = 1;
    for (int s = w > h ? w : h; s > 1; s >>= 1) ++levels;
    glCreateTextures(GL_TEXTURE_2D, 1, &e->texture);
    glTextureStorage2D(e->texture, levels, GL_RGBA16F, w, h);
    glPixelStorei(GL_UNPACK_ALIGNMENT, 4);
    glTextureSubImage2D(e->texture, 0, 0, 0, w, h, GL_RGB, GL_FLOAT, rgb);
    glGenerateTextureMipmap(e->texture);
    glTextureParameteri(e->texture, GL_TEXTURE_MIN_FILTER, GL_LINEAR_MIPMAP_LINEAR);
    glTextureParameteri(e->texture, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    glTextureParameteri(e->texture, GL_TEXTURE_WRAP_S, GL_REPEAT);
    glTextureParameteri(e->texture, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    /* Out of video memory is the one failure left: say so rather than sample an empty texture. */
    GLenum gl = glGetError();
    if (gl != GL_NO_ERROR) {
        ob_environment_destroy(e);
        return ob_set_error(OB_ERR_IO, "environment map %s (%dx%d) could not be uploaded: GL error 0x%04x", what, w, h, gl);
    }
    return OB_OK;
}

void ob_environment_destroy(ob_environment *e)
{
    if (e->texture) glDeleteTextures(1, &e->texture);
    memset(e, 0, sizeof *e);
}
