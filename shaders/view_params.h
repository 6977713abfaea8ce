/* The present pass's debug views (ob_present): one texture of the last frame mapped to display
 * bytes, as the CLI's --view images (app/render.c view_image). */
#ifndef OB_VIEW_PARAMS_H
#define OB_VIEW_PARAMS_H
#include "ob_shared.h"

#define OB_VIEW_GROUP_X 8
#define OB_VIEW_GROUP_Y 8

/* mode.x: the view, OB_VIEW_MODE_* of ob_enums.h. */

OB_CONSTANTS_BEGIN(ob_view_constants, OB_BINDING_PASS)
    OB_VEC4 size;     /* width, height; depth: the far plane; samples: 1 / the most a pixel could take */
    OB_IVEC4 mode;    /* the view; directional (1: the source holds SSDO's RGB M or bounce, 0: AO
                         in .r / no bounce); samples: the count, 1 = scaled by the multiplier */
    OB_IVEC4 grid;    /* samples: AO pixels per full pixel k, unused x3 */
OB_CONSTANTS_END(ob_view_constants, vw)

#endif
