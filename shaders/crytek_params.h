/* Crytek SSAO constants (Puri 2024 §2.2; Mittring 2007). Filled by src/methods/crytek.c. */
#ifndef OB_CRYTEK_PARAMS_H
#define OB_CRYTEK_PARAMS_H
#include "frame_params.h"

#define OB_CRYTEK_GROUP_X 8
#define OB_CRYTEK_GROUP_Y 8
#define OB_CRYTEK_MAX_SAMPLES 256

/* The camera and the AO grid are the frame's (frame_params.h: ao_proj, ao_proj_info, ao_size). */
OB_CONSTANTS_BEGIN(ob_crytek_constants, OB_BINDING_PASS)
    OB_FLOAT radius;        /* sphere radius, world units */
    OB_FLOAT bias;          /* depth bias, world units (the parameter x radius) */
    OB_FLOAT intensity;     /* AO = visibility^intensity */
    OB_INT correction;      /* 1: SSDO thesis §5.4's AO' = min(1, 2 AO) */
    OB_INT samples;         /* kernel entries in use */
    OB_INT noise;           /* OB_NOISE_* rotation */
    OB_INT adaptive;        /* 1: take adaptive_base x the edge pass's multiplier samples (SSDO thesis §4.1) */
    OB_INT adaptive_base;   /* the base count the multiplier (1..3) scales */
    OB_VEC4 kernel[OB_CRYTEK_MAX_SAMPLES]; /* offsets inside the unit sphere, w unused */
OB_CONSTANTS_END(ob_crytek_constants, crytek)
OB_CONSTANTS_SIZE(ob_crytek_constants, 2 * 16 + OB_CRYTEK_MAX_SAMPLES * 16);

#endif
