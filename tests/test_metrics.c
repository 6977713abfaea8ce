/* CPU unit tests of the image-comparison metrics (src/eval/metrics.c): hand-computed RMSE, MAE,
 * bias and PSNR, SSIM against closed forms (Wang et al. 2004, eq. 13) and against a direct 2-D
 * window sum, masks, the error heatmap's colours and row order, the metric masks (occluded,
 * silhouette band, thin parts, border) on small depth buffers whose masks are known, and argument
 * checks. */
#include <math.h>
#include <stdbool.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "check.h"
#include "obscura/eval.h"

#define C1 (0.01 * 0.01)
#define C2 (0.03 * 0.03)

/* A reproducible pattern in [0, 1]: an LCG, so no test depends on the C library's rand(). */
static void fill_noise(float *px, size_t n, uint32_t seed)
{
    uint32_t s = seed;
    for (size_t i = 0; i < n; ++i) {
        s = s * 1664525u + 1013904223u;
        px[i] = (float)(s >> 8) / 16777216.0f;
    }
}

static void test_identical(void)
{
    float a[5 * 4 * 2] = {0.0f};
    fill_noise(a, 5 * 4 * 2, 1u);
    ob_metrics m;
    CHECK(ob_compare_images(a, a, NULL, 5, 4, 2, &m) == OB_OK, "identical compare");
    CHECK(m.rmse == 0.0 && m.mae == 0.0 && m.bias == 0.0, "identical: rmse %g mae %g bias %g", m.rmse, m.mae, m.bias);
    CHECK(isinf(m.psnr) && m.psnr > 0.0, "identical: psnr %g", m.psnr);
    CHECK_NEAR(m.ssim, 1.0, 1e-12, "identical ssim");
    CHECK(m.count == 20, "identical count %zu", m.count);
}

static void test_one_pixel_off(void)
{
    /* 4x4, one pixel off by 0.5: MSE = 0.25/16, RMSE = 0.125, MAE = 0.5/16, PSNR = 20 log10(8). */
    float ref[16] = {0.0f}, test[16] = {0.0f};
    for (int i = 0; i < 16; ++i) ref[i] = test[i] = 0.25f;
    test[5] = 0.75f;
    ob_metrics m;
    CHECK(ob_compare_images(test, ref, NULL, 4, 4, 1, &m) == OB_OK, "one pixel compare");
    CHECK_NEAR(m.rmse, 0.125, 1e-12, "rmse");
    CHECK_NEAR(m.mae, 0.03125, 1e-12, "mae");
    CHECK_NEAR(m.bias, 0.03125, 1e-12, "bias (test higher)");
    CHECK_NEAR(m.psnr, 20.0 * log10(1.0 / 0.125), 1e-9, "psnr");
    CHECK_NEAR(m.psnr, 18.0618, 1e-4, "psnr in dB");
    CHECK(m.ssim < 1.0 && m.ssim > 0.0, "ssim %g", m.ssim);
    CHECK(m.count == 16, "count %zu", m.count);
    /* The other way round the bias flips sign and nothing else changes. */
    ob_metrics r;
    CHECK(ob_compare_images(ref, test, NULL, 4, 4, 1, &r) == OB_OK, "swapped compare");
    CHECK_NEAR(r.bias, -0.03125, 1e-12, "bias (test lower)");
    CHECK_NEAR(r.rmse, m.rmse, 1e-15, "rmse symmetric");
    CHECK_NEAR(r.ssim, m.ssim, 1e-12, "ssim symmetric");

    /* Masks: without the odd pixel the images agree; with half the image, MSE = 0.25/8. */
    uint8_t mask[16] = {0};
    for (int i = 0; i < 16; ++i) mask[i] = 1;
    mask[5] = 0;
    CHECK(ob_compare_images(test, ref, mask, 4, 4, 1, &m) == OB_OK, "masked compare");
    CHECK(m.count == 15 && m.rmse == 0.0 && m.bias == 0.0 && isinf(m.psnr), "masked out: count %zu rmse %g",
          m.count, m.rmse);
    for (int i = 0; i < 16; ++i) mask[i] = i < 8;
    CHECK(ob_compare_images(test, ref, mask, 4, 4, 1, &m) == OB_OK, "half-mask compare");
    CHECK(m.count == 8, "half-mask count %zu", m.count);
    CHECK_NEAR(m.rmse, sqrt(0.25 / 8.0), 1e-12, "half-mask rmse");
    CHECK_NEAR(m.mae, 0.0625, 1e-12, "half-mask mae");
}

static void test_psnr_srgb(void)
{
    /* IEC 61966-2-1 values worked by hand: sRGB(0.25) = 0.537099, sRGB(0.75) = 0.880825. The 4x4
     * image with one pixel 0.25 -> 0.75: MSE = (0.880825 - 0.537099)^2 / 16, 21.3169 dB, where the
     * linear PSNR is 18.0618 dB. */
    float ref[16] = {0.0f}, test[16] = {0.0f};
    for (int i = 0; i < 16; ++i) ref[i] = test[i] = 0.25f;
    test[5] = 0.75f;
    ob_metrics m;
    CHECK(ob_compare_images(test, ref, NULL, 4, 4, 1, &m) == OB_OK, "srgb compare");
    CHECK_NEAR(m.psnr_srgb, 21.31694, 1e-4, "srgb psnr");
    CHECK_NEAR(m.psnr, 18.06180, 1e-4, "linear psnr unchanged");

    /* The linear segment below 0.0031308: 0.002 encodes to 12.92 x 0.002 = 0.02584, so against 0 the
     * MSE is 0.02584^2 and the PSNR 31.754 dB (the power branch would give 0.0242, 32.33 dB). */
    const float dark[1] = {0.002f}, black[1] = {0.0f};
    CHECK(ob_compare_images(dark, black, NULL, 1, 1, 1, &m) == OB_OK, "dark compare");
    CHECK_NEAR(m.psnr_srgb, -20.0 * log10(12.92 * (double)0.002f), 1e-9, "linear-segment psnr");
    CHECK_NEAR(m.psnr_srgb, 31.754, 1e-3, "linear-segment psnr in dB");

    /* Values are clamped to [0, 1] before encoding: 1.5 against 1 is no sRGB error, while the linear
     * PSNR still sees 0.5; -0.5 against 0 likewise. */
    const float over[2] = {1.5f, -0.5f}, top[2] = {1.0f, 0.0f};
    CHECK(ob_compare_images(over, top, NULL, 2, 1, 1, &m) == OB_OK, "clamp compare");
    CHECK(isinf(m.psnr_srgb) && m.psnr_srgb > 0.0, "clamped srgb psnr %g", m.psnr_srgb);
    CHECK_NEAR(m.psnr, 20.0 * log10(2.0), 1e-9, "unclamped linear psnr");

    /* Identical images: +inf; a NaN: NaN. */
    CHECK(ob_compare_images(ref, ref, NULL, 4, 4, 1, &m) == OB_OK && isinf(m.psnr_srgb), "identical srgb psnr");
    const float nan_px[1] = {NAN};
    CHECK(ob_compare_images(nan_px, black, NULL, 1, 1, 1, &m) == OB_OK && isnan(m.psnr_srgb), "NaN srgb psnr %g",
          m.psnr_srgb);
}

static void test_channels(void)
{
    /* 2x2x3 with one value off by 0.3: the means run over all 12 values, count is 4 pixels. */
    float ref[12] = {0.0f}, test[12] = {0.0f};
    for (int i = 0; i < 12; ++i) ref[i] = test[i] = 0.5f;
    test[4] = 0.2f;
    ob_metrics m;
    CHECK(ob_compare_images(test, ref, NULL, 2, 2, 3, &m) == OB_OK, "rgb compare");
    CHECK(m.count == 4, "rgb count %zu", m.count);
    CHECK_NEAR(m.rmse, sqrt(0.09 / 12.0), 1e-7, "rgb rmse");
    CHECK_NEAR(m.bias, -0.3 / 12.0, 1e-7, "rgb bias");
}

static void test_ssim_closed_forms(void)
{
    enum { W = 24, H = 20, N = W * H };
    float *x = calloc(N, sizeof(float));
    float *y = calloc(N, sizeof(float));
    ob_metrics m;

    /* Constant images: sigma = 0, so eq. 13 is the luminance term alone, at every window. */
    for (int i = 0; i < N; ++i) {
        x[i] = 0.3f;
        y[i] = 0.7f;
    }
    double mx = (double)0.3f, my = (double)0.7f;
    double want = (2.0 * mx * my + C1) / (mx * mx + my * my + C1);
    CHECK(ob_compare_images(x, y, NULL, W, H, 1, &m) == OB_OK, "constant compare");
    CHECK_NEAR(m.ssim, want, 1e-9, "constant-image ssim");
    CHECK_NEAR(m.bias, mx - my, 1e-7, "constant-image bias");

    /* A constant offset: bias = offset, SSIM < 1 (the luminance term) but still high. */
    fill_noise(x, N, 7u);
    for (int i = 0; i < N; ++i) {
        x[i] = 0.25f + 0.5f * x[i];
        y[i] = x[i] + 0.1f;
    }
    CHECK(ob_compare_images(y, x, NULL, W, H, 1, &m) == OB_OK, "offset compare");
    CHECK_NEAR(m.bias, 0.1, 1e-6, "offset bias");
    CHECK_NEAR(m.rmse, 0.1, 1e-6, "offset rmse");
    CHECK(m.ssim < 0.999 && m.ssim > 0.9, "offset ssim %g", m.ssim);

    /* An image against its inverse: the structure term is -1, so SSIM is strongly negative. */
    fill_noise(x, N, 11u);
    for (int i = 0; i < N; ++i) y[i] = 1.0f - x[i];
    CHECK(ob_compare_images(x, y, NULL, W, H, 1, &m) == OB_OK, "inverse compare");
    CHECK(m.ssim < 0.1, "inverse ssim %g", m.ssim);

    /* Symmetry: SSIM(x, y) = SSIM(y, x) for unrelated images. */
    fill_noise(y, N, 13u);
    ob_metrics a, b;
    CHECK(ob_compare_images(x, y, NULL, W, H, 1, &a) == OB_OK && ob_compare_images(y, x, NULL, W, H, 1, &b) == OB_OK,
          "symmetry compares");
    CHECK_NEAR(a.ssim, b.ssim, 1e-12, "ssim symmetric");
    CHECK_NEAR(a.bias, -b.bias, 1e-15, "bias antisymmetric");

    /* The mask picks windows: a difference in one corner does not reach a window centred more
     * than 5 pixels away, so that window alone gives SSIM 1 while the full image does not. */
    fill_noise(x, N, 17u);
    memcpy(y, x, N * sizeof(float));
    y[0] = 1.0f - y[0];
    uint8_t *mask = calloc(N, 1);
    mask[(H - 1) * W + (W - 1)] = 1;
    CHECK(ob_compare_images(x, y, NULL, W, H, 1, &a) == OB_OK && a.ssim < 1.0, "corner change: ssim %g", a.ssim);
    CHECK(ob_compare_images(x, y, mask, W, H, 1, &b) == OB_OK, "one-window compare");
    CHECK(b.count == 1 && b.ssim == 1.0 && b.rmse == 0.0, "far window: count %zu ssim %.17g", b.count, b.ssim);
    /* ... while a window centred 5 pixels away does see it (its centre's error is still 0). */
    mask[(H - 1) * W + (W - 1)] = 0;
    mask[5 * W + 0] = 1;
    CHECK(ob_compare_images(x, y, mask, W, H, 1, &b) == OB_OK && b.ssim < 1.0 && b.rmse == 0.0,
          "near window: ssim %g", b.ssim);
    free(mask);
    free(x);
    free(y);
}

/* Local SSIM at (px, py) straight from eqs. 13-16: the 2-D window cut at the border and
 * renormalised, as the header documents. */
static double direct_ssim(const float *x, const float *y, int w, int h, int ch, int c, int px, int py)
{
    double s[5] = {0.0, 0.0, 0.0, 0.0, 0.0}, wsum = 0.0;
    for (int dy = -5; dy <= 5; ++dy) {
        for (int dx = -5; dx <= 5; ++dx) {
            int qx = px + dx, qy = py + dy;
            if (qx < 0 || qy < 0 || qx >= w || qy >= h) continue;
            double wt = exp(-(double)(dx * dx + dy * dy) / (2.0 * 1.5 * 1.5));
            size_t i = ((size_t)qy * (size_t)w + (size_t)qx) * (size_t)ch + (size_t)c;
            double a = x[i], b = y[i];
            s[0] += wt * a;
            s[1] += wt * b;
            s[2] += wt * a * a;
            s[3] += wt * b * b;
            s[4] += wt * a * b;
            wsum += wt;
        }
    }
    double mx = s[0] / wsum, my = s[1] / wsum;
    double vx = 0.0, vy = 0.0, cxy = 0.0;
    for (int dy = -5; dy <= 5; ++dy) {
        for (int dx = -5; dx <= 5; ++dx) {
            int qx = px + dx, qy = py + dy;
            if (qx < 0 || qy < 0 || qx >= w || qy >= h) continue;
            double wt = exp(-(double)(dx * dx + dy * dy) / (2.0 * 1.5 * 1.5)) / wsum;
            size_t i = ((size_t)qy * (size_t)w + (size_t)qx) * (size_t)ch + (size_t)c;
            vx += wt * (x[i] - mx) * (x[i] - mx);
            vy += wt * (y[i] - my) * (y[i] - my);
            cxy += wt * (x[i] - mx) * (y[i] - my);
        }
    }
    return (2.0 * mx * my + C1) * (2.0 * cxy + C2) / ((mx * mx + my * my + C1) * (vx + vy + C2));
}

static void test_ssim_against_direct(void)
{
    /* Odd sizes smaller and larger than the window, two channels, a sparse mask: the separable
     * ring-buffer implementation must match the direct 2-D sum everywhere, borders included. */
    const int sizes[3][2] = {{13, 9}, {4, 17}, {3, 3}};
    for (int k = 0; k < 3; ++k) {
        int w = sizes[k][0], h = sizes[k][1], ch = 2;
        size_t n = (size_t)w * (size_t)h;
        float *x = calloc(n * (size_t)ch, sizeof(float));
        float *y = calloc(n * (size_t)ch, sizeof(float));
        uint8_t *mask = calloc(n, 1);
        fill_noise(x, n * (size_t)ch, 100u + (uint32_t)k);
        fill_noise(y, n * (size_t)ch, 200u + (uint32_t)k);
        /* Make y partly like x so the index is not near 0 everywhere. */
        for (size_t i = 0; i < n * (size_t)ch; ++i) y[i] = 0.7f * x[i] + 0.3f * y[i];
        double want = 0.0;
        size_t in = 0;
        for (int py = 0; py < h; ++py) {
            for (int px = 0; px < w; ++px) {
                size_t p = (size_t)py * (size_t)w + (size_t)px;
                mask[p] = (uint8_t)((px + 2 * py) % 3 != 0);
                if (!mask[p]) continue;
                ++in;
                for (int c = 0; c < ch; ++c) want += direct_ssim(x, y, w, h, ch, c, px, py);
            }
        }
        want /= (double)in * (double)ch;
        ob_metrics m;
        CHECK(ob_compare_images(x, y, mask, w, h, ch, &m) == OB_OK, "%dx%d compare", w, h);
        CHECK(m.count == in, "%dx%d count %zu vs %zu", w, h, m.count, in);
        CHECK_NEAR(m.ssim, want, 1e-10, "ssim vs direct window sum");
        free(x);
        free(y);
        free(mask);
    }
}

static void test_heatmap(void)
{
    /* 3x2, bottom row first: bottom row = {0, +0.2, -0.2}, top row = {masked, +1 (saturates), -5}. */
    const float ref[6] = {0.5f, 0.5f, 0.5f, 0.5f, 0.0f, 1.0f};
    const float test[6] = {0.5f, 0.7f, 0.3f, 0.9f, 1.0f, 0.0f};
    const uint8_t mask[6] = {1, 1, 1, 0, 1, 1};
    uint8_t rgb[6 * 3];
    memset(rgb, 7, sizeof rgb);
    CHECK(ob_error_heatmap(test, ref, mask, 3, 2, true, 0.5f, rgb) == OB_OK, "heatmap");
    /* Output is top row first, so the bottom input row lands in output row 1. */
    const uint8_t *zero = rgb + (1 * 3 + 0) * 3, *pos = rgb + (1 * 3 + 1) * 3, *neg = rgb + (1 * 3 + 2) * 3;
    const uint8_t *grey = rgb + 0, *sat_pos = rgb + 3, *sat_neg = rgb + 6;
    CHECK(zero[0] == 255 && zero[1] == 255 && zero[2] == 255, "zero error white: %d %d %d", zero[0], zero[1], zero[2]);
    CHECK(grey[0] == 128 && grey[1] == 128 && grey[2] == 128, "masked grey: %d %d %d", grey[0], grey[1], grey[2]);
    CHECK(pos[0] > pos[2] + 30 && pos[0] >= pos[1], "positive red-dominant: %d %d %d", pos[0], pos[1], pos[2]);
    CHECK(neg[2] > neg[0] + 30 && neg[2] >= neg[1], "negative blue-dominant: %d %d %d", neg[0], neg[1], neg[2]);
    CHECK(sat_pos[0] == 103 && sat_pos[1] == 0 && sat_pos[2] == 31, "+range saturates: %d %d %d", sat_pos[0],
          sat_pos[1], sat_pos[2]);
    CHECK(sat_neg[0] == 5 && sat_neg[1] == 48 && sat_neg[2] == 97, "-range saturates: %d %d %d", sat_neg[0],
          sat_neg[1], sat_neg[2]);
    /* Symmetric magnitudes: +0.2 is paler than +0.5 (saturated), i.e. more green. */
    CHECK(pos[1] > sat_pos[1] && neg[1] > sat_neg[1], "colour deepens with the error");

    /* Top row first in, same out; no mask = every pixel coloured. */
    CHECK(ob_error_heatmap(test, ref, NULL, 3, 2, false, 0.5f, rgb) == OB_OK, "heatmap top-first");
    CHECK(rgb[0] == 255 && rgb[1] == 255 && rgb[2] == 255, "top-first: first pixel white");
    CHECK(rgb[9] > rgb[11], "top-first: pixel (0,1) red-dominant");

    /* A NaN difference is black, off the map. */
    const float nan_test[1] = {NAN};
    const float half[1] = {0.5f};
    CHECK(ob_error_heatmap(nan_test, half, NULL, 1, 1, false, 1.0f, rgb) == OB_OK && rgb[0] == 0 && rgb[1] == 0 &&
              rgb[2] == 0,
          "nan black");
}

static void test_bad_arguments(void)
{
    float a[4] = {0.0f, 0.25f, 0.5f, 1.0f};
    uint8_t none[4] = {0, 0, 0, 0};
    uint8_t rgb[12];
    ob_metrics m;
    m.count = 99;
    CHECK(ob_compare_images(NULL, a, NULL, 2, 2, 1, &m) == OB_ERR_INVALID_ARGUMENT && m.count == 0, "NULL test");
    CHECK(ob_compare_images(a, NULL, NULL, 2, 2, 1, &m) == OB_ERR_INVALID_ARGUMENT, "NULL reference");
    CHECK(ob_compare_images(a, a, NULL, 2, 2, 1, NULL) == OB_ERR_INVALID_ARGUMENT, "NULL out");
    CHECK(ob_compare_images(a, a, NULL, 0, 2, 1, &m) == OB_ERR_INVALID_ARGUMENT, "zero width");
    CHECK(ob_compare_images(a, a, NULL, 2, -1, 1, &m) == OB_ERR_INVALID_ARGUMENT, "negative height");
    CHECK(ob_compare_images(a, a, NULL, 2, 2, 0, &m) == OB_ERR_INVALID_ARGUMENT, "zero channels");
    CHECK(ob_compare_images(a, a, NULL, 1 << 30, 1 << 30, 1, &m) == OB_ERR_INVALID_ARGUMENT, "huge image");
    CHECK(ob_compare_images(a, a, none, 2, 2, 1, &m) == OB_ERR_INVALID_ARGUMENT, "empty mask");
    const char *msg = NULL;
    CHECK(ob_get_error(&msg) == OB_ERR_INVALID_ARGUMENT && msg && strstr(msg, "mask"), "message names the mask: %s",
          msg ? msg : "(null)");
    CHECK(ob_error_heatmap(NULL, a, NULL, 2, 2, false, 1.0f, rgb) == OB_ERR_INVALID_ARGUMENT, "heatmap NULL test");
    CHECK(ob_error_heatmap(a, NULL, NULL, 2, 2, false, 1.0f, rgb) == OB_ERR_INVALID_ARGUMENT, "heatmap NULL ref");
    CHECK(ob_error_heatmap(a, a, NULL, 2, 2, false, 1.0f, NULL) == OB_ERR_INVALID_ARGUMENT, "heatmap NULL out");
    CHECK(ob_error_heatmap(a, a, NULL, 0, 2, false, 1.0f, rgb) == OB_ERR_INVALID_ARGUMENT, "heatmap zero width");
    CHECK(ob_error_heatmap(a, a, NULL, 2, 2, false, 0.0f, rgb) == OB_ERR_INVALID_ARGUMENT, "heatmap zero range");
    CHECK(ob_error_heatmap(a, a, NULL, 2, 2, false, -1.0f, rgb) == OB_ERR_INVALID_ARGUMENT, "heatmap negative range");
    CHECK(ob_error_heatmap(a, a, NULL, 2, 2, false, NAN, rgb) == OB_ERR_INVALID_ARGUMENT, "heatmap NaN range");
    CHECK(ob_error_heatmap(a, a, NULL, 2, 2, false, INFINITY, rgb) == OB_ERR_INVALID_ARGUMENT, "heatmap inf range");
}

/* ---- metric masks (src/eval/masks.c) ----------------------------------------------------------- */

static const uint8_t *plane(const uint8_t *masks, int w, int h, ob_metric_mask m)
{
    return masks + (size_t)m * (size_t)w * (size_t)h;
}

static size_t plane_count(const uint8_t *masks, int w, int h, ob_metric_mask m)
{
    size_t n = 0;
    for (size_t i = 0; i < (size_t)w * (size_t)h; ++i) n += plane(masks, w, h, m)[i] != 0;
    return n;
}

static void fill_depth(float *depth, int w, int x0, int x1, int y0, int y1, float z)
{
    for (int y = y0; y <= y1; ++y)
        for (int x = x0; x <= x1; ++x) depth[y * w + x] = z;
}

static void test_mask_defaults(void)
{
    ob_metric_mask_desc d = ob_metric_mask_defaults(NULL, 320);
    CHECK(d.occluded_below == 0.75f && d.edge_relative == 0.1f && d.border_fraction == 0.05f,
          "320: %g %g %g", (double)d.occluded_below, (double)d.edge_relative, (double)d.border_fraction);
    CHECK(d.edge_band == 2 && d.thin_reach == 3, "320: band %d reach %d", d.edge_band, d.thin_reach);
    d = ob_metric_mask_defaults(NULL, 640);
    CHECK(d.edge_band == 4 && d.thin_reach == 6, "640: band %d reach %d", d.edge_band, d.thin_reach);
    /* Never below one pixel: 64 wide would round the band to 0. */
    d = ob_metric_mask_defaults(NULL, 64);
    CHECK(d.edge_band == 1 && d.thin_reach == 1, "64: band %d reach %d", d.edge_band, d.thin_reach);
    /* Only the zeros are replaced. */
    d = ob_metric_mask_defaults(&(ob_metric_mask_desc){.edge_band = 7, .occluded_below = 0.5f}, 320);
    CHECK(d.edge_band == 7 && d.occluded_below == 0.5f && d.thin_reach == 3, "given: band %d below %g reach %d",
          d.edge_band, (double)d.occluded_below, d.thin_reach);
    CHECK(!strcmp(ob_metric_mask_name(OB_MASK_OCCLUDED), "occluded") &&
              !strcmp(ob_metric_mask_name(OB_MASK_SILHOUETTE), "silhouette") &&
              !strcmp(ob_metric_mask_name(OB_MASK_THIN), "thin") && !strcmp(ob_metric_mask_name(OB_MASK_BORDER), "border"),
          "mask names");
    CHECK(!strcmp(ob_metric_mask_name(OB_MASK_COUNT), "") && !strcmp(ob_metric_mask_name((ob_metric_mask)-1), ""),
          "out-of-range mask names");
}

static void test_mask_flat(void)
{
    /* A flat wall at depth 2 seen head-on, 40x20: no edge and nothing thin; the occluded pixels are
     * exactly those under 0.75 (0.75 itself is not); the border is 2 columns (5 % of 40) on the
     * left and right and 1 row (5 % of 20) at the bottom and top: 800 - 36 x 18 = 152 pixels. */
    enum { W = 40, H = 20, N = W * H };
    float depth[N], ref[N];
    uint8_t masks[N * OB_MASK_COUNT];
    for (int i = 0; i < N; ++i) {
        depth[i] = 2.0f;
        ref[i] = 1.0f;
    }
    ref[5 * W + 5] = 0.5f;
    ref[6 * W + 30] = 0.7499f;
    ref[7 * W + 20] = 0.75f;
    ref[0] = 0.0f;
    memset(masks, 9, sizeof masks);
    CHECK(ob_metric_masks(depth, ref, W, H, 0.5f, NULL, masks) == OB_OK, "flat masks");
    const uint8_t *occ = plane(masks, W, H, OB_MASK_OCCLUDED), *bor = plane(masks, W, H, OB_MASK_BORDER);
    CHECK(plane_count(masks, W, H, OB_MASK_OCCLUDED) == 3, "flat: %zu occluded", plane_count(masks, W, H, OB_MASK_OCCLUDED));
    CHECK(occ[5 * W + 5] == 1 && occ[6 * W + 30] == 1 && occ[0] == 1 && occ[7 * W + 20] == 0, "flat: which occluded");
    CHECK(plane_count(masks, W, H, OB_MASK_SILHOUETTE) == 0, "flat: %zu silhouette",
          plane_count(masks, W, H, OB_MASK_SILHOUETTE));
    CHECK(plane_count(masks, W, H, OB_MASK_THIN) == 0, "flat: %zu thin", plane_count(masks, W, H, OB_MASK_THIN));
    CHECK(plane_count(masks, W, H, OB_MASK_BORDER) == 152, "flat: %zu border", plane_count(masks, W, H, OB_MASK_BORDER));
    CHECK(bor[1 * W + 1] == 1 && bor[1 * W + 2] == 0 && bor[1 * W + 37] == 0 && bor[1 * W + 38] == 1,
          "flat: border columns");
    CHECK(bor[0 * W + 10] == 1 && bor[1 * W + 10] == 0 && bor[18 * W + 10] == 0 && bor[19 * W + 10] == 1,
          "flat: border rows");

    /* The threshold and the border width follow the desc. */
    CHECK(ob_metric_masks(depth, ref, W, H, 0.5f, &(ob_metric_mask_desc){.occluded_below = 0.8f, .border_fraction = 0.1f},
                          masks) == OB_OK,
          "flat masks, desc");
    CHECK(plane_count(masks, W, H, OB_MASK_OCCLUDED) == 4, "flat 0.8: %zu occluded", plane_count(masks, W, H, OB_MASK_OCCLUDED));
    CHECK(plane_count(masks, W, H, OB_MASK_BORDER) == N - 32 * 16, "flat 10 %%: %zu border",
          plane_count(masks, W, H, OB_MASK_BORDER));

    /* A grazing floor whose depth grows 5 % per pixel has no silhouette; 15 % per pixel has. */
    for (int y = 0; y < H; ++y)
        for (int x = 0; x < W; ++x) depth[y * W + x] = powf(1.05f, (float)y);
    CHECK(ob_metric_masks(depth, ref, W, H, 0.5f, NULL, masks) == OB_OK, "5 %% ramp masks");
    CHECK(plane_count(masks, W, H, OB_MASK_SILHOUETTE) == 0, "5 %% ramp: %zu silhouette",
          plane_count(masks, W, H, OB_MASK_SILHOUETTE));
    for (int y = 0; y < H; ++y)
        for (int x = 0; x < W; ++x) depth[y * W + x] = powf(1.15f, (float)y);
    CHECK(ob_metric_masks(depth, ref, W, H, 0.5f, NULL, masks) == OB_OK, "15 %% ramp masks");
    CHECK(plane_count(masks, W, H, OB_MASK_SILHOUETTE) == N, "15 %% ramp: %zu silhouette",
          plane_count(masks, W, H, OB_MASK_SILHOUETTE));
}

/* The band by its definition, from the box's outline instead of from depths: pixels within
 * distance k of a pixel whose 4-neighbour is on the other side of the outline. */
static bool near_outline(const uint8_t *inside, int w, int h, int x, int y, int k)
{
    for (int qy = 0; qy < h; ++qy)
        for (int qx = 0; qx < w; ++qx) {
            if ((qx - x) * (qx - x) + (qy - y) * (qy - y) > k * k) continue;
            const int nb[4][2] = {{1, 0}, {-1, 0}, {0, 1}, {0, -1}};
            for (int s = 0; s < 4; ++s) {
                int rx = qx + nb[s][0], ry = qy + nb[s][1];
                if (rx >= 0 && ry >= 0 && rx < w && ry < h && inside[qy * w + qx] != inside[ry * w + rx]) return true;
            }
        }
    return false;
}

static void test_mask_silhouette(void)
{
    /* 24x16: a wall at depth 10 and a box at depth 5 over x 8..15, y 4..11, band k = 2. */
    enum { W = 24, H = 16, N = W * H };
    float depth[N], ref[N];
    uint8_t inside[N], masks[N * OB_MASK_COUNT];
    for (int i = 0; i < N; ++i) {
        depth[i] = 10.0f;
        ref[i] = 1.0f;
        inside[i] = 0;
    }
    fill_depth(depth, W, 8, 15, 4, 11, 5.0f);
    for (int y = 4; y <= 11; ++y)
        for (int x = 8; x <= 15; ++x) inside[y * W + x] = 1;
    const ob_metric_mask_desc desc = {.edge_band = 2};
    CHECK(ob_metric_masks(depth, ref, W, H, 0.1f, &desc, masks) == OB_OK, "box masks");
    const uint8_t *sil = plane(masks, W, H, OB_MASK_SILHOUETTE);
    /* Along row 8: the edges are x = 7 (wall) and 8 (box), so x = 5..10 are in, 4 and 11 are out. */
    CHECK(sil[8 * W + 4] == 0 && sil[8 * W + 5] == 1 && sil[8 * W + 7] == 1, "wall side of the left edge");
    CHECK(sil[8 * W + 8] == 1 && sil[8 * W + 10] == 1 && sil[8 * W + 11] == 0, "box side of the left edge");
    /* A disc, not a square: (6, 3) is sqrt(2) from the edge pixel (7, 4), (5, 2) is sqrt(8). */
    CHECK(sil[3 * W + 6] == 1 && sil[2 * W + 5] == 0, "round band at the corner: %d %d", sil[3 * W + 6], sil[2 * W + 5]);
    int wrong = 0;
    for (int y = 0; y < H; ++y)
        for (int x = 0; x < W; ++x) wrong += sil[y * W + x] != near_outline(inside, W, H, x, y, 2);
    CHECK(wrong == 0, "box band: %d pixels differ from the definition", wrong);
    size_t band2 = plane_count(masks, W, H, OB_MASK_SILHOUETTE);
    CHECK(ob_metric_masks(depth, ref, W, H, 0.1f, &(ob_metric_mask_desc){.edge_band = 1}, masks) == OB_OK,
          "box masks k = 1");
    CHECK(plane_count(masks, W, H, OB_MASK_SILHOUETTE) < band2, "k = 1 band is narrower: %zu vs %zu",
          plane_count(masks, W, H, OB_MASK_SILHOUETTE), band2);

    /* A step of 5 % is no edge; 15 % is (relative to the nearer depth: 10 -> 11.5). */
    for (int i = 0; i < N; ++i) depth[i] = 10.0f;
    fill_depth(depth, W, 8, 15, 4, 11, 10.5f);
    CHECK(ob_metric_masks(depth, ref, W, H, 0.1f, &desc, masks) == OB_OK, "5 %% step masks");
    CHECK(plane_count(masks, W, H, OB_MASK_SILHOUETTE) == 0, "5 %% step: %zu silhouette",
          plane_count(masks, W, H, OB_MASK_SILHOUETTE));
    fill_depth(depth, W, 8, 15, 4, 11, 11.5f);
    CHECK(ob_metric_masks(depth, ref, W, H, 0.1f, &desc, masks) == OB_OK, "15 %% step masks");
    wrong = 0;
    for (int y = 0; y < H; ++y)
        for (int x = 0; x < W; ++x) wrong += sil[y * W + x] != near_outline(inside, W, H, x, y, 2);
    CHECK(wrong == 0, "15 %% step: %d pixels differ from the definition", wrong);

    /* Relative to the nearer depth, so both sides of a step are edges: a box at 10 before a wall
     * at 11.05 differs by 10.5 % of the box's depth (9.5 % of the wall's), and the band still reaches
     * 2 pixels into the wall from the wall's own edge pixel at x = 7. */
    for (int i = 0; i < N; ++i) depth[i] = 11.05f;
    fill_depth(depth, W, 8, 15, 4, 11, 10.0f);
    CHECK(ob_metric_masks(depth, ref, W, H, 0.1f, &desc, masks) == OB_OK, "10.5 %% step masks");
    CHECK(sil[8 * W + 5] == 1 && sil[8 * W + 4] == 0, "both sides of a step are edges: %d %d", sil[8 * W + 5],
          sil[8 * W + 4]);

    /* Sky: the wall's last columns before a sky strip (x 20..23) are edges; sky is in no mask,
     * even where the reference there is 0 (occluded) and it lies in the border. */
    for (int i = 0; i < N; ++i) depth[i] = 10.0f;
    fill_depth(depth, W, 20, 23, 0, H - 1, 0.0f);
    for (int y = 0; y < H; ++y) ref[y * W + 21] = 0.0f;
    CHECK(ob_metric_masks(depth, ref, W, H, 0.1f, &desc, masks) == OB_OK, "sky masks");
    CHECK(sil[8 * W + 16] == 0 && sil[8 * W + 17] == 1 && sil[8 * W + 19] == 1 && sil[8 * W + 20] == 0,
          "sky edge band: %d %d %d %d", sil[8 * W + 16], sil[8 * W + 17], sil[8 * W + 19], sil[8 * W + 20]);
    int in_sky = 0;
    for (int m = 0; m < OB_MASK_COUNT; ++m)
        for (int y = 0; y < H; ++y)
            for (int x = 20; x < W; ++x) in_sky += plane(masks, W, H, (ob_metric_mask)m)[y * W + x];
    CHECK(in_sky == 0, "sky pixels in a mask: %d", in_sky);
    CHECK(plane_count(masks, W, H, OB_MASK_SILHOUETTE) == 3 * H, "sky band: %zu", plane_count(masks, W, H, OB_MASK_SILHOUETTE));
}

static void test_mask_thin(void)
{
    /* 48x12, wall at 10, R = 1, reach 3: a pixel i of a part W wide has background i + 1 to its
     * left and W - i to its right, so a part up to 3 wide is thin throughout, one 5 wide at its
     * middle pixel only, one 6 wide nowhere. Poles over every row: x 2..4 (3 wide), 8..12 (5 wide),
     * 16..21 (6 wide), 25 (0.5 in front: nearer than R, not thin), 28 (10 behind: a gap, not thin),
     * 36..37 (against sky at 35 and 38: thin), 46..47 (at the image's edge, where nothing is seen
     * beyond: not thin). A rail 2 rows high over x 40..45, y 2..3 is thin by the rows below and
     * above. */
    enum { W = 48, H = 12, N = W * H };
    float depth[N], ref[N];
    uint8_t masks[N * OB_MASK_COUNT];
    for (int i = 0; i < N; ++i) {
        depth[i] = 10.0f;
        ref[i] = 1.0f;
    }
    fill_depth(depth, W, 2, 4, 0, H - 1, 5.0f);
    fill_depth(depth, W, 8, 12, 0, H - 1, 5.0f);
    fill_depth(depth, W, 16, 21, 0, H - 1, 5.0f);
    fill_depth(depth, W, 25, 25, 0, H - 1, 9.5f);
    fill_depth(depth, W, 28, 28, 0, H - 1, 20.0f);
    fill_depth(depth, W, 35, 35, 0, H - 1, 0.0f);
    fill_depth(depth, W, 36, 37, 0, H - 1, 5.0f);
    fill_depth(depth, W, 38, 38, 0, H - 1, 0.0f);
    fill_depth(depth, W, 40, 45, 2, 3, 5.0f);
    fill_depth(depth, W, 46, 47, 0, H - 1, 5.0f);
    const ob_metric_mask_desc desc = {.thin_reach = 3};
    CHECK(ob_metric_masks(depth, ref, W, H, 1.0f, &desc, masks) == OB_OK, "thin masks");
    const uint8_t *thin = plane(masks, W, H, OB_MASK_THIN);
    bool want[W] = {false};
    want[2] = want[3] = want[4] = want[10] = want[36] = want[37] = true;
    int wrong = 0;
    for (int x = 0; x < W; ++x) {
        if (thin[6 * W + x] != want[x]) {
            ++wrong;
            fprintf(stderr, "  thin row 6, x = %d: %d\n", x, thin[6 * W + x]);
        }
    }
    CHECK(wrong == 0, "thin along row 6: %d wrong", wrong);
    CHECK(thin[2 * W + 42] == 1 && thin[3 * W + 40] == 1 && thin[3 * W + 45] == 1, "the rail is thin");
    CHECK(thin[1 * W + 42] == 0 && thin[4 * W + 42] == 0, "the wall beside the rail is not");
    CHECK(plane_count(masks, W, H, OB_MASK_THIN) == (size_t)(6 * H + 12), "thin count %zu",
          plane_count(masks, W, H, OB_MASK_THIN));

    /* The 0.5-deep pole is thin at R = 0.25; the 6-wide one has two thin pixels with a reach of 4. */
    CHECK(ob_metric_masks(depth, ref, W, H, 0.25f, &desc, masks) == OB_OK && thin[6 * W + 25] == 1,
          "shallow pole thin at R = 0.25");
    CHECK(ob_metric_masks(depth, ref, W, H, 1.0f, &(ob_metric_mask_desc){.thin_reach = 4}, masks) == OB_OK &&
              thin[6 * W + 18] == 1 && thin[6 * W + 19] == 1 && thin[6 * W + 17] == 0 && thin[6 * W + 20] == 0,
          "6-wide pole with reach 4: %d %d %d %d", thin[6 * W + 17], thin[6 * W + 18], thin[6 * W + 19],
          thin[6 * W + 20]);

    /* Every definition is symmetric under a vertical flip: the masks of the flipped depth are the
     * flipped masks (with an asymmetric scene: the rail is near the bottom). */
    float flipped[N], flipped_ref[N];
    uint8_t again[N * OB_MASK_COUNT];
    for (int i = 0; i < N; ++i) ref[i] = (float)(i % 7) / 7.0f;
    for (int y = 0; y < H; ++y)
        for (int x = 0; x < W; ++x) {
            flipped[(H - 1 - y) * W + x] = depth[y * W + x];
            flipped_ref[(H - 1 - y) * W + x] = ref[y * W + x];
        }
    CHECK(ob_metric_masks(depth, ref, W, H, 1.0f, NULL, masks) == OB_OK &&
              ob_metric_masks(flipped, flipped_ref, W, H, 1.0f, NULL, again) == OB_OK,
          "flip masks");
    wrong = 0;
    for (int m = 0; m < OB_MASK_COUNT; ++m)
        for (int y = 0; y < H; ++y)
            for (int x = 0; x < W; ++x)
                wrong += plane(masks, W, H, (ob_metric_mask)m)[y * W + x] !=
                         plane(again, W, H, (ob_metric_mask)m)[(H - 1 - y) * W + x];
    CHECK(wrong == 0, "flipped masks: %d pixels differ", wrong);
}

static void test_mask_bad_arguments(void)
{
    float d[4] = {1.0f, 1.0f, 1.0f, 1.0f};
    uint8_t masks[4 * OB_MASK_COUNT];
    CHECK(ob_metric_masks(NULL, d, 2, 2, 1.0f, NULL, masks) == OB_ERR_INVALID_ARGUMENT, "NULL depth");
    CHECK(ob_metric_masks(d, NULL, 2, 2, 1.0f, NULL, masks) == OB_ERR_INVALID_ARGUMENT, "NULL reference");
    CHECK(ob_metric_masks(d, d, 2, 2, 1.0f, NULL, NULL) == OB_ERR_INVALID_ARGUMENT, "NULL masks_out");
    CHECK(ob_metric_masks(d, d, 0, 2, 1.0f, NULL, masks) == OB_ERR_INVALID_ARGUMENT, "zero width");
    CHECK(ob_metric_masks(d, d, 1 << 30, 1 << 30, 1.0f, NULL, masks) == OB_ERR_INVALID_ARGUMENT, "huge image");
    CHECK(ob_metric_masks(d, d, 2, 2, 0.0f, NULL, masks) == OB_ERR_INVALID_ARGUMENT, "zero radius");
    CHECK(ob_metric_masks(d, d, 2, 2, NAN, NULL, masks) == OB_ERR_INVALID_ARGUMENT, "NaN radius");
    const char *msg = NULL;
    CHECK(ob_get_error(&msg) == OB_ERR_INVALID_ARGUMENT && msg && strstr(msg, "radius"), "message names the radius: %s",
          msg ? msg : "(null)");
    CHECK(ob_metric_masks(d, d, 2, 2, 1.0f, &(ob_metric_mask_desc){.edge_band = -1}, masks) == OB_ERR_INVALID_ARGUMENT,
          "negative band");
    CHECK(ob_metric_masks(d, d, 2, 2, 1.0f, &(ob_metric_mask_desc){.thin_reach = 5000}, masks) == OB_ERR_INVALID_ARGUMENT,
          "huge reach");
    CHECK(ob_metric_masks(d, d, 2, 2, 1.0f, &(ob_metric_mask_desc){.edge_relative = -0.1f}, masks) ==
              OB_ERR_INVALID_ARGUMENT,
          "negative edge_relative");
    CHECK(ob_metric_masks(d, d, 2, 2, 1.0f, &(ob_metric_mask_desc){.occluded_below = INFINITY}, masks) ==
              OB_ERR_INVALID_ARGUMENT,
          "infinite occluded_below");
    CHECK(ob_metric_masks(d, d, 2, 2, 1.0f, &(ob_metric_mask_desc){.border_fraction = 0.6f}, masks) ==
              OB_ERR_INVALID_ARGUMENT,
          "border_fraction over 0.5");
    /* A 1x1 image is all border. */
    CHECK(ob_metric_masks(d, d, 1, 1, 1.0f, NULL, masks) == OB_OK && masks[OB_MASK_BORDER] == 1, "1x1 border");
}

int main(void)
{
    test_identical();
    test_one_pixel_off();
    test_psnr_srgb();
    test_channels();
    test_ssim_closed_forms();
    test_ssim_against_direct();
    test_heatmap();
    test_bad_arguments();
    test_mask_defaults();
    test_mask_flat();
    test_mask_silhouette();
    test_mask_thin();
    test_mask_bad_arguments();
    return check_finish("metrics");
}
