/* Constants of the subsampling passes: downsample (full -> AO resolution), upsample (joint
 * bilateral, AO -> full resolution) and the adaptive-sampling edge pass. */
#ifndef OB_RESAMPLE_PARAMS_H
#define OB_RESAMPLE_PARAMS_H
#include "ob_shared.h"

#define OB_RESAMPLE_GROUP_X 8
#define OB_RESAMPLE_GROUP_Y 8

/* The grid (ob_resample_fill, shared by the three passes), then each pass's own members, named
 * for it and left 0 by the other two. */
OB_CONSTANTS_BEGIN(ob_resample_constants, OB_BINDING_PASS)
    OB_IVEC2 full_size;              /* the G-buffer, px */
    OB_IVEC2 ao_size;                /* the AO grid, px: full_size / ao_k rounded up */
    OB_INT ao_k;                     /* full pixels per AO pixel along each axis: 1, 2 or 4 */
    OB_INT ao_o;                     /* AO pixel i stands for full pixel ao_k i + ao_o (ob_ao_grid_make) */
    /* upsample: the depth guide's sigma on |d_q - d_p| / d_p (unitless; eq. 3.12's g) */
    OB_FLOAT upsample_depth_sigma;
    OB_FLOAT upsample_sky_value;     /* upsample, RGB variant: sky pixels' value, 1 for M, 0 for the bounce */
    OB_FLOAT edge_depth_step;        /* edges: relative depth step between neighbours that makes an edge */
    OB_FLOAT edge_normal_turn;       /* edges: 1 - cos(angle) between neighbours' normals that makes an edge */
    OB_FLOAT pad0;
    OB_FLOAT pad1;
OB_CONSTANTS_END(ob_resample_constants, rs)
OB_CONSTANTS_SIZE(ob_resample_constants, 3 * 16);

#endif
