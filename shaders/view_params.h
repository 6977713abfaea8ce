/* The present pass's debug views (ob_present): one texture of the last frame mapped to display
 * bytes, as the CLI's --view images (app/render.c view_image). */
#ifndef OB_VIEW_PARAMS_H
#define OB_VIEW_PARAMS_H
#include "ob_shared.h"

#define OB_VIEW_GROUP_X 8
#define OB_VIEW_GROUP_Y 8

OB_CONSTANTS_BEGIN(ob_view_constants, OB_BINDING_PASS)
    OB_INT view_mode;         /* OB_VIEW_MODE_* of ob_enums.h (ob_view_inputs.view) */
    OB_INT directional;       /* 1: the source holds SSDO's RGB M or bounce; 0: AO in .r, no bounce */
    OB_INT sample_count;      /* samples: the method's count, or the adaptive base count */
    OB_INT use_multiplier;    /* samples: 1 = adaptive, sample_count x the edge pass's per-block value */
    OB_INT ao_k;              /* samples: full pixels per AO pixel, to find a pixel's block */
    OB_FLOAT far_z;           /* depth: the far plane, view-space units; grey = 1 - depth / far_z */
    OB_FLOAT inv_max_samples; /* samples: 1 / the most a pixel could take, which shows white */
    OB_INT offset;            /* display pixel p shows source pixel p + offset (the guard band, renderer.h) */
    OB_IVEC2 size;            /* the display texture, px */
    OB_FLOAT inv_history_frames; /* history_age: 1 / the history length, 0 = no history (black) */
    OB_FLOAT pad2;
OB_CONSTANTS_END(ob_view_constants, vw)
OB_CONSTANTS_SIZE(ob_view_constants, 3 * 16);

#endif
