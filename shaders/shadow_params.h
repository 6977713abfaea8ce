/* Shadow maps (SSDO thesis §2.1, §5.1, §6.1): the limits the C side clamps to, and the constant
 * blocks of the two passes that make the maps (the depth raster pass and the VSM moments + blur
 * compute pass). Shared by src/passes/shadow.c and shaders/shadow*.glsl. The texture units the
 * maps are sampled at are OB_UNIT_SHADOW_* in ob_units.h; the lighting constants' shadow_*
 * members live in lighting_params.h. */
#ifndef OB_SHADOW_PARAMS_H
#define OB_SHADOW_PARAMS_H
#include "ob_shared.h"

/* PCF taps each side: 8 gives a 17x17 kernel of bilinear comparisons, already 289 lookups. */
#define OB_SHADOW_MAX_PCF_RADIUS 8
/* VSM blur taps each side (radius = ceil(2 sigma), so sigma up to 8 texels). */
#define OB_SHADOW_VSM_MAX_RADIUS 16
/* tan of the angle to the light is clamped here (~84 degrees): beyond it the slope-scaled bias
 * would push the reference through thin walls, and n.l < 0.1 leaves almost no light to shadow. */
#define OB_SHADOW_MAX_SLOPE 10.0

#define OB_SHADOW_GROUP_X 8
#define OB_SHADOW_GROUP_Y 8
/* VSM blur: texels per invocation along the blur axis (shadow_vsm.glsl). */
#define OB_SHADOW_VSM_RUN 8

/* The depth pass: world -> light clip space, and for spot/point maps the light position and
 * 1/far, so the fragment shader stores the linear distance to the light / far. */
#if !defined(OB_GLSL) || defined(OB_SHADOW_DEPTH_PASS)
OB_CONSTANTS_BEGIN(ob_shadow_depth_constants, OB_BINDING_PASS)
    OB_MAT4 view_proj;       /* world -> light clip space */
    OB_VEC3 light_position;  /* spot, point: the light (world) the stored distance is measured from */
    OB_FLOAT inv_far;        /* spot, point: 1 / far, so the map stores distance / far in [0, 1] */
OB_CONSTANTS_END(ob_shadow_depth_constants, shd)
OB_CONSTANTS_SIZE(ob_shadow_depth_constants, 64 + 16);
#endif

/* One direction of the VSM blur (SSDO thesis §5.1: "first vertically, then horizontally"; the order
 * does not change a separable Gaussian). The x pass turns depth into moments as it reads. */
#if !defined(OB_GLSL) || defined(OB_SHADOW_VSM_PASS)
OB_CONSTANTS_BEGIN(ob_shadow_vsm_constants, OB_BINDING_PASS)
    OB_IVEC2 axis;     /* the blur's direction: (1,0) or (0,1) */
    OB_INT radius;     /* taps each side */
    OB_INT layer;      /* layer of the depth / moments array */
    OB_IVEC2 size;     /* map width and height, texels */
    OB_FLOAT pad0;
    OB_FLOAT pad1;
    OB_VEC4 weights[OB_SHADOW_VSM_MAX_RADIUS + 1]; /* normalised Gaussian w[0..radius] in .x, yzw unused */
OB_CONSTANTS_END(ob_shadow_vsm_constants, vsm)
OB_CONSTANTS_SIZE(ob_shadow_vsm_constants, 2 * 16 + (OB_SHADOW_VSM_MAX_RADIUS + 1) * 16);
#endif

#endif
