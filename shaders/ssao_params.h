/* Hemisphere SSAO constants (Puri 2024 §2.3/§3.3, Belonogov 2018 §3.2). Filled by src/methods/ssao.c. */
#ifndef OB_SSAO_PARAMS_H
#define OB_SSAO_PARAMS_H
#include "frame_params.h"

#define OB_SSAO_GROUP_X 8
#define OB_SSAO_GROUP_Y 8
#define OB_SSAO_MAX_SAMPLES 256
#define OB_SSAO_NOISE_SIZE 4

/* The camera and the AO grid are the frame's (frame_params.h: ao_proj, ao_proj_info, ao_size). */
OB_CONSTANTS_BEGIN(ob_ssao_constants, OB_BINDING_PASS)
    OB_FLOAT radius;        /* hemisphere radius, world units */
    OB_FLOAT bias;          /* depth bias, world units (the parameter x radius) */
    OB_FLOAT intensity;     /* AO = visibility^intensity */
    OB_INT samples;         /* kernel entries in use */
    OB_INT noise;           /* OB_NOISE_* rotation */
    OB_INT adaptive;        /* 1: take adaptive_base x the edge pass's multiplier samples (SSDO thesis §4.1) */
    OB_INT adaptive_base;   /* the base count the multiplier (1..3) scales */
    OB_FLOAT pad0;
    OB_VEC4 kernel[OB_SSAO_MAX_SAMPLES]; /* tangent-space hemisphere offsets (z along the normal), w unused */
OB_CONSTANTS_END(ob_ssao_constants, ssao)
OB_CONSTANTS_SIZE(ob_ssao_constants, 2 * 16 + OB_SSAO_MAX_SAMPLES * 16);

#endif
