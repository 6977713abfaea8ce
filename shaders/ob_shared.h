/* Types shared by C and GLSL so each pass's std140 constant block is declared once
 * (the XeGTAO.h pattern). Keep every member a vec4, ivec4 or mat4: std140 then lays them out
 * exactly like the C struct, with no hidden padding. */
#ifndef OB_SHARED_H
#define OB_SHARED_H

#ifdef OB_GLSL
#define OB_VEC4 vec4
#define OB_IVEC4 ivec4
#define OB_MAT4 mat4
#define OB_CONSTANTS_BEGIN(type, binding_point) layout(std140, binding = binding_point) uniform type##_block {
#define OB_CONSTANTS_END(type, instance) } instance;
#else
typedef float ob_gl_vec4[4];
typedef int ob_gl_ivec4[4];
typedef float ob_gl_mat4[16];
#define OB_VEC4 ob_gl_vec4
#define OB_IVEC4 ob_gl_ivec4
#define OB_MAT4 ob_gl_mat4
#define OB_CONSTANTS_BEGIN(type, binding_point) typedef struct type {
#define OB_CONSTANTS_END(type, instance) } type;
#endif

/* The adaptive-sampling edge pass works on blocks of this many AO pixels per side (seed 003
 * §4.1: computed "in much lower resolutions" to get wider areas around discontinuities); the
 * methods read their block's sample multiplier at pixel / OB_EDGE_BLOCK. */
#define OB_EDGE_BLOCK 4

/* Uniform-buffer binding points, one per constant block in a pass. */
#define OB_BINDING_PASS 0

#endif
