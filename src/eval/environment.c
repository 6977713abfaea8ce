/* The environment map from a Radiance .hdr file (stb_image), handed to the core's
 * ob_renderer_set_environment_rgb: the file is the evaluation library's business (the core takes
 * radiance from a host as floats), its checks before any byte is decoded are here. */
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
#include "obscura/eval.h"

/* The header check's bound before decoding; the core then holds the map to the GL's own
 * GL_MAX_TEXTURE_SIZE. 32768 is the largest any current GPU reports. */
#define OB_ENV_MAX_SIDE 32768

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
        return ob_set_error(OB_ERR_IO, "environment map %s is %lldx%lld, larger than any GPU's largest texture (%d): scale it down",
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

ob_error ob_renderer_set_environment(ob_renderer *r, const char *hdr_path)
{
    if (!r || !hdr_path) return ob_set_error(OB_ERR_INVALID_ARGUMENT, "ob_renderer_set_environment: NULL argument");
    const char *path = hdr_path;
    /* Checked on the open descriptor: a FIFO in the map's place fails at once (file.h). */
    FILE *f = ob_fopen_regular(path, "environment map");
    if (!f) return OB_ERR_IO;
    struct stat st = {0};
    if (fstat(fileno(f), &st) != 0) {
        fclose(f);
        return ob_set_error(OB_ERR_IO, "cannot read environment map %s: %s", path, strerror(errno));
    }
    ob_error err = env_check_header(f, path, (long long)st.st_size, OB_ENV_MAX_SIDE);
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
    /* The size and radiance checks are the core's, whose messages name the map by what it is
     * given: here the path. */
    err = ob_renderer_set_environment_rgb(r, w, h, rgb, path);
    stbi_image_free(rgb);
    return err;
}
