/* Constants of the subsampling passes: downsample (full -> AO resolution), upsample (joint
 * bilateral, AO -> full resolution) and the adaptive-sampling edge pass. */
#ifndef OB_RESAMPLE_PARAMS_H
#define OB_RESAMPLE_PARAMS_H
#include "ob_shared.h"

#define OB_RESAMPLE_GROUP_X 8
#define OB_RESAMPLE_GROUP_Y 8

OB_CONSTANTS_BEGIN(ob_resample_constants, OB_BINDING_PASS)
    OB_IVEC4 full_size;  /* full width, height; AO width, height */
    OB_IVEC4 factor;     /* k (full pixels per AO pixel), o (the representative sub-pixel), unused */
    OB_VEC4 sigma;       /* upsample: depth sigma (relative), the sky value of the RGB variant; edges: depth
                            step, normal turn thresholds */
OB_CONSTANTS_END(ob_resample_constants, rs)

#endif
