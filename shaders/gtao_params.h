/* Ground-truth ambient occlusion constants (Jimenez, Wu, Pesce & Jarabo 2016, "Practical
 * Realtime Strategies for Accurate Indirect Occlusion"). Filled by src/methods/gtao.c; the camera
 * and the AO grid are the frame's (frame_params.h). */
#ifndef OB_GTAO_PARAMS_H
#define OB_GTAO_PARAMS_H
#include "frame_params.h"

#define OB_GTAO_GROUP_X 8
#define OB_GTAO_GROUP_Y 8
#define OB_GTAO_MAX_SLICES 32
#define OB_GTAO_MAX_STEPS 32

OB_CONSTANTS_BEGIN(ob_gtao_constants, OB_BINDING_PASS)
    OB_FLOAT radius;          /* R of AO_R, world units: occluders count within it */
    OB_FLOAT falloff_mul;     /* occluder weight = clamp(distance * falloff_mul + falloff_add, 0, 1): */
    OB_FLOAT falloff_add;     /*   1 up to (1 - falloff) R, 0 from R on (a step at R when falloff = 0) */
    OB_FLOAT thin;            /* thin-occluder compensation: the depth part of a sample's distance x (1 + thin) */
    OB_INT slices;            /* N_slices: screen directions over [0, π) */
    OB_INT steps;             /* horizon-search steps on each side of each slice */
    OB_INT noise;             /* OB_NOISE_* per-pixel slice and step jitter */
    OB_INT depth_mips;        /* 1: far steps read the depth MIP chain (OB_UNIT_SLICE_DEPTH_MIPS) */
    OB_FLOAT slice_offset;    /* added to the per-pixel jitters, from the frame index (R2 sequence) */
    OB_FLOAT step_offset;     /*   when temporal noise is on; 0 otherwise */
    OB_FLOAT mip_scale;       /* 2^-offset: a step at distance x px reads level floor(log2(x mip_scale)), so
                                 steps nearer than 2^offset px read the full-resolution depth */
    OB_INT max_mip;           /* the coarsest MIP level a step may read */
    OB_INT bent_normals;      /* 1: also write the bent normal (image 1) */
    OB_INT adaptive;          /* 1: per-pixel slices, adaptive_base x the multiplier (OB_UNIT_SLICE_MULTIPLIER) */
    OB_INT adaptive_base;     /*   the slices at multiplier 1 (SSDO thesis §4.1) */
    OB_INT layers;            /* 1: the second layer (OB_UNIT_SECOND_DEPTH) bounds each sample's object */
    OB_FLOAT column;          /* world units: how far behind its front a sample beyond R is solid (its part
                                 inside R occludes: slice_march.glsl ob_column_entry); 0 = none */
    OB_FLOAT full_reach;      /* the distance up to which an occluder's weight is 1: (1 - falloff) R */
    OB_FLOAT column_shell2;   /* (full_reach + column)^2: a front farther from P cannot reach the sphere */
    OB_FLOAT pad0;            /* (the facet wedge `facets` is the program's: OB_MARCH_FACETS) */
OB_CONSTANTS_END(ob_gtao_constants, gtao)
OB_CONSTANTS_SIZE(ob_gtao_constants, 5 * 16);

#endif
