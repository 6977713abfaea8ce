/* Every enum that both C and GLSL need, declared once. The values are those of the public enums in
 * include/obscura/obscura.h; src/core/enums.c asserts that they agree, so GLSL can switch on the
 * numbers the C side stores. Plain #defines: GLSL 4.50 has no enums. */
#ifndef OB_ENUMS_H
#define OB_ENUMS_H

/* ob_light_type */
#define OB_LIGHT_TYPE_DIRECTIONAL 0
#define OB_LIGHT_TYPE_POINT 1
#define OB_LIGHT_TYPE_SPOT 2

/* ob_shadow_method */
#define OB_SHADOW_METHOD_NONE 0
#define OB_SHADOW_METHOD_HARD 1
#define OB_SHADOW_METHOD_PCF 2
#define OB_SHADOW_METHOD_VSM 3

/* ob_ambient_mode */
#define OB_AMBIENT_MODE_CONSTANT 0
#define OB_AMBIENT_MODE_HEMISPHERE 1
#define OB_AMBIENT_MODE_ENVIRONMENT 2

/* ob_view (the debug views of ob_present; 0 = final, which needs no pass) */
#define OB_VIEW_MODE_FINAL 0
#define OB_VIEW_MODE_AO 1
#define OB_VIEW_MODE_NORMALS 2
#define OB_VIEW_MODE_DEPTH 3
#define OB_VIEW_MODE_SHADOW 4
#define OB_VIEW_MODE_RADIANCE 5
#define OB_VIEW_MODE_SAMPLES 6
#define OB_VIEW_MODE_BOUNCE 7
#define OB_VIEW_MODE_BENT_NORMALS 8
#define OB_VIEW_MODE_LUMINANCE 9
#define OB_VIEW_MODE_SECOND_DEPTH 10
#define OB_VIEW_MODE_EXTRA 11
#define OB_VIEW_MODE_HISTORY_AGE 12
/* The luminance view's range in stops (obscura.h OB_LUMINANCE_LOG2_*). */
#define OB_VIEW_LUMINANCE_LOG2_LO (-8)
#define OB_VIEW_LUMINANCE_LOG2_HI 4

/* Per-pixel noise of the methods' "noise" enum parameter (registry.c's ob_noise_options order):
 * a tiled 4x4 texture, or Jimenez's interleaved gradient noise. */
#define OB_NOISE_TEXTURE4 0
#define OB_NOISE_IGN 1

/* Kernel numbers and directions of the methods' "sampling" and "directions" parameters
 * (src/sampling/sampling.h, registry.c's option lists). */
#define OB_SAMPLING_MODE_RANDOM 0
#define OB_SAMPLING_MODE_HALTON 1
#define OB_DIRECTIONS_MODE_UNIFORM 0
#define OB_DIRECTIONS_MODE_COSINE 1

/* Which sectors of a visibility bitmask a sample's angle interval sets (vbao.c's coverage
 * options): every sector it touches, those whose centre it covers, or only those it covers
 * whole. */
#define OB_SECTOR_COVERAGE_TOUCH 0
#define OB_SECTOR_COVERAGE_HALF 1
#define OB_SECTOR_COVERAGE_ALL 2

/* How a visibility bitmask joins consecutive steps on one surface (vbao.c's connect options):
 * not at all; by the chord between their fronts; the chord with each run's ends extended over
 * their strata along the samples' tangents; or that, with the curve through both fronts along
 * their normals' tangents in place of the chord. Each mode adds to the one before. */
#define OB_CONNECT_OFF 0
#define OB_CONNECT_CHORD 1
#define OB_CONNECT_ENDS 2
#define OB_CONNECT_CURVE 3

#endif
