/* Constants of the depth MIP prefilter (src/passes/depth_mips.c, shaders/depth_mips.glsl): a MIP
 * chain of linear view depth for the horizon-based methods to read far taps from coarser levels
 * (McGuire, Mara & Luebke 2012, "Scalable Ambient Obscurance", HPG, §2.2). */
#ifndef OB_DEPTH_MIPS_PARAMS_H
#define OB_DEPTH_MIPS_PARAMS_H
#include "ob_shared.h"

/* OB_DEPTH_MIPS_LEVELS, the levels made by the one dispatch, is in ob_shared.h (the readers' taps
 * need it too). */
/* A work group is GROUP x GROUP threads; each reads a 2x2 quad of level 0 and owns one level-1
 * texel, so the group covers a TILE x TILE tile of level 0 and reduces it to one level-4 texel
 * in shared memory. 8x8 = 64 threads: two NVIDIA warps or one AMD wave64. */
#define OB_DEPTH_MIPS_GROUP 8
#define OB_DEPTH_MIPS_TILE (2 * OB_DEPTH_MIPS_GROUP)

#if (1 << (OB_DEPTH_MIPS_LEVELS - 1)) != OB_DEPTH_MIPS_TILE
#error "one work group reduces its tile to one texel of the last level: TILE must be 2^(LEVELS - 1)"
#endif

OB_CONSTANTS_BEGIN(ob_depth_mips_constants, OB_BINDING_PASS)
    OB_IVEC2 size;       /* level 0 (the input), px; level L is max(1, size >> L), GL's rule */
    OB_INT levels;       /* levels the texture has, 1..OB_DEPTH_MIPS_LEVELS (ob_depth_mips_level_count) */
    OB_FLOAT pad0;
OB_CONSTANTS_END(ob_depth_mips_constants, dm)
OB_CONSTANTS_SIZE(ob_depth_mips_constants, 16);

#endif
