/* Screen-space directional occlusion constants (Ritschel et al. 2009 as described in SSDO thesis
 * §3.3; SSDO thesis §4.2's merged one-pass variant; Belonogov 2018 §4.1-4.2). Filled by src/methods/ssdo.c.
 * The camera, the AO grid, the lights and the ambient light are the frame's (frame_params.h). */
#ifndef OB_SSDO_PARAMS_H
#define OB_SSDO_PARAMS_H
#include "frame_params.h"

#define OB_SSDO_GROUP_X 8
#define OB_SSDO_GROUP_Y 8
#define OB_SSDO_MAX_SAMPLES 256

/* ob_ssdo_constants.stage: which output a dispatch writes */
#define OB_SSDO_STAGE_DIRECT 0 /* `ssdo` pass 1: M from uniform directions (eq. 5.3) */
#define OB_SSDO_STAGE_MERGED 1 /* `ssdo_merged`: M (cosine directions, eq. 5.2) + bounce x M */
#define OB_SSDO_STAGE_BOUNCE 2 /* `ssdo` pass 2: the bounce from the same occluders (eq. 3.4) */
#define OB_SSDO_STAGE_BOTH 3   /* `ssdo` fused: passes 1 and 2 in one dispatch, the same samples taken once */

OB_CONSTANTS_BEGIN(ob_ssdo_constants, OB_BINDING_PASS)
    OB_FLOAT radius;        /* sampling hemisphere radius, world units */
    OB_FLOAT bias;          /* depth bias, world units (the parameter x radius) */
    OB_FLOAT bounce_scale;  /* eq. 3.4's sender patch area A_s = pi r^2 / N over pi, x bounce_strength */
    OB_FLOAT lobe;          /* lights as cosine lobes max(0, w.l)^k: k */
    OB_INT samples;         /* kernel entries in use */
    OB_INT noise;           /* OB_NOISE_* rotation */
    OB_INT bounce;          /* 1: gather the bounce (eq. 3.4); 0: write a black one */
    OB_INT stage;           /* OB_SSDO_STAGE_*: which output this dispatch writes */
    OB_INT adaptive;        /* 1: per-pixel samples, adaptive_base x the multiplier (OB_UNIT_SSDO_MULTIPLIER), the
                               first of the kernel's 3 x adaptive_base Halton entries */
    OB_INT adaptive_base;
    OB_INT layers;          /* 1: a sample behind the second depth layer (OB_UNIT_SECOND_DEPTH) is free */
    OB_INT extra_view;      /* 1: the extra view (OB_UNIT_EXTRA_*) tests occluders and sends bounces too */
    OB_MAT4 extra_from_view; /* this frame's view space -> the extra camera's */
    OB_MAT4 extra_to_view;   /* and back */
    OB_MAT4 extra_proj;      /* the extra camera's projection */
    OB_VEC4 extra_proj_info; /* its 1/P00, 1/P11, P20, P21 (ob_view_position) */
    OB_VEC4 kernel[OB_SSDO_MAX_SAMPLES]; /* tangent-space unit direction xyz, step length w */
OB_CONSTANTS_END(ob_ssdo_constants, ssdo)
OB_CONSTANTS_SIZE(ob_ssdo_constants, 3 * 16 + 3 * 64 + 16 + OB_SSDO_MAX_SAMPLES * 16);

#endif
