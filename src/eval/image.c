/* PNG, JPEG and PFM files, written atomically: a temporary file in the same directory, then rename, so
 * a failure never leaves a half-written output behind. */
#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include <stb/stb_image_write.h>

#include "base/error.h"
#include "obscura/eval.h"

typedef struct atomic_file {
    FILE *f;
    char tmp[4096];
    const char *path;
} atomic_file;

static ob_error atomic_open(atomic_file *a, const char *path)
{
    memset(a, 0, sizeof a[0]);
    if (!path || !*path) return ob_set_error(OB_ERR_INVALID_ARGUMENT, "empty output path");
    if (snprintf(a->tmp, sizeof a->tmp, "%s.tmp-XXXXXX", path) >= (int)sizeof a->tmp)
        return ob_set_error(OB_ERR_IO, "output path too long: %s", path);
    int fd = mkstemp(a->tmp);
    if (fd < 0) return ob_set_error(OB_ERR_IO, "cannot write %s: %s", path, strerror(errno));
    a->f = fdopen(fd, "wb");
    if (!a->f) {
        close(fd);
        unlink(a->tmp);
        return ob_set_error(OB_ERR_IO, "cannot write %s: %s", path, strerror(errno));
    }
    a->path = path;
    return OB_OK;
}

static ob_error atomic_close(atomic_file *a, bool ok)
{
    bool closed = fclose(a->f) == 0;
    if (!ok || !closed) {
        unlink(a->tmp);
        return ob_set_error(OB_ERR_IO, "cannot write %s: %s", a->path, closed ? "write failed" : strerror(errno));
    }
    /* mkstemp makes the file 0600; outputs are ordinary files. */
    mode_t mask = umask(0);
    umask(mask);
    chmod(a->tmp, 0666 & ~mask);
    if (rename(a->tmp, a->path) != 0) {
        int e = errno;
        unlink(a->tmp);
        return ob_set_error(OB_ERR_IO, "cannot write %s: %s", a->path, strerror(e));
    }
    return OB_OK;
}

static void write_to_file(void *ctx, void *data, int size)
{
    atomic_file *a = ctx;
    /* A short write sets the stream error flag, which atomic_close checks. */
    (void)fwrite(data, 1, (size_t)size, a->f);
}

ob_error ob_write_png(const char *path, int width, int height, int channels, const uint8_t *px)
{
    if (width <= 0 || height <= 0 || !px || (channels != 1 && channels != 3 && channels != 4))
        return ob_set_error(OB_ERR_INVALID_ARGUMENT, "ob_write_png: bad image");
    atomic_file a;
    ob_error err = atomic_open(&a, path);
    if (err != OB_OK) return err;
    int ok = stbi_write_png_to_func(write_to_file, &a, width, height, channels, px, width * channels);
    return atomic_close(&a, ok && !ferror(a.f));
}

ob_error ob_write_jpg(const char *path, int width, int height, int channels, const uint8_t *px, int quality)
{
    if (width <= 0 || height <= 0 || !px || (channels != 1 && channels != 3 && channels != 4))
        return ob_set_error(OB_ERR_INVALID_ARGUMENT, "ob_write_jpg: bad image");
    if (quality < 1 || quality > 100)
        return ob_set_error(OB_ERR_OUT_OF_RANGE, "ob_write_jpg: quality %d is outside 1..100", quality);
    atomic_file a;
    ob_error err = atomic_open(&a, path);
    if (err != OB_OK) return err;
    /* stb's baseline JPEG drops a fourth (alpha) channel itself: JPEG has none. */
    int ok = stbi_write_jpg_to_func(write_to_file, &a, width, height, channels, px, quality);
    return atomic_close(&a, ok && !ferror(a.f));
}

ob_error ob_write_pfm(const char *path, int width, int height, int channels, const float *px)
{
    if (width <= 0 || height <= 0 || !px || (channels != 1 && channels != 3))
        return ob_set_error(OB_ERR_INVALID_ARGUMENT, "ob_write_pfm: bad image");
    atomic_file a;
    ob_error err = atomic_open(&a, path);
    if (err != OB_OK) return err;
    /* Negative scale = little-endian (x86 and every GPU host we run on). */
    bool ok = fprintf(a.f, "%s\n%d %d\n-1.0\n", channels == 3 ? "PF" : "Pf", width, height) > 0;
    size_t n = (size_t)width * (size_t)height * (size_t)channels;
    ok = ok && fwrite(px, sizeof(float), n, a.f) == n;
    return atomic_close(&a, ok && !ferror(a.f));
}

ob_error ob_read_pfm(const char *path, int *width, int *height, int *channels, float **px)
{
    if (!path || !width || !height || !channels || !px) return ob_set_error(OB_ERR_INVALID_ARGUMENT, "ob_read_pfm: NULL argument");
    *px = NULL;
    FILE *f = fopen(path, "rb");
    if (!f) return ob_set_error(OB_ERR_IO, "cannot read %s: %s", path, strerror(errno));
    char magic[3] = {0};
    int w = 0, h = 0;
    double scale = 0.0;
    if (fscanf(f, "%2s %d %d %lf", magic, &w, &h, &scale) != 4 || fgetc(f) == EOF ||
        (strcmp(magic, "Pf") != 0 && strcmp(magic, "PF") != 0) || w <= 0 || h <= 0 || w > 65536 || h > 65536 ||
        scale >= 0.0 || !isfinite(scale)) {
        fclose(f);
        return ob_set_error(OB_ERR_IO, "%s is not a little-endian PFM image", path);
    }
    int c = magic[1] == 'F' ? 3 : 1;
    size_t n = (size_t)w * (size_t)h * (size_t)c;
    float *data = malloc(n * sizeof(float));
    if (!data) {
        fclose(f);
        return ob_set_error(OB_ERR_OUT_OF_MEMORY, "out of memory reading %s", path);
    }
    if (fread(data, sizeof(float), n, f) != n) {
        free(data);
        fclose(f);
        return ob_set_error(OB_ERR_IO, "%s is truncated", path);
    }
    fclose(f);
    *width = w;
    *height = h;
    *channels = c;
    *px = data;
    return OB_OK;
}

ob_error ob_write_text(const char *path, const char *text)
{
    if (!text) return ob_set_error(OB_ERR_INVALID_ARGUMENT, "ob_write_text: NULL text");
    atomic_file a;
    ob_error err = atomic_open(&a, path);
    if (err != OB_OK) return err;
    size_t n = strlen(text);
    bool ok = fwrite(text, 1, n, a.f) == n;
    return atomic_close(&a, ok && !ferror(a.f));
}
