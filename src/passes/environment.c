/* The environment map: an equirectangular .hdr for the background, SSDO's incoming radiance and,
 * through nine spherical harmonics, the diffuse ambient (Ramamoorthi & Hanrahan 2001, "An
 * Efficient Representation for Irradiance Environment Maps"). */
#include <errno.h>
#include <math.h>
#include <stdbool.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include <stb/stb_image.h>

#include "base/error.h"
#include "io/file.h"
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

/* stb_image reads through these so that a decoder asking for bytes past the end is seen: stb
 * fills a truncated .hdr with zeros and returns it as whole. */
typedef struct env_reader {
    FILE *f;
    bool past_end; /* the decoder asked for more after the last byte */
} env_reader;

static int env_read(void *user, char *data, int size)
{
    env_reader *r = user;
    size_t n = fread(data, 1, (size_t)size, r->f);
    if (n == 0 && size > 0) r->past_end = true;
    return (int)n;
}

static void env_skip(void *user, int n)
{
    env_reader *r = user;
    if (fseek(r->f, n, SEEK_CUR) != 0) r->past_end = true;
}

static int env_eof(void *user)
{
    env_reader *r = user;
    return feof(r->f);
}

/* The dimensions a Radiance header declares, checked against the bytes after it before anything
 * is allocated (a 93-byte file claiming 10000x10000 took 2.3 GB). Each scanline is at least its
 * smaller encoding: flat (4 bytes a pixel) or run-length (4 bytes of header, then per channel one
 * 2-byte run per 127 pixels). */
static ob_error env_check_header(FILE *f, const char *path, long long size, int max_texture)
{
    char line[512] = "";
    /* Radiance alone, as documented (--env FILE.hdr): stb would also take a PNG, a JPEG or a PPM
     * as 8-bit sRGB and call it radiance. */
    if (!fgets(line, sizeof line, f) || strncmp(line, "#?", 2) != 0)
        return ob_set_error(OB_ERR_IO, "cannot read environment map %s: not a Radiance .hdr image (its first line is "
                            "not '#?RADIANCE' or '#?RGBE')", path);
    for (int k = 0; k < 256; ++k) {
        if (!fgets(line, sizeof line, f)) return ob_set_error(OB_ERR_IO, "environment map %s: Radiance header never ends (truncated)", path);
        if (line[0] == '\n') break;
    }
    char ya[3] = "", xa[3] = "";
    long long h = 0, w = 0;
    if (!fgets(line, sizeof line, f) || sscanf(line, "%2s %lld %2s %lld", ya, &h, xa, &w) != 4 || strcmp(ya, "-Y") != 0 ||
        strcmp(xa, "+X") != 0)
        return ob_set_error(OB_ERR_IO, "environment map %s: expected a '-Y HEIGHT +X WIDTH' line after the header", path);
    if (w < 2 || h < 1 || w > 1 << 24 || h > 1 << 24)
        return ob_set_error(OB_ERR_IO, "environment map %s: declared size %lldx%lld is out of range", path, w, h);
    if (w > max_texture || h > max_texture)
        return ob_set_error(OB_ERR_IO, "environment map %s is %lldx%lld, larger than this GPU's largest texture (%d): scale it down",
                            path, w, h, max_texture);
    long long at = ftell(f);
    long long flat = 4 * w, rle = 4 + 4 * 2 * ((w + 126) / 127);
    /* stb reads scanlines narrower than 8 or wider than 32767 flat only. */
    long long per_line = w < 8 || w > 32767 ? flat : (rle < flat ? rle : flat);
    if (at < 0 || size - at < per_line * h)
        return ob_set_error(OB_ERR_IO, "environment map %s declares %lldx%lld pixels, which need at least %lld bytes; the file holds %lld (truncated)",
                            path, w, h, per_line * h, at < 0 ? 0 : size - at);
    rewind(f);
    return OB_OK;
}

ob_error ob_environment_load(ob_environment *e, const char *path)
{
    if (!e || !path) return ob_set_error(OB_ERR_INVALID_ARGUMENT, "ob_environment_load: NULL argument");
    /* Checked on the open descriptor: a FIFO in the map's place fails at once (file.h). */
    FILE *f = ob_fopen_regular(path, "environment map");
    if (!f) return OB_ERR_IO;
    struct stat st = {0};
    if (fstat(fileno(f), &st) != 0) {
        fclose(f);
        return ob_set_error(OB_ERR_IO, "cannot read environment map %s: %s", path, strerror(errno));
    }
    GLint max_texture = 0;
    glGetIntegerv(GL_MAX_TEXTURE_SIZE, &max_texture);
    if (max_texture <= 0) max_texture = 16384; /* no answer: GL 4.5's minimum is 16384 */
    ob_error err = env_check_header(f, path, (long long)st.st_size, max_texture);
    if (err != OB_OK) {
        fclose(f);
        return err;
    }
    int w = 0, h = 0, n = 0;
    env_reader reader = {.f = f, .past_end = false};
    const stbi_io_callbacks io = {.read = env_read, .skip = env_skip, .eof = env_eof};
    float *rgb = stbi_loadf_from_callbacks(&io, &reader, &w, &h, &n, 3);
    fclose(f);
    if (!rgb)
        return ob_set_error(OB_ERR_IO, "cannot read environment map %s: %s; expected a Radiance .hdr image",
                            path, stbi_failure_reason());
    if (reader.past_end) {
        stbi_image_free(rgb);
        return ob_set_error(OB_ERR_IO, "environment map %s is truncated: its %dx%d pixels end before the file does", path, w, h);
    }
    if (w < 2 || h < 1) {
        stbi_image_free(rgb);
        return ob_set_error(OB_ERR_IO, "environment map %s is %dx%d: too small", path, w, h);
    }
    if (w > max_texture || h > max_texture) {
        stbi_image_free(rgb);
        return ob_set_error(OB_ERR_IO, "environment map %s is %dx%d, larger than this GPU's largest texture (%d): scale it down",
                            path, w, h, max_texture);
    }
    for (size_t i = 0; i < (size_t)w * (size_t)h * 3; ++i) {
        if (!isfinite(rgb[i]) || rgb[i] < 0.0f) {
            stbi_image_free(rgb);
            return ob_set_error(OB_ERR_IO, "environment map %s holds negative or non-finite radiance", path);
        }
    }
    ob_environment_destroy(e);
    ob_environment_sh(rgb, w, h, e->sh);
    while (glGetError() != GL_NO_ERROR) {
    } /* an earlier call's error is not this upload's */
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
    stbi_image_free(rgb);
    /* Out of video memory is the one failure left: say so rather than sample an empty texture. */
    GLenum gl = glGetError();
    if (gl != GL_NO_ERROR) {
        ob_environment_destroy(e);
        return ob_set_error(OB_ERR_IO, "environment map %s (%dx%d) could not be uploaded: GL error 0x%04x", path, w, h, gl);
    }
    snprintf(e->path, sizeof e->path, "%s", path);
    return OB_OK;
}

void ob_environment_destroy(ob_environment *e)
{
    if (e->texture) glDeleteTextures(1, &e->texture);
    memset(e, 0, sizeof *e);
}
