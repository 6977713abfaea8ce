/* Image-comparison metrics: RMSE, MAE, bias, PSNR (linear and sRGB-encoded) and SSIM of a method's
 * visibility against the ray-traced reference, and a signed error heatmap for the report.
 *
 * sRGB PSNR: XeGTAO reports its error against 512-spp ray tracing as PSNR of the sRGB-encoded AO
 * (about 21.4 dB for its High preset), so we report it too, to set our numbers beside theirs. The
 * transfer is IEC 61966-2-1's: 12.92 v below 0.0031308, 1.055 v^(1/2.4) - 0.055 above.
 *
 * SSIM: Z. Wang, A. C. Bovik, H. R. Sheikh, E. P. Simoncelli, "Image Quality Assessment: From
 * Error Visibility to Structural Similarity", IEEE TIP 13(4), 2004. Eq. 13 gives the local index,
 * eqs. 14-16 the Gaussian-weighted local statistics (11x11 window, sigma 1.5, unit sum), eq. 17 the
 * mean over windows (MSSIM); the constants are C1 = (K1 L)^2, C2 = (K2 L)^2 with K1 = 0.01,
 * K2 = 0.03 (§III.C), and L = 1 because visibility lives in [0, 1].
 */
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "base/error.h"
#include "obscura/eval.h"

/* Wang et al. 2004, §III.C: an 11x11 circular-symmetric Gaussian with sigma = 1.5 samples. */
#define SSIM_RADIUS 5
#define SSIM_TAPS (2 * SSIM_RADIUS + 1)
#define SSIM_SIGMA 1.5
#define SSIM_K1 0.01
#define SSIM_K2 0.03
#define SSIM_L 1.0 /* dynamic range of visibility */

/* IEC 61966-2-1 encoding of a value clamped to [0, 1], as an sRGB image would store it. NaN stays
 * NaN (neither comparison holds), so a broken pass still shows as NaN metrics. */
static double srgb_encode(double v)
{
    v = v < 0.0 ? 0.0 : v > 1.0 ? 1.0 : v;
    return v <= 0.0031308 ? 12.92 * v : 1.055 * pow(v, 1.0 / 2.4) - 0.055;
}

/* Peak 1; MSE = 0 gives +inf, which is what identical images deserve. */
static double psnr_of(double mse)
{
    return mse > 0.0 ? 10.0 * log10(1.0 / mse) : (mse == 0.0 ? INFINITY : NAN);
}

/* Five windowed sums per pixel: E[x], E[y], E[x^2], E[y^2], E[xy]. */
enum { MOM_X = 0, MOM_Y, MOM_XX, MOM_YY, MOM_XY, MOM_COUNT };

/* Checks shared by both entry points; pixels gets width * height. The cap keeps every index and
 * every byte count (x channels, x 3 for RGB, x MOM_COUNT doubles) inside size_t and int. */
static ob_error check_size(const char *fn, int width, int height, int channels, size_t *pixels)
{
    if (width < 1 || height < 1 || channels < 1)
        return ob_set_error(OB_ERR_INVALID_ARGUMENT, "%s: bad size %dx%dx%d", fn, width, height, channels);
    const size_t limit = (size_t)1 << 28;
    size_t n = (size_t)width * (size_t)height;
    if (n > limit / (size_t)channels)
        return ob_set_error(OB_ERR_INVALID_ARGUMENT, "%s: image too large %dx%dx%d", fn, width, height, channels);
    *pixels = n;
    return OB_OK;
}

/* The 1-D Gaussian taps; the 2-D window is their outer product, so the sums separate into a row
 * pass and a column pass. Not normalised here: each pass divides by the sum of the taps that fall
 * inside the image, which is what renormalising the cut 2-D window to unit sum amounts to (the cut
 * window is a rectangle, so its weight sum is the product of the two 1-D sums). */
static void gaussian_taps(double taps[SSIM_TAPS])
{
    for (int i = 0; i < SSIM_TAPS; ++i) {
        double d = (double)(i - SSIM_RADIUS);
        taps[i] = exp(-d * d / (2.0 * SSIM_SIGMA * SSIM_SIGMA));
    }
}

/* Row pass for one image row of one channel: the five windowed row sums at every x. */
static void ssim_row(const float *test, const float *reference, int width, int channels, int c, int y,
                     const double taps[SSIM_TAPS], double *out /* MOM_COUNT * width */)
{
    const size_t row = (size_t)y * (size_t)width;
    for (int x = 0; x < width; ++x) {
        double s[MOM_COUNT] = {0.0, 0.0, 0.0, 0.0, 0.0};
        double wsum = 0.0;
        int lo = x - SSIM_RADIUS < 0 ? 0 : x - SSIM_RADIUS;
        int hi = x + SSIM_RADIUS > width - 1 ? width - 1 : x + SSIM_RADIUS;
        for (int k = lo; k <= hi; ++k) {
            size_t i = (row + (size_t)k) * (size_t)channels + (size_t)c;
            double w = taps[k - x + SSIM_RADIUS];
            double a = (double)test[i];
            double b = (double)reference[i];
            s[MOM_X] += w * a;
            s[MOM_Y] += w * b;
            s[MOM_XX] += w * a * a;
            s[MOM_YY] += w * b * b;
            s[MOM_XY] += w * a * b;
            wsum += w;
        }
        for (int m = 0; m < MOM_COUNT; ++m) out[(size_t)m * (size_t)width + (size_t)x] = s[m] / wsum;
    }
}

/* Sum of the local SSIM (eq. 13) over the masked-in pixels of channel c. The row passes live in a
 * ring of SSIM_TAPS rows, so memory stays O(width) whatever the image height. */
static double ssim_channel_sum(const float *test, const float *reference, const uint8_t *mask, int width,
                               int height, int channels, int c, const double taps[SSIM_TAPS], double *ring)
{
    const double c1 = (SSIM_K1 * SSIM_L) * (SSIM_K1 * SSIM_L);
    const double c2 = (SSIM_K2 * SSIM_L) * (SSIM_K2 * SSIM_L);
    const size_t slot = (size_t)MOM_COUNT * (size_t)width;
    double total = 0.0;
    int rows_done = 0; /* row passes computed so far: rows [0, rows_done) */
    for (int y = 0; y < height; ++y) {
        int lo = y - SSIM_RADIUS < 0 ? 0 : y - SSIM_RADIUS;
        int hi = y + SSIM_RADIUS > height - 1 ? height - 1 : y + SSIM_RADIUS;
        /* hi - lo < SSIM_TAPS, so rows [lo, hi] are all still in the ring. */
        while (rows_done <= hi) {
            ssim_row(test, reference, width, channels, c, rows_done, taps, ring + (size_t)(rows_done % SSIM_TAPS) * slot);
            ++rows_done;
        }
        for (int x = 0; x < width; ++x) {
            size_t p = (size_t)y * (size_t)width + (size_t)x;
            if (mask && !mask[p]) continue;
            double s[MOM_COUNT] = {0.0, 0.0, 0.0, 0.0, 0.0};
            double wsum = 0.0;
            for (int k = lo; k <= hi; ++k) {
                const double *r = ring + (size_t)(k % SSIM_TAPS) * slot;
                double w = taps[k - y + SSIM_RADIUS];
                for (int m = 0; m < MOM_COUNT; ++m) s[m] += w * r[(size_t)m * (size_t)width + (size_t)x];
                wsum += w;
            }
            double mx = s[MOM_X] / wsum;
            double my = s[MOM_Y] / wsum;
            /* Eqs. 15-16 as E[x^2] - E[x]^2: in double, with values in [0, 1], the cancellation
             * error (~1e-16) is far below C2 (9e-4), so it cannot move the index. */
            double vx = s[MOM_XX] / wsum - mx * mx;
            double vy = s[MOM_YY] / wsum - my * my;
            double cxy = s[MOM_XY] / wsum - mx * my;
            double num = (2.0 * mx * my + c1) * (2.0 * cxy + c2);
            double den = (mx * mx + my * my + c1) * (vx + vy + c2);
            total += num / den;
        }
    }
    return total;
}

ob_error ob_compare_images(const float *test, const float *reference, const uint8_t *mask, int width,
                           int height, int channels, ob_metrics *out)
{
    if (out) memset(out, 0, sizeof out[0]);
    if (!test || !reference || !out)
        return ob_set_error(OB_ERR_INVALID_ARGUMENT, "ob_compare_images: NULL %s",
                            !test ? "test" : !reference ? "reference" : "out");
    size_t pixels = 0;
    ob_error err = check_size("ob_compare_images", width, height, channels, &pixels);
    if (err != OB_OK) return err;

    /* Pixel errors in double: a 4K image has 25M values, and float sums would lose the small
     * errors that separate good methods. */
    size_t count = 0;
    double sum = 0.0, sum_abs = 0.0, sum_sq = 0.0, sum_sq_srgb = 0.0;
    for (size_t p = 0; p < pixels; ++p) {
        if (mask && !mask[p]) continue;
        ++count;
        for (int c = 0; c < channels; ++c) {
            size_t i = p * (size_t)channels + (size_t)c;
            double d = (double)test[i] - (double)reference[i];
            sum += d;
            sum_abs += fabs(d);
            sum_sq += d * d;
            double e = srgb_encode((double)test[i]) - srgb_encode((double)reference[i]);
            sum_sq_srgb += e * e;
        }
    }
    if (count == 0) return ob_set_error(OB_ERR_INVALID_ARGUMENT, "ob_compare_images: no pixel in the mask");

    double *ring = malloc((size_t)SSIM_TAPS * (size_t)MOM_COUNT * (size_t)width * sizeof(double));
    if (!ring) return ob_set_error(OB_ERR_OUT_OF_MEMORY, "ob_compare_images: %d-pixel row buffer", width);
    double taps[SSIM_TAPS] = {0.0};
    gaussian_taps(taps);
    double ssim_sum = 0.0;
    for (int c = 0; c < channels; ++c)
        ssim_sum += ssim_channel_sum(test, reference, mask, width, height, channels, c, taps, ring);
    free(ring);

    double values = (double)count * (double)channels;
    double mse = sum_sq / values;
    out->count = count;
    out->rmse = sqrt(mse);
    out->mae = sum_abs / values;
    out->bias = sum / values;
    /* Peak 1: visibility's range (and the sRGB-encoded range). */
    out->psnr = psnr_of(mse);
    out->psnr_srgb = psnr_of(sum_sq_srgb / values);
    /* Every channel averages over the same windows, so one mean over all of them is the mean of
     * the per-channel means. */
    out->ssim = ssim_sum / values;
    return OB_OK;
}

/* ColorBrewer RdBu (11 classes), run from blue (test lower) to red (test higher), with its
 * off-white centre replaced by pure white so that "no error" reads as blank paper. */
static const uint8_t heat_stops[11][3] = {
    {5, 48, 97},    {33, 102, 172}, {67, 147, 195}, {146, 197, 222}, {209, 229, 240}, {255, 255, 255},
    {253, 219, 199}, {244, 165, 130}, {214, 96, 77}, {178, 24, 43},  {103, 0, 31},
};

static void heat_colour(double t /* in [-1, 1] */, uint8_t rgb[3])
{
    double u = (t + 1.0) * 5.0; /* 0 .. 10 across the stops */
    int i = (int)floor(u);
    if (i < 0) i = 0;
    if (i > 9) i = 9;
    double f = u - (double)i;
    for (int k = 0; k < 3; ++k) {
        double v = (1.0 - f) * (double)heat_stops[i][k] + f * (double)heat_stops[i + 1][k];
        rgb[k] = (uint8_t)lround(v);
    }
}

ob_error ob_error_heatmap(const float *test, const float *reference, const uint8_t *mask, int width, int height,
                          bool bottom_first, float range, uint8_t *rgb_out)
{
    if (!test || !reference || !rgb_out)
        return ob_set_error(OB_ERR_INVALID_ARGUMENT, "ob_error_heatmap: NULL %s",
                            !test ? "test" : !reference ? "reference" : "rgb_out");
    size_t pixels = 0;
    ob_error err = check_size("ob_error_heatmap", width, height, 3, &pixels);
    if (err != OB_OK) return err;
    if (!(range > 0.0f) || !isfinite(range))
        return ob_set_error(OB_ERR_INVALID_ARGUMENT, "ob_error_heatmap: range %g must be finite and > 0", (double)range);

    for (int y = 0; y < height; ++y) {
        int src_y = bottom_first ? height - 1 - y : y;
        for (int x = 0; x < width; ++x) {
            size_t src = (size_t)src_y * (size_t)width + (size_t)x;
            uint8_t *px = rgb_out + ((size_t)y * (size_t)width + (size_t)x) * 3;
            if (mask && !mask[src]) {
                px[0] = px[1] = px[2] = 128;
                continue;
            }
            double d = (double)test[src] - (double)reference[src];
            if (!isfinite(d)) {
                /* Black is not on the map, so a NaN from a broken pass cannot pass for an error. */
                px[0] = px[1] = px[2] = 0;
                continue;
            }
            double t = d / (double)range;
            heat_colour(t < -1.0 ? -1.0 : t > 1.0 ? 1.0 : t, px);
        }
    }
    return OB_OK;
}
