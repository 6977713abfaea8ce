/* Test helper: decode a PNG (stb_image) or PFM (libobscura) and print
 * "WIDTH HEIGHT CHANNELS MIN MAX MEAN" (PNG values in 0..255, PFM values as stored).
 * Two more forms for PNGs (the viewer's screenshots):
 *   imgcheck region X Y W H FILE.png   "MIN MAX MEAN STDDEV" of the rectangle (x right, y down)
 *   imgcheck diff A.png B.png          the mean absolute difference per channel value (0..255)
 * Exit 1 if a file does not decode, 2 on bad usage (including a rectangle outside the image or
 * images of different sizes). */
#include <math.h>
#include <stb/stb_image.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "obscura/eval.h"

static int region(int argc, char **argv)
{
    if (argc != 7) return 2;
    int x0 = atoi(argv[2]), y0 = atoi(argv[3]), rw = atoi(argv[4]), rh = atoi(argv[5]);
    int w = 0, h = 0, c = 0;
    unsigned char *px = stbi_load(argv[6], &w, &h, &c, 0);
    if (!px) {
        fprintf(stderr, "imgcheck: %s: %s\n", argv[6], stbi_failure_reason());
        return 1;
    }
    if (x0 < 0 || y0 < 0 || rw < 1 || rh < 1 || x0 + rw > w || y0 + rh > h) {
        fprintf(stderr, "imgcheck: rectangle %d,%d %dx%d is outside the %dx%d image\n", x0, y0, rw, rh, w, h);
        stbi_image_free(px);
        return 2;
    }
    double lo = 1e300, hi = -1e300, sum = 0.0, sum2 = 0.0;
    size_t n = 0;
    for (int y = y0; y < y0 + rh; ++y)
        for (int x = x0; x < x0 + rw; ++x)
            for (int k = 0; k < (c == 4 ? 3 : c); ++k) { /* colour only: alpha says nothing here */
                double v = px[((size_t)y * (size_t)w + (size_t)x) * (size_t)c + (size_t)k];
                lo = v < lo ? v : lo;
                hi = v > hi ? v : hi;
                sum += v;
                sum2 += v * v;
                ++n;
            }
    double mean = sum / (double)n, var = sum2 / (double)n - mean * mean;
    printf("%.0f %.0f %.4f %.4f\n", lo, hi, mean, var > 0.0 ? sqrt(var) : 0.0);
    stbi_image_free(px);
    return 0;
}

static int diff(int argc, char **argv)
{
    if (argc != 4) return 2;
    int w[2] = {0, 0}, h[2] = {0, 0}, c[2] = {0, 0};
    unsigned char *px[2] = {NULL, NULL};
    for (int i = 0; i < 2; ++i) {
        px[i] = stbi_load(argv[2 + i], &w[i], &h[i], &c[i], 0);
        if (!px[i]) {
            fprintf(stderr, "imgcheck: %s: %s\n", argv[2 + i], stbi_failure_reason());
            stbi_image_free(px[0]);
            return 1;
        }
    }
    int code = 0;
    if (w[0] != w[1] || h[0] != h[1] || c[0] != c[1]) {
        fprintf(stderr, "imgcheck: %dx%dx%d and %dx%dx%d differ in size\n", w[0], h[0], c[0], w[1], h[1], c[1]);
        code = 2;
    } else {
        size_t n = (size_t)w[0] * (size_t)h[0] * (size_t)c[0];
        double sum = 0.0;
        for (size_t i = 0; i < n; ++i) sum += fabs((double)px[0][i] - (double)px[1][i]);
        printf("%.4f\n", sum / (double)n);
    }
    stbi_image_free(px[0]);
    stbi_image_free(px[1]);
    return code;
}

int main(int argc, char **argv)
{
    if (argc >= 2 && !strcmp(argv[1], "region")) return region(argc, argv);
    if (argc >= 2 && !strcmp(argv[1], "diff")) return diff(argc, argv);
    if (argc != 2) {
        fprintf(stderr, "usage: imgcheck FILE.png|FILE.pfm\n");
        return 2;
    }
    const char *path = argv[1];
    size_t len = strlen(path);
    double lo = 1e300, hi = -1e300, sum = 0.0;
    int w = 0, h = 0, c = 0;
    if (len > 4 && !strcmp(path + len - 4, ".pfm")) {
        float *px = NULL;
        if (ob_read_pfm(path, &w, &h, &c, &px) != OB_OK) {
            const char *msg = NULL;
            ob_get_error(&msg);
            fprintf(stderr, "imgcheck: %s\n", msg);
            return 1;
        }
        size_t n = (size_t)w * (size_t)h * (size_t)c;
        for (size_t i = 0; i < n; ++i) {
            lo = px[i] < lo ? px[i] : lo;
            hi = px[i] > hi ? px[i] : hi;
            sum += px[i];
        }
        printf("%d %d %d %.6f %.6f %.6f\n", w, h, c, lo, hi, sum / (double)n);
        free(px);
        return 0;
    }
    unsigned char *px = stbi_load(path, &w, &h, &c, 0);
    if (!px) {
        fprintf(stderr, "imgcheck: %s: %s\n", path, stbi_failure_reason());
        return 1;
    }
    size_t n = (size_t)w * (size_t)h * (size_t)c;
    for (size_t i = 0; i < n; ++i) {
        lo = px[i] < lo ? px[i] : lo;
        hi = px[i] > hi ? px[i] : hi;
        sum += px[i];
    }
    printf("%d %d %d %.0f %.0f %.4f\n", w, h, c, lo, hi, sum / (double)n);
    stbi_image_free(px);
    return 0;
}
