/* Constants of the floor kernel (src/passes/floor.c, shaders/floor.glsl): the bare N-tap compute
 * kernel that `obscura bench --floor` times beside every AO pass (docs/architecture.md "Performance method"). */
#ifndef OB_FLOOR_PARAMS_H
#define OB_FLOOR_PARAMS_H
#include "ob_shared.h"

/* 8x8 work groups, as every AO method dispatches (OB_SSAO_GROUP_X ... OB_VB_GROUP_Y): the same
 * footprint per group, so the same texture-cache behaviour between neighbouring invocations. */
#define OB_FLOOR_GROUP_X 8
#define OB_FLOOR_GROUP_Y 8
/* The most taps a method asks for: gtao and vbao at 32 slices x 32 steps x 2 sides. The tap table
 * lives in a storage buffer (a uniform block is only guaranteed 16 KiB). */
#define OB_FLOOR_MAX_TAPS 2048
/* Per-pixel rotations: a 4x4 tile, as the methods' noise tile (shaders/noise.glsl). */
#define OB_FLOOR_ROTATIONS 16
/* Binding of the tap table (a std430 storage buffer). */
#define OB_FLOOR_TAPS_BINDING 0

OB_CONSTANTS_BEGIN(ob_floor_constants, OB_BINDING_PASS)
    OB_IVEC2 size;          /* the AO grid, px: input and output */
    OB_INT taps;            /* entries of the tap table in use */
    OB_FLOAT radius;        /* the method's R, world units */
    OB_FLOAT px_per_unit;   /* R_px = radius x px_per_unit / d (d = the pixel's linear depth) */
    OB_FLOAT max_radius_px; /* the method's clamp of R_px (hbao.max_radius_px), else a huge value */
    OB_FLOAT pad0;
    OB_FLOAT pad1;
    OB_VEC4 rotation[OB_FLOOR_ROTATIONS]; /* cos, sin of tile pixel (x & 3) + 4 (y & 3); zw unused */
OB_CONSTANTS_END(ob_floor_constants, fl)
OB_CONSTANTS_SIZE(ob_floor_constants, 2 * 16 + OB_FLOOR_ROTATIONS * 16);

#endif
