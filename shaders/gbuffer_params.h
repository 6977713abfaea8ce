/* G-buffer raster pass constants. */
#ifndef OB_GBUFFER_PARAMS_H
#define OB_GBUFFER_PARAMS_H
#include "ob_shared.h"

/* A vertex's part label (scene/parts.c) carries this on top on a sheet, a part with holes in it:
 * the vertex shader takes it off into a flag (scene.h's OB_PART_SHEET, the same number). */
#define OB_PART_SHEET_FLAG 4096

OB_CONSTANTS_BEGIN(ob_gbuffer_constants, OB_BINDING_PASS)
    OB_MAT4 view;           /* world -> view, column-major */
    OB_MAT4 proj;           /* view -> clip */
    OB_MAT4 normal_matrix;  /* inverse-transpose of view's upper 3x3, in a mat4 */
    OB_VEC3 diffuse;        /* the material's diffuse colour, linear RGB (0.8 grey without a material) */
    OB_INT textured;        /* 1: a diffuse texture is bound at OB_UNIT_DIFFUSE_MAP and multiplies diffuse */
OB_CONSTANTS_END(ob_gbuffer_constants, gb)
OB_CONSTANTS_SIZE(ob_gbuffer_constants, 3 * 64 + 16);

#endif
