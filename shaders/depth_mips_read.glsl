/* Reading the depth MIP chain (passes/depth_mips.c, shaders/depth_mips.glsl) where a tap lands:
 * the texel under it and the one full-resolution pixel whose depth that texel holds. The chain
 * picks one child per level, SAO's rotated grid (texel p of level L is texel 2p + (p.y & 1, p.x & 1)
 * of level L - 1, sky included), so following the same picks back down finds that pixel, and a
 * reader reconstructs the tap there: exact on planes at every level, as at level 0. Shared by the
 * slice methods' march (slice_march.glsl ob_march_depth) and the random-kernel methods' taps
 * (taps.glsl). Needs ob_shared.h (OB_DEPTH_MIPS_LEVELS). */
#ifndef OB_DEPTH_MIPS_READ_GLSL
#define OB_DEPTH_MIPS_READ_GLSL

/* The pixel whose depth texel `texel` of level `level` holds, for AO pixel q in an image of
 * `size`. Beyond a level's last texel (odd sizes) the chain holds nothing: clamped, as the pass
 * does (GL's level size, max(1, size >> L)). The picks back down take a constant trip count with
 * selects, not a loop over this lane's level: llvmpipe runs a data-dependent loop for as long as
 * its slowest lane. */
ivec2 ob_depth_mip_source(ivec2 q, int level, ivec2 size, out ivec2 texel)
{
    texel = min(q >> level, max(size >> level, ivec2(1)) - 1);
    ivec2 c = texel;
    for (int l = 0; l < OB_DEPTH_MIPS_LEVELS - 1; ++l) c = l < level ? 2 * c + ivec2(c.y & 1, c.x & 1) : c;
    return c;
}

#endif
