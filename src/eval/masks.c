/* Where the error matters: pixel masks over which the report measures RMSE and bias again, so that
 * a method's error at creases, halos, thin parts and the screen border is not averaged away by the
 * open surfaces that fill most of an image (issue 15).
 *
 * Every mask is built from what the report already has: the renderer's linear depth (0 = sky) and
 * the reference AO_R. Sky is in no mask: its AO is not defined, and the global metrics skip it too.
 * Every definition is symmetric under a vertical flip, so the masks come out in the inputs' row
 * order, whichever that is.
 */
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "base/error.h"
#include "obscura/eval.h"

/* Reference AO_R below 0.75 is occluded: a floor point at 0.6 R from one wall (docs/architecture.md's analytic
 * case) is there, an open plane (1) and a gentle slope are not. */
#define DEFAULT_OCCLUDED_BELOW 0.75f
/* A neighbour 10 % nearer or farther is across a silhouette: a plane seen head-on changes depth by
 * far less per pixel, and one at grazing angles only beyond about 20 camera heights at 320x240. */
#define DEFAULT_EDGE_RELATIVE 0.10f
/* Halos reach a few pixels from the silhouette: 2 at 320 wide, and the same fraction of the image
 * at other sizes (k = max(1, round(width / 160))). */
#define DEFAULT_EDGE_BAND_PER_WIDTH (2.0 / 320.0)
/* Thin parts up to 2 x 3 - 1 = 5 pixels wide at 320 (pole, rail, chair leg), scaled alike. */
#define DEFAULT_THIN_REACH_PER_WIDTH (3.0 / 320.0)
/* The outer 5 % of each side: where the screen cuts a method's search, and where guard bands help. */
#define DEFAULT_BORDER_FRACTION 0.05f

static const char *const mask_names[OB_MASK_COUNT] = {"occluded", "silhouette", "thin", "border"};

const char *ob_metric_mask_name(ob_metric_mask mask)
{
    return (int)mask >= 0 && mask < OB_MASK_COUNT ? mask_names[mask] : "";
}

static int scaled_pixels(double per_width, int width)
{
    long n = lround(per_width * (double)width);
    return n < 1 ? 1 : n > 1 << 20 ? 1 << 20 : (int)n;
}

ob_metric_mask_desc ob_metric_mask_defaults(const ob_metric_mask_desc *desc, int width)
{
    ob_metric_mask_desc d = desc ? *desc : (ob_metric_mask_desc){0};
    if (d.occluded_below == 0.0f) d.occluded_below = DEFAULT_OCCLUDED_BELOW;
    if (d.edge_relative == 0.0f) d.edge_relative = DEFAULT_EDGE_RELATIVE;
    if (d.edge_band == 0) d.edge_band = scaled_pixels(DEFAULT_EDGE_BAND_PER_WIDTH, width);
    if (d.thin_reach == 0) d.thin_reach = scaled_pixels(DEFAULT_THIN_REACH_PER_WIDTH, width);
    if (d.border_fraction == 0.0f) d.border_fraction = DEFAULT_BORDER_FRACTION;
    return d;
}

/* Sky, or a value no pass should write (NaN, negative): no surface there. */
static bool is_geometry(float d)
{
    return d > 0.0f && isfinite(d);
}

/* The depths of two geometry pixels lie across a silhouette. Relative to the nearer of the two, so
 * both sides of the step are edges (a halo sits on the far side, a dark rim on the near one). */
static bool depth_step(float a, float b, float relative)
{
    float nearer = a < b ? a : b;
    return fabsf(a - b) > relative * nearer;
}

/* Some pixel 1..reach steps from (x, y) along (dx, dy), inside the image, is sky or farther than
 * `depth` by more than `gap`: background shows on that side. */
static bool far_side(const float *depth, int w, int h, int x, int y, int dx, int dy, int reach, float gap,
                     float depth_xy)
{
    for (int i = 1; i <= reach; ++i) {
        int qx = x + i * dx, qy = y + i * dy;
        if (qx < 0 || qy < 0 || qx >= w || qy >= h) return false;
        float q = depth[(size_t)qy * (size_t)w + (size_t)qx];
        if (!is_geometry(q) || q > depth_xy + gap) return true;
    }
    return false;
}

ob_error ob_metric_masks(const float *linear_depth, const float *reference, int width, int height, float radius,
                         const ob_metric_mask_desc *desc, uint8_t *masks_out)
{
    if (!linear_depth || !reference || !masks_out)
        return ob_set_error(OB_ERR_INVALID_ARGUMENT, "ob_metric_masks: NULL %s",
                            !linear_depth ? "linear_depth" : !reference ? "reference" : "masks_out");
    /* The cap keeps width x height x OB_MASK_COUNT inside size_t and every index inside int. */
    if (width < 1 || height < 1 || (size_t)width * (size_t)height > ((size_t)1 << 28) / OB_MASK_COUNT)
        return ob_set_error(OB_ERR_INVALID_ARGUMENT, "ob_metric_masks: bad size %dx%d", width, height);
    if (!(radius > 0.0f) || !isfinite(radius))
        return ob_set_error(OB_ERR_INVALID_ARGUMENT, "ob_metric_masks: radius %g must be finite and > 0", (double)radius);
    const ob_metric_mask_desc d = ob_metric_mask_defaults(desc, width);
    if (!(d.occluded_below > 0.0f) || !isfinite(d.occluded_below))
        return ob_set_error(OB_ERR_INVALID_ARGUMENT, "ob_metric_masks: occluded_below %g must be finite and > 0",
                            (double)d.occluded_below);
    if (!(d.edge_relative > 0.0f) || !isfinite(d.edge_relative))
        return ob_set_error(OB_ERR_INVALID_ARGUMENT, "ob_metric_masks: edge_relative %g must be finite and > 0",
                            (double)d.edge_relative);
    if (d.edge_band < 1 || d.edge_band > 1024 || d.thin_reach < 1 || d.thin_reach > 1024)
        return ob_set_error(OB_ERR_INVALID_ARGUMENT, "ob_metric_masks: edge_band %d and thin_reach %d must be 1..1024",
                            d.edge_band, d.thin_reach);
    if (!(d.border_fraction > 0.0f && d.border_fraction <= 0.5f))
        return ob_set_error(OB_ERR_INVALID_ARGUMENT, "ob_metric_masks: border_fraction %g must be in (0, 0.5]",
                            (double)d.border_fraction);

    const int w = width, h = height;
    const size_t n = (size_t)w * (size_t)h;
    uint8_t *edge = calloc(n, 1);
    if (!edge) return ob_set_error(OB_ERR_OUT_OF_MEMORY, "ob_metric_masks: %dx%d edge map", w, h);
    memset(masks_out, 0, n * OB_MASK_COUNT);
    uint8_t *occluded = masks_out + n * OB_MASK_OCCLUDED;
    uint8_t *silhouette = masks_out + n * OB_MASK_SILHOUETTE;
    uint8_t *thin = masks_out + n * OB_MASK_THIN;
    uint8_t *border = masks_out + n * OB_MASK_BORDER;

    /* At least one pixel, so that a tiny image still has a border. */
    int bx = (int)lroundf(d.border_fraction * (float)w), by = (int)lroundf(d.border_fraction * (float)h);
    bx = bx < 1 ? 1 : bx;
    by = by < 1 ? 1 : by;
    static const int step[4][2] = {{1, 0}, {-1, 0}, {0, 1}, {0, -1}};
    for (int y = 0; y < h; ++y) {
        for (int x = 0; x < w; ++x) {
            size_t p = (size_t)y * (size_t)w + (size_t)x;
            float z = linear_depth[p];
            if (!is_geometry(z)) continue;
            occluded[p] = reference[p] < d.occluded_below;
            border[p] = x < bx || x >= w - bx || y < by || y >= h - by;
            /* Edges: a 4-neighbour across a depth step, or sky. The image's own border is none. */
            for (int s = 0; s < 4 && !edge[p]; ++s) {
                int qx = x + step[s][0], qy = y + step[s][1];
                if (qx < 0 || qy < 0 || qx >= w || qy >= h) continue;
                float q = linear_depth[(size_t)qy * (size_t)w + (size_t)qx];
                edge[p] = !is_geometry(q) || depth_step(z, q, d.edge_relative);
            }
            /* Thin: background farther than R on both sides, left and right or below and above.
             * Farther than R means the method's search from here can reach past the part into
             * empty space, which is where screen-space methods guess. A pixel behind both sides (a
             * gap) is not a thin part, so it is left out. */
            int r = d.thin_reach;
            thin[p] = (far_side(linear_depth, w, h, x, y, -1, 0, r, radius, z) &&
                       far_side(linear_depth, w, h, x, y, 1, 0, r, radius, z)) ||
                      (far_side(linear_depth, w, h, x, y, 0, -1, r, radius, z) &&
                       far_side(linear_depth, w, h, x, y, 0, 1, r, radius, z));
        }
    }
    /* The silhouette band: geometry within edge_band pixels (Euclidean) of an edge pixel. */
    const int k = d.edge_band;
    for (int y = 0; y < h; ++y) {
        for (int x = 0; x < w; ++x) {
            if (!edge[(size_t)y * (size_t)w + (size_t)x]) continue;
            for (int dy = -k; dy <= k; ++dy) {
                int qy = y + dy;
                if (qy < 0 || qy >= h) continue;
                for (int dx = -k; dx <= k; ++dx) {
                    int qx = x + dx;
                    if (qx < 0 || qx >= w || dx * dx + dy * dy > k * k) continue;
                    size_t q = (size_t)qy * (size_t)w + (size_t)qx;
                    if (is_geometry(linear_depth[q])) silhouette[q] = 1;
                }
            }
        }
    }
    free(edge);
    return OB_OK;
}
