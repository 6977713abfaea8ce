/* shaders/ob_enums.h repeats the public enums as numbers GLSL can use; here the compiler checks
 * that the two agree, so a new enum value cannot drift between C and the shaders. */
#include "ob_enums.h"
#include "obscura/scene.h"
#include "sampling/sampling.h"

_Static_assert(OB_LIGHT_TYPE_DIRECTIONAL == OB_LIGHT_DIRECTIONAL && OB_LIGHT_TYPE_POINT == OB_LIGHT_POINT &&
                   OB_LIGHT_TYPE_SPOT == OB_LIGHT_SPOT,
               "ob_enums.h light types are ob_light_type's values");
_Static_assert(OB_SHADOW_METHOD_NONE == OB_SHADOW_NONE && OB_SHADOW_METHOD_HARD == OB_SHADOW_HARD &&
                   OB_SHADOW_METHOD_PCF == OB_SHADOW_PCF && OB_SHADOW_METHOD_VSM == OB_SHADOW_VSM,
               "ob_enums.h shadow methods are ob_shadow_method's values");
_Static_assert(OB_AMBIENT_MODE_CONSTANT == OB_AMBIENT_CONSTANT && OB_AMBIENT_MODE_HEMISPHERE == OB_AMBIENT_HEMISPHERE &&
                   OB_AMBIENT_MODE_ENVIRONMENT == OB_AMBIENT_ENVIRONMENT,
               "ob_enums.h ambient modes are ob_ambient_mode's values");
_Static_assert(OB_VIEW_MODE_FINAL == OB_VIEW_FINAL && OB_VIEW_MODE_AO == OB_VIEW_AO &&
                   OB_VIEW_MODE_NORMALS == OB_VIEW_NORMALS && OB_VIEW_MODE_DEPTH == OB_VIEW_DEPTH &&
                   OB_VIEW_MODE_SHADOW == OB_VIEW_SHADOW && OB_VIEW_MODE_RADIANCE == OB_VIEW_RADIANCE &&
                   OB_VIEW_MODE_SAMPLES == OB_VIEW_SAMPLES && OB_VIEW_MODE_BOUNCE == OB_VIEW_BOUNCE &&
                   OB_VIEW_MODE_BENT_NORMALS == OB_VIEW_BENT_NORMALS && OB_VIEW_MODE_LUMINANCE == OB_VIEW_LUMINANCE &&
                   OB_VIEW_MODE_SECOND_DEPTH == OB_VIEW_SECOND_DEPTH && OB_VIEW_MODE_EXTRA == OB_VIEW_EXTRA &&
                   OB_VIEW_MODE_HISTORY_AGE == OB_VIEW_HISTORY_AGE && OB_VIEW_COUNT == 13 &&
                   OB_VIEW_LUMINANCE_LOG2_LO == OB_LUMINANCE_LOG2_LO &&
                   OB_VIEW_LUMINANCE_LOG2_HI == OB_LUMINANCE_LOG2_HI,
               "ob_enums.h view modes are ob_view's values");
_Static_assert(OB_SAMPLING_MODE_RANDOM == OB_SAMPLING_RANDOM && OB_SAMPLING_MODE_HALTON == OB_SAMPLING_HALTON &&
                   OB_DIRECTIONS_MODE_UNIFORM == OB_DIRECTIONS_UNIFORM &&
                   OB_DIRECTIONS_MODE_COSINE == OB_DIRECTIONS_COSINE,
               "ob_enums.h sampling modes are sampling.h's values");
