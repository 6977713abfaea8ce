/* Internal pieces of the ray-traced reference (reference.c) that tests and tools reuse. */
#ifndef OB_REFERENCE_INTERNAL_H
#define OB_REFERENCE_INTERNAL_H

#include "obscura/eval.h"

/* One light at a surface point, exactly as shaders/lighting.glsl computes it before the shadow
 * term and the albedo: writes the unit direction toward the light and the distance to it (INFINITY
 * for directional lights), and returns colour x intensity x falloff x max(0, n.l) in rgb. Returns
 * false (rgb zero) where the light does not reach the point. */
bool ob_reference_light(const ob_light *light, const float p[3], const float n[3], float l_out[3], float *dist_out,
                        float rgb_out[3]);

/* The per-point random stream: a PCG32 seeded from the seed and the point's index, so a point's
 * rays do not depend on which thread casts them. */
struct ob_rng;
void ob_reference_point_rng(struct ob_rng *rng, uint64_t seed, size_t index);

#endif
