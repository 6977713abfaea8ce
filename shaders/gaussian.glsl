#version 450 core
/* One direction of the separable Gaussian blur (Belonogov 2018 §4.3.1, eq. 4.4), run along x then y.
 * No depth, no normals: every pixel, sky included, is averaged with its neighbours, so the AO of a
 * foreground object smears onto the background and the sky's 1 brightens silhouettes. That is the
 * point: it is the geometry-blind baseline. Taps past the image border repeat the edge pixel, so
 * the CPU-normalised weights always sum to 1. */
#include "filter_params.h"

layout(local_size_x = OB_FILTER_GROUP_X, local_size_y = OB_FILTER_GROUP_Y) in;

layout(binding = OB_UNIT_FILTER_IN) uniform sampler2D ao_in;
layout(binding = OB_IMAGE_UNIT_OUT, OB_FILTER_FORMAT) uniform writeonly image2D ao_out;

void main()
{
    ivec2 pix = ivec2(gl_GlobalInvocationID.xy);
    ivec2 size = flt.size;
    if (any(greaterThanEqual(pix, size))) return;
    ivec2 dir = flt.axis;
    int radius = flt.radius;
    OB_FILTER_T sum = OB_FILTER_T(0.0);
    /* One fetch per iteration over -r..r, like the bilateral passes: folding the symmetric taps
     * into one iteration (w_i (a + b)) ran 2.5x slower on llvmpipe (~90 vs ~35 ms, 1280x720). */
    for (int i = -radius; i <= radius; ++i) {
        ivec2 q = clamp(pix + i * dir, ivec2(0), size - 1);
        sum += flt.weights[abs(i)].x * OB_FILTER_FETCH(ao_in, q);
    }
    imageStore(ao_out, pix, vec4(OB_FILTER_RESULT(sum)));
}
