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
 * does (GL's level size, max(1, size >> L)).
 * The picks back down in closed form, no loop over the levels: one pick takes c to
 * 2c + (c.y & 1, c.x & 1), whose low bits are (c.y & 1, c.x & 1), so the next pick adds the
 * top texel's (a, b) = (c.x & 1, c.y & 1) swapped again, and k picks append k bits alternating
 * from b (x) or a (y) at bit k - 1 down to bit 0: x = c.x 2^k + b P + a Q, y = c.y 2^k + a P + b Q,
 * with P the bits k - 1, k - 3, ... and Q the others below 2^k. The same pixel as the picks one by
 * one (a constant-trip loop of selects, so that llvmpipe did not run a data-dependent loop for
 * its slowest lane): a third of the integer operations per tap. */
ivec2 ob_depth_mip_source(ivec2 q, int level, ivec2 size, out ivec2 texel)
{
    texel = min(q >> level, max(size >> level, ivec2(1)) - 1);
    int k = clamp(level, 0, OB_DEPTH_MIPS_LEVELS - 1);
    int m = (1 << k) - 1;
    int p = ((k & 1) != 0 ? 0x55 : 0xAA) & m, o = m ^ p;
    ivec2 low = texel & 1; /* (a, b) */
    return (texel << k) | (-low.yx & p) | (-low & o);
}

#endif
