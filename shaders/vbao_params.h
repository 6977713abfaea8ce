/* Visibility-bitmask constants (Therrien, Levesque & Gilet 2023, "Screen Space Indirect Lighting
 * with Visibility Bitmask"), shared by `vbao` and `vbgi`. Filled by src/methods/vbao.c; the
 * camera and the AO grid are the frame's (frame_params.h). */
#ifndef OB_VBAO_PARAMS_H
#define OB_VBAO_PARAMS_H
#include "frame_params.h"

#define OB_VB_GROUP_X 8
#define OB_VB_GROUP_Y 8
#define OB_VB_MAX_SLICES 32
#define OB_VB_MAX_STEPS 32

OB_CONSTANTS_BEGIN(ob_vb_constants, OB_BINDING_PASS)
    OB_FLOAT radius;          /* R of AO_R, world units: a sample counts where it lies within R */
    OB_FLOAT thickness;       /* a sample's thickness behind its front, world units: */
    OB_FLOAT thickness_slope; /*   thickness + thickness_slope x the sample's linear depth */
    OB_INT weighting;         /* OB_DIRECTIONS_MODE_*: sectors weighted uniformly in angle or by the cosine */
    OB_INT slices;            /* N_slices: screen directions over [0, π) */
    OB_INT steps;             /* steps on each side of each slice */
    OB_INT noise;             /* OB_NOISE_* per-pixel slice and step jitter */
    OB_FLOAT slice_offset;    /* added to the per-pixel jitters, from the frame index (R2 sequence) */
    OB_FLOAT step_offset;     /*   when temporal noise is on; 0 otherwise */
    OB_FLOAT mip_scale;       /* as gtao_params.h: a step at x px reads level floor(log2(x mip_scale)) */
    OB_INT max_mip;           /* the coarsest MIP level a step may read (the OB_MARCH_DEPTH_MIPS program) */
    OB_INT emitter_cosine;    /* vbgi: 1 = a sender's radiance x its cosine toward P (the paper's),
                                 0 = the radiance itself where the sender faces P */
    OB_INT adaptive;          /* 1: per-pixel slices, adaptive_base x the multiplier (OB_UNIT_SLICE_MULTIPLIER) */
    OB_INT adaptive_base;     /*   the slices at multiplier 1 (SSDO thesis §4.1) */
    OB_INT layers;            /* 1: a sample's back is the second depth layer behind it (OB_UNIT_SECOND_DEPTH) */
    OB_INT pad0;              /* (the joining rule `connect` and the facet wedge `facets` are the
                                 program's: OB_VB_CONNECT, OB_MARCH_FACETS) */
OB_CONSTANTS_END(ob_vb_constants, vb)
OB_CONSTANTS_SIZE(ob_vb_constants, 4 * 16);

#endif
