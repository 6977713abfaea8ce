/* Types shared by C and GLSL so each pass's std140 constant block is declared once
 * (the XeGTAO.h pattern: one header, two languages).
 *
 * Layout rules that keep the C struct and the std140 block byte-identical without hidden padding:
 *   - members come in 16-byte rows: four scalars (OB_FLOAT / OB_INT / OB_UINT), two OB_VEC2 /
 *     OB_IVEC2, one OB_VEC3 followed by one scalar, or one OB_VEC4 / OB_IVEC4; OB_MAT4 is four rows;
 *   - a row that is not full is filled with explicit OB_FLOAT pad_N members;
 *   - arrays only of OB_VEC4 / OB_IVEC4 / OB_MAT4 (std140 gives every array element a 16-byte
 *     stride);
 *   - every block is followed by OB_CONSTANTS_SIZE(type, bytes), a static assert in C (a no-op in
 *     GLSL), so a member added without its padding fails to compile. */
#ifndef OB_SHARED_H
#define OB_SHARED_H

#include "ob_enums.h"
#include "ob_units.h"

#ifdef OB_GLSL
#define OB_FLOAT float
#define OB_INT int
#define OB_UINT uint
#define OB_VEC2 vec2
#define OB_IVEC2 ivec2
#define OB_VEC3 vec3
#define OB_VEC4 vec4
#define OB_IVEC4 ivec4
#define OB_MAT4 mat4
#define OB_CONSTANTS_BEGIN(type, binding_point) layout(std140, binding = binding_point) uniform type##_block {
#define OB_CONSTANTS_END(type, instance) } instance;
#define OB_CONSTANTS_SIZE(type, bytes)
#else
typedef float ob_gl_vec2[2];
typedef int ob_gl_ivec2[2];
typedef float ob_gl_vec3[3];
typedef float ob_gl_vec4[4];
typedef int ob_gl_ivec4[4];
typedef float ob_gl_mat4[16];
#define OB_FLOAT float
#define OB_INT int
#define OB_UINT unsigned int
#define OB_VEC2 ob_gl_vec2
#define OB_IVEC2 ob_gl_ivec2
#define OB_VEC3 ob_gl_vec3
#define OB_VEC4 ob_gl_vec4
#define OB_IVEC4 ob_gl_ivec4
#define OB_MAT4 ob_gl_mat4
#define OB_CONSTANTS_BEGIN(type, binding_point) typedef struct type {
#define OB_CONSTANTS_END(type, instance) } type;
#define OB_CONSTANTS_SIZE(type, bytes)                                                                \
    _Static_assert(sizeof(type) == (bytes) && (bytes) % 16 == 0,                                     \
                   #type " must be " #bytes " bytes in whole 16-byte rows (see shaders/ob_shared.h)")
#endif

/* The adaptive-sampling edge pass works on blocks of this many AO pixels per side (SSDO thesis
 * §4.1: computed "in much lower resolutions" to get wider areas around discontinuities); the
 * methods read their block's sample multiplier at pixel / OB_EDGE_BLOCK. */
#define OB_EDGE_BLOCK 4

/* A tap d px from its pixel reads level floor(log2 d - 3.3) of the depth MIP chain
 * (passes/depth_mips.c): full resolution nearer than 2^4.3 ≈ 20 px, and beyond, texels of 2^L px
 * at least 2^(L + 3.3) px out, a tenth of the distance or less (XeGTAO's DepthMIPSamplingOffset,
 * same reasoning). The slice march (slice_march.glsl, via methods/slices.c) and the random-kernel
 * methods' taps (taps.glsl) both. */
#define OB_DEPTH_MIPS_TAP_OFFSET 3.3
/* Levels of the depth MIP chain made by its one dispatch: 0 (a copy of the input) to 4, so a far
 * tap reads a 16x16 footprint of level 0 from one texel. XeGTAO keeps 5 as well
 * (XE_GTAO_DEPTH_MIP_LEVELS); with the tap level log2(offset px) - 3.3 it reaches level 4 for taps
 * about 160 px away. */
#define OB_DEPTH_MIPS_LEVELS 5

/* Uniform-buffer binding points: a pass's own constants, and the per-frame block (frame_params.h)
 * that every pass may read beside them. */
#define OB_BINDING_PASS 0
#define OB_BINDING_FRAME 1

#endif
