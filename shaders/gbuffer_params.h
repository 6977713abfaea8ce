/* G-buffer raster pass constants. */
#ifndef OB_GBUFFER_PARAMS_H
#define OB_GBUFFER_PARAMS_H
#include "ob_shared.h"

OB_CONSTANTS_BEGIN(ob_gbuffer_constants, OB_BINDING_PASS)
    OB_MAT4 view;
    OB_MAT4 proj;
    OB_MAT4 normal_matrix;  /* inverse-transpose of view's upper 3x3, in a mat4 */
    OB_VEC4 diffuse;        /* material diffuse colour (linear), a = 1 when a texture is bound */
OB_CONSTANTS_END(ob_gbuffer_constants, gb)

#endif
