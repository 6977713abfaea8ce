#version 450 core
/* Depth MIP prefilter: levels 0..OB_DEPTH_MIPS_LEVELS-1 of linear view depth in one dispatch
 * (McGuire, Mara & Luebke 2012, "Scalable Ambient Obscurance", §2.2: far taps read coarser
 * levels so that they stay in the texture cache). Each work group copies its 16x16 tile of the
 * input to level 0 and reduces it level by level in shared memory down to one level-4 texel, with
 * a barrier between levels (the structure of XeGTAO's prefilter pass).
 *
 * The reduction picks ONE of the 2x2 children, SAO's rotated grid (§2.2): level-L texel p takes
 * the child at 2p + (p.y & 1, p.x & 1) of level L-1. Why a pick and not a filter: a horizon
 * search asks "is there a surface at this depth here", and any blend of a foreground and a
 * background depth (a plain average, or XeGTAO's weighted average, which still blends depths
 * within its falloff range of the farthest one) answers with a surface floating between them at
 * silhouettes, which then occludes the background as a false horizon. A pick returns a depth that
 * some level-0 pixel under the texel really has, so every level holds only real surface points.
 * Why the rotated grid and not min or max (also picks): min dilates every foreground object by
 * up to 2^L - 1 pixels at level L (dark halos on the background), max erodes them (thin occluders
 * vanish from coarse levels), and a fixed child (always the top-left one) shifts the image by half
 * a texel per level; the rotated grid varies the child over each 2x2 of texels, so over a 4x4
 * footprint every row and column is sampled once, without a bias in x, y or z (§2.2).
 *
 * Sky (depth 0, no geometry) is picked like any depth: every texel holds the depth of the one
 * level-0 pixel its picks lead to, so a reader that follows the same picks down reconstructs the
 * tap where that depth really is (slice_march.glsl ob_march_depth, taps.glsl). Taking the farthest
 * geometry of the four where the pick was sky (as this pass did first) put that depth at the sky
 * pixel's position, up to 2^L - 1 px off its own, and beside a silhouette against the sky such
 * a point floats in front of the surface: at 5x cornell's radius every MIP reader read darker
 * (alchemy -0.014 on average, gtao -0.006, vbao -0.006; with picks -0.001 to +0.001,
 * tests/test_methods.c). A sky texel is no sample, as a sky pixel is at level 0.
 *
 * Sizes are GL's (level L is max(1, size >> L)); a child beyond level L-1 (only where that level
 * is 1 texel wide) is clamped onto its last texel. The CPU twin, for the tests, is
 * ob_depth_mips_reference in src/passes/depth_mips.c. */
#include "depth_mips_params.h"

layout(local_size_x = OB_DEPTH_MIPS_GROUP, local_size_y = OB_DEPTH_MIPS_GROUP) in;

layout(binding = OB_UNIT_DEPTH) uniform sampler2D linear_depth;
/* Units 0..LEVELS-1 hold levels 0..LEVELS-1 (units beyond dm.levels hold the last level and are
 * never written: a texture too small for 5 levels cannot have them). */
layout(binding = OB_IMAGE_UNIT_DEPTH_MIPS, r32f) uniform writeonly image2D mips[OB_DEPTH_MIPS_LEVELS];

/* Level L of this group's tile lives in scratch[L & 1] (row stride GROUP), so a level reads one
 * array and writes the other; level L+1 overwrites level L-1 only after the barrier that follows
 * every read of it. */
shared float scratch[2][OB_DEPTH_MIPS_GROUP * OB_DEPTH_MIPS_GROUP];

ivec2 level_size(int level)
{
    return max(dm.size >> level, ivec2(1));
}

/* d00, d10, d01, d11: the children at 2p + (0,0), (1,0), (0,1), (1,1). */
float reduce(float d00, float d10, float d01, float d11, ivec2 p)
{
    int ox = p.y & 1, oy = p.x & 1;
    float picked = oy == 0 ? (ox == 0 ? d00 : d10) : (ox == 0 ? d01 : d11);
    return picked;
}

void store(int level, ivec2 p, float v)
{
    if (level < dm.levels && all(lessThan(p, level_size(level)))) imageStore(mips[level], p, vec4(v));
}

void main()
{
    const int G = OB_DEPTH_MIPS_GROUP;
    ivec2 t = ivec2(gl_LocalInvocationID.xy);
    ivec2 group = ivec2(gl_WorkGroupID.xy);

    /* Level 0, and level 1 from it: this thread's level-1 texel p and its 2x2 children, clamped
     * into the input (only a 1-pixel-wide input has a child beyond it). No early return: every
     * thread must reach the barriers. */
    ivec2 p = group * G + t;
    float d[4];
    for (int k = 0; k < 4; ++k) {
        ivec2 q = 2 * p + ivec2(k & 1, k >> 1);
        d[k] = texelFetch(linear_depth, min(q, dm.size - 1), 0).r;
        store(0, q, d[k]);
    }
    float v = reduce(d[0], d[1], d[2], d[3], p);
    store(1, p, v);
    scratch[1][t.y * G + t.x] = v;

    /* Levels 2.. from shared memory: at level L the group's tile is n = G >> (L-1) texels wide, and
     * level L-1's is 2n wide starting at group * 2n. */
    for (int level = 2; level < OB_DEPTH_MIPS_LEVELS; ++level) {
        memoryBarrierShared();
        barrier();
        int n = G >> (level - 1);
        if (all(lessThan(t, ivec2(n)))) {
            p = group * n + t;
            ivec2 below = level_size(level - 1);
            int src = (level - 1) & 1;
            for (int k = 0; k < 4; ++k) {
                /* Clamped onto level L-1, then into this tile: a texel of level L that lies inside
                 * its level reads children inside the tile; the second clamp only keeps the
                 * (never stored) texels beyond the level from reading outside the array. */
                ivec2 c = min(2 * p + ivec2(k & 1, k >> 1), below - 1) - group * 2 * n;
                c = clamp(c, ivec2(0), ivec2(2 * n - 1));
                d[k] = scratch[src][c.y * G + c.x];
            }
            v = reduce(d[0], d[1], d[2], d[3], p);
            scratch[level & 1][t.y * G + t.x] = v;
            store(level, p, v);
        }
    }
}
