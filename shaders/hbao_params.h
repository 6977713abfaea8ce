/* Horizon-based AO constants (Bavoil & Sainz 2008; Belonogov 2018 §3.3 eq. 3.1-3.2, Puri 2024 §2.4 and
 * §3.4). Filled by src/methods/hbao.c. */
#ifndef OB_HBAO_PARAMS_H
#define OB_HBAO_PARAMS_H
#include "frame_params.h"

#define OB_HBAO_GROUP_X 8
#define OB_HBAO_GROUP_Y 8
#define OB_HBAO_MAX_DIRECTIONS 32
#define OB_HBAO_MAX_STEPS 32
#define OB_HBAO_NOISE_SIZE 4

/* The camera and the AO grid are the frame's (frame_params.h: ao_proj_info, ao_size). */
OB_CONSTANTS_BEGIN(ob_hbao_constants, OB_BINDING_PASS)
    OB_FLOAT radius;        /* horizon search radius R, world units */
    OB_FLOAT inv_radius;    /* 1 / R: W = 1 - r/R */
    OB_FLOAT px_per_unit;   /* pixels per world unit at depth 1: (height / 2) x P11 of the AO grid */
    OB_FLOAT max_radius_px; /* upper bound on the projected radius */
    OB_FLOAT sin_bias;      /* sin and cos of the angle bias added to the tangent angle */
    OB_FLOAT cos_bias;
    OB_FLOAT intensity;     /* AO = 1 - intensity x occlusion */
    OB_INT directions;      /* N_d */
    OB_INT steps;           /* N_s per direction */
    OB_INT noise;           /* OB_NOISE_* rotation and step jitter */
    OB_INT adaptive;        /* 1: per-pixel directions, adaptive_base x the multiplier (OB_UNIT_SAMPLE_MULTIPLIER) */
    OB_INT adaptive_base;   /*   the directions at multiplier 1 (SSDO thesis §4.1) */
OB_CONSTANTS_END(ob_hbao_constants, hbao)
OB_CONSTANTS_SIZE(ob_hbao_constants, 3 * 16);

#endif
