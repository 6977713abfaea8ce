/* CPU unit tests of the image-comparison metrics (src/eval/metrics.c): hand-computed RMSE, MAE,
 * bias and PSNR, SSIM against closed forms (Wang et al. 2004, eq. 13) and against a direct 2-D
 * window sum, masks, the error heatmap's colours and row order, and argument checks. */
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "check.h"
#include "obscura/obscura.h"

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
    return check_finish("metrics");
}
