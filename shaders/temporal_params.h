/* Constants of the temporal accumulation pass (src/passes/temporal.c, shaders/temporal.glsl): the
 * previous frame's camera as the AO grid saw it, and the history's rules. This frame's camera is the
 * per-frame block's (frame_params.h). */
#ifndef OB_TEMPORAL_PARAMS_H
#define OB_TEMPORAL_PARAMS_H
#include "frame_params.h"

#define OB_TEMPORAL_GROUP_X 8
#define OB_TEMPORAL_GROUP_Y 8
/* A history tap within this many pixel footprints (3D distance) of the reprojected point is kept on
 * any plane: the bilinear taps lie within sqrt(2) px of the point on a surface facing the camera,
 * and 2 leaves room for the grid's change of scale between two frames of a path. */
#define OB_TEMPORAL_NEAR_PIXELS 2.0

OB_CONSTANTS_BEGIN(ob_temporal_constants, OB_BINDING_PASS)
    OB_MAT4 to_prev_view;       /* this frame's view space -> the previous frame's (prev view x inv view) */
    OB_MAT4 prev_ao_proj;       /* the previous frame's projection as seen from the AO grid */
    OB_VEC4 prev_ao_proj_info;  /* 1/P00, 1/P11, P20, P21 of prev_ao_proj (common.glsl; ob_proj_info) */
    OB_INT history_valid;       /* 0: no history (first frame, new method, size or scale): age 0 everywhere */
    OB_FLOAT history_frames;    /* N: the blend never weighs the current frame below 1 / N */
    OB_FLOAT plane_tolerance;   /* a history tap is the same surface when it lies within this x depth of
                                   this point's tangent plane ... */
    OB_FLOAT normal_cos;        /* ... and its normal is within acos(normal_cos) of this point's */
    OB_FLOAT footprint_falloff; /* the history's age is multiplied by 2^(-falloff |log2 s|), s = the point's
                                   pixel footprint in the previous frame / in this one */
    OB_FLOAT detail;            /* A in [0, 1): the least share of one-pixel detail the history keeps under
                                   sub-pixel motion (the blend's bound, temporal.glsl 5); 0 = no bound */
    OB_INT has_motion;          /* 1: a host's motion vectors move each point (ob_host_frame.motion) */
    OB_FLOAT pad1;
    OB_VEC2 motion_scale;       /* the host's units -> full-resolution pixels, previous - current, +y up */
    OB_FLOAT pad2;
    OB_FLOAT pad3;
OB_CONSTANTS_END(ob_temporal_constants, tp)
OB_CONSTANTS_SIZE(ob_temporal_constants, 2 * 64 + 4 * 16);

#endif
