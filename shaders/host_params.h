/* Constants of the host path's two passes (src/passes/host.c): the input pass (shaders/
 * host_input.glsl: the host's depth linearised, its normals decoded into view space or rebuilt from
 * depth) and the output pass (shaders/host_output.glsl: the AO chain's results cropped to the
 * visible frame in the host's formats). */
#ifndef OB_HOST_PARAMS_H
#define OB_HOST_PARAMS_H
#include "ob_shared.h"

#define OB_HOST_GROUP_X 8
#define OB_HOST_GROUP_Y 8

/* The input pass's program variants (host.c defines OB_HOST_DEPTH_KIND, OB_HOST_NORMAL_ENCODING
 * and OB_HOST_SECOND as one of these each): compile-time, not uniform branches, because llvmpipe
 * runs an untaken uniform branch masked, paying for its fetches and stores all the same. */
/* How the input pass reads the host's depth (OB_HOST_DEPTH_KIND). */
#define OB_HOST_DEPTH_LINEAR 0   /* R16F/R32F positive view depth, 0 = sky */
#define OB_HOST_DEPTH_WINDOW 1   /* a depth buffer's window depth through the projection */

/* How it reads the normals (OB_HOST_NORMAL_ENCODING). */
#define OB_HOST_NORMAL_NONE 0       /* rebuilt from depth */
#define OB_HOST_NORMAL_RAW 1        /* xyz as stored (RGBA16F, RGBA32F) */
#define OB_HOST_NORMAL_UNORM 2      /* xyz * 2 - 1 (RGB10_A2, RGBA8) */
#define OB_HOST_NORMAL_OCT 3        /* octahedral in [-1, 1] (RG16F, RG16_SNORM) */
#define OB_HOST_NORMAL_OCT_UNORM 4  /* octahedral * 0.5 + 0.5 (RG8) */
#define OB_HOST_NORMAL_ENCODINGS 5

OB_CONSTANTS_BEGIN(ob_host_input_constants, OB_BINDING_PASS)
    OB_MAT4 normal_to_view;   /* world -> view rotation for world-space normals; identity otherwise */
    OB_IVEC2 size;            /* the input size, px */
    OB_INT orthographic;      /* 1: P23 = 0, P33 = 1 */
    OB_INT reversed;          /* 1: window depth falls with distance, so the sky (cleared) is 0, else 1 */
    /* Window depth w -> NDC z = w * ndc_scale + ndc_bias (2, -1 for GL's default depth range; 1, 0
     * under glClipControl's GL_ZERO_TO_ONE), then view depth from the projection's z row:
     * perspective d = P32 / (ndc + P22), orthographic d = (P32 - ndc) / P22. */
    OB_FLOAT ndc_scale;
    OB_FLOAT ndc_bias;
    OB_FLOAT p22;
    OB_FLOAT p32;
OB_CONSTANTS_END(ob_host_input_constants, hi)
OB_CONSTANTS_SIZE(ob_host_input_constants, 64 + 2 * 16);

/* What the output pass makes of its source (ob_host_output_constants.mode). */
#define OB_HOST_OUT_COPY 0     /* as it is: one channel to R, RGBA to RGBA */
#define OB_HOST_OUT_MEAN 1     /* RGB to one channel: the mean (a directional method's M into R) */
#define OB_HOST_OUT_GREY 2     /* one channel to RGB (visibility into an RGBA output) */
#define OB_HOST_OUT_NORMAL 3   /* a view-space bent normal, renormalised, turned by `turn` */

OB_CONSTANTS_BEGIN(ob_host_output_constants, OB_BINDING_PASS)
    OB_MAT4 turn;             /* view -> the host's normal space (OB_HOST_OUT_NORMAL) */
    OB_IVEC2 size;            /* the visible size, px */
    OB_IVEC2 offset;          /* the guard band: visible pixel p is source pixel p + offset */
    OB_INT mode;              /* OB_HOST_OUT_* */
    OB_FLOAT pad0;
    OB_FLOAT pad1;
    OB_FLOAT pad2;
OB_CONSTANTS_END(ob_host_output_constants, ho)
OB_CONSTANTS_SIZE(ob_host_output_constants, 64 + 2 * 16);

#endif
