/* The per-frame block (docs/architecture.md "Conventions": one block at its own binding point that every
 * pass reads; no pass copies another's data): the camera, the AO grid, the lights, the ambient
 * light and the frame index. Filled once per frame by src/core/frame.c (ob_frame_constants_fill,
 * a pure function) and bound at OB_BINDING_FRAME beside each pass's own block, so lighting,
 * SSDO and compose read the same lights and a method reads the camera without a copy of it.
 * World space unless noted. */
#ifndef OB_FRAME_PARAMS_H
#define OB_FRAME_PARAMS_H
#include "ob_shared.h"

#define OB_MAX_LIGHTS 8

OB_CONSTANTS_BEGIN(ob_frame_constants, OB_BINDING_FRAME)
    OB_MAT4 view;            /* world -> view */
    OB_MAT4 inv_view;        /* view -> world */
    OB_MAT4 proj;            /* the full-resolution projection (column-major, OpenGL clip space) */
    OB_MAT4 ao_proj;         /* the same as seen from the AO grid: AO pixel i lies at full pixel k i + o
                                (src/core/frame.c grid_projection keeps reconstruction exact) */
    OB_VEC4 proj_info;       /* 1/P00, 1/P11, P20, P21 of proj: common.glsl ob_view_position;
                                orthographic: 1/P00, 1/P11, -P30, -P31 (ob_proj_info) */
    OB_VEC4 ao_proj_info;    /* the same of ao_proj */
    OB_VEC2 size;            /* full resolution, px */
    OB_VEC2 inv_size;        /* 1 / size */
    OB_VEC2 ao_size;         /* the AO grid, px: size / k rounded up (the methods' and filters' targets) */
    OB_VEC2 ao_inv_size;     /* 1 / ao_size */
    OB_INT ao_k;             /* full pixels per AO pixel: 1, 2 or 4 (ob_settings.ao_divisor) */
    OB_INT ao_o;             /* offset of the AO grid inside each k x k block */
    OB_UINT frame_index;     /* counts rendered frames, for noise that varies over time */
    OB_INT light_count;      /* lights in use, up to OB_MAX_LIGHTS */
    OB_INT ambient_mode;     /* OB_AMBIENT_MODE_* */
    OB_FLOAT near_z;         /* the camera's planes, world units */
    OB_FLOAT far_z;
    OB_FLOAT noise_turn;     /* ob_settings.temporal: the per-frame turn (fraction of a circle) of every
                                random-kernel method's rotation noise (noise.glsl), 0 otherwise */
    OB_INT orthographic;     /* 1: proj is orthographic (P23 = 0, P33 = 1): view rays are parallel to -Z,
                                and screen sizes do not shrink with depth (common.glsl ob_depth_scale,
                                ob_view_ray); 0: perspective (every ob_render_frame) */
    OB_FLOAT pad0;
    OB_FLOAT pad1;
    OB_FLOAT pad2;
    OB_VEC4 ambient;         /* constant ambient radiance (rgb) */
    OB_VEC4 sky;             /* hemisphere ambient: radiance from +Y (rgb) */
    OB_VEC4 ground;          /* hemisphere ambient: radiance from -Y (rgb) */
    OB_VEC4 background;      /* radiance of pixels with no geometry, constant ambient (rgb) */
    OB_VEC4 sh[9];           /* environment: irradiance / pi SH (rgb), order l = 0..2
                                (src/passes/environment.c; Ramamoorthi & Hanrahan 2001, eq. 13) */
    OB_VEC4 light_color[OB_MAX_LIGHTS];     /* rgb x intensity; w = OB_LIGHT_TYPE_* */
    OB_VEC4 light_position[OB_MAX_LIGHTS];  /* point/spot position; w = range (0 = none) */
    OB_VEC4 light_direction[OB_MAX_LIGHTS]; /* directional: unit, toward the light; spot: unit axis
                                               from the light; w = shadow map index, -1 = unshadowed
                                               (src/passes/shadow.c ob_shadows_fill) */
    OB_VEC4 light_spot[OB_MAX_LIGHTS];      /* cos(inner half-angle), cos(outer half-angle), unused x2 */
OB_CONSTANTS_END(ob_frame_constants, frame)
OB_CONSTANTS_SIZE(ob_frame_constants, 4 * 64 + 2 * 16 + 2 * 16 + 3 * 16 + 4 * 16 + 9 * 16 + 4 * 8 * 16);

#endif
