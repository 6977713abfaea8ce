/* Test helper: decode a PNG (stb_image) or PFM (libobscura) and print
 * "WIDTH HEIGHT CHANNELS MIN MAX MEAN" (PNG values in 0..255, PFM values as stored).
 * Exit 1 if the file does not decode. */
#include <stb/stb_image.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "obscura/obscura.h"

int main(int argc, char **argv)
{
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
