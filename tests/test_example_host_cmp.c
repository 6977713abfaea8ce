/* tests/test_example_host.sh's comparison of two AO images (PFM, 1 channel, the same size):
 *   test_example_host_cmp TEST.pfm REFERENCE.pfm DEPTH.pfm MAX_MEAN MAX_P99 MAX_BIAS
 * over the pixels where either image is occluded (AO below 0.95) and DEPTH (the reference's
 * linear depth, 0 = sky) is geometry: the open floor, where both read 1, would water the mean
 * down. Prints
 *   "mean_abs M p99_abs P max_abs X bias B px N of T"
 * (bias = mean(test - reference): > 0 where the test is lighter; N occluded pixels of T geometry
 * pixels) and exits 0 when the mean absolute difference is at most MAX_MEAN, its 99th percentile
 * at most MAX_P99 and |bias| at most MAX_BIAS, 1 when not, 2 on bad usage or unreadable files. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "obscura/eval.h"

static int cmp_float(const void *a, const void *b)
{
    float x = *(const float *)a, y = *(const float *)b;
    return (x > y) - (x < y);
}

int main(int argc, char **argv)
{
    if (argc != 7) {
        fprintf(stderr, "usage: test_example_host_cmp TEST.pfm REFERENCE.pfm DEPTH.pfm MAX_MEAN MAX_P99 MAX_BIAS\n");
        return 2;
    }
    float *px[3] = {NULL, NULL, NULL};
    int w[3], h[3], c[3];
    for (int i = 0; i < 3; ++i) {
        if (ob_read_pfm(argv[1 + i], &w[i], &h[i], &c[i], &px[i]) != OB_OK) {
            const char *msg = "";
            ob_get_error(&msg);
            fprintf(stderr, "test_example_host_cmp: %s\n", msg);
            return 2;
        }
        if (c[i] != 1 || w[i] != w[0] || h[i] != h[0]) {
            fprintf(stderr, "test_example_host_cmp: %s is %dx%dx%d, expected %dx%dx1\n", argv[1 + i], w[i], h[i], c[i],
                    w[0], h[0]);
            return 2;
        }
    }
    size_t n = (size_t)w[0] * (size_t)h[0], count = 0, geometry = 0;
    float *diff = malloc(n * sizeof(float));
    if (!diff) return 2;
    double sum = 0.0, bias = 0.0, max = 0.0;
    for (size_t i = 0; i < n; ++i) {
        if (!(px[2][i] > 0.0f)) continue; /* sky in the reference */
        ++geometry;
        if (!(px[0][i] < 0.95f || px[1][i] < 0.95f)) continue; /* open in both (NaN counts as occluded) */
        double d = (double)px[0][i] - (double)px[1][i];
        if (isnan(d)) d = INFINITY; /* a NaN is as wrong as it gets */
        diff[count++] = (float)fabs(d);
        sum += fabs(d), bias += d, max = fabs(d) > max ? fabs(d) : max;
    }
    if (count == 0) {
        fprintf(stderr, "test_example_host_cmp: no occluded geometry pixel (%zu geometry pixels)\n", geometry);
        return 2;
    }
    qsort(diff, count, sizeof(float), cmp_float);
    double mean = sum / (double)count, p99 = diff[(size_t)(0.99 * (double)(count - 1))];
    double max_mean = atof(argv[4]), max_p99 = atof(argv[5]), max_bias = atof(argv[6]);
    bias /= (double)count;
    printf("mean_abs %.4f p99_abs %.4f max_abs %.4f bias %+.4f px %zu of %zu\n", mean, p99, max, bias, count, geometry);
    for (int i = 0; i < 3; ++i) free(px[i]);
    free(diff);
    return mean <= max_mean && p99 <= max_p99 && fabs(bias) <= max_bias ? 0 : 1;
}
