/* Alchemy AO constants (McGuire et al. 2011; Puri 2024 §2.5, §3.4). Filled by src/methods/alchemy.c. */
#ifndef OB_ALCHEMY_PARAMS_H
#define OB_ALCHEMY_PARAMS_H
#include "frame_params.h"

#define OB_ALCHEMY_GROUP_X 8
#define OB_ALCHEMY_GROUP_Y 8

/* The camera and the AO grid are the frame's (frame_params.h: ao_proj_info, ao_size). */
OB_CONSTANTS_BEGIN(ob_alchemy_constants, OB_BINDING_PASS)
    OB_FLOAT radius;        /* world-space disk radius r */
    OB_FLOAT sigma;         /* intensity scale sigma (McGuire et al. 2011 eq. 10) */
    OB_FLOAT k;             /* contrast exponent k */
    OB_FLOAT beta;          /* bias distance beta, x |z_C| */
    OB_FLOAT epsilon;       /* epsilon against division by zero */
    OB_FLOAT turns;         /* spiral turns tau */
    OB_FLOAT px_per_unit;   /* pixels per world unit at depth 1: (height / 2) x P11 of the AO grid */
    OB_INT samples;         /* spiral samples s */
    OB_INT noise;           /* OB_NOISE_* rotation */
    OB_INT adaptive;        /* 1: per-pixel samples, adaptive_base x the multiplier (OB_UNIT_SAMPLE_MULTIPLIER) */
    OB_INT adaptive_base;   /*   the samples at multiplier 1 (SSDO thesis §4.1) */
    OB_FLOAT pad0;
OB_CONSTANTS_END(ob_alchemy_constants, alchemy)
OB_CONSTANTS_SIZE(ob_alchemy_constants, 3 * 16);

#endif
