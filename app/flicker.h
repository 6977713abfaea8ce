/* Flicker metrics (issue 17) for compare --path / --orbit: per combination of the lists, with
 * temporal accumulation off and on,
 *   - static noise: the camera still at the path's first frame for FLICKER_STILL_FRAMES frames with
 *     the frame index (and so every method's noise) advancing, after a history length of warm-up:
 *     the mean over geometry pixels of each pixel's standard deviation over time;
 *   - warped temporal error: along the path, the mean |AO_t - AO_t-1 reprojected| over pixels seen
 *     in both frames (the previous frame's depth at the reprojected point is the point's own),
 *     minus the same for the ray-traced reference along the path (its change is real);
 *   - RMSE against the reference on the last frame, and the worst frame's RMSE and index; and every
 *     frame's, with their mean: a screen-space estimate depends on the view, so the accumulated
 *     image is an average over the last views, and the last frame alone can land where the
 *     single frame's error dips (docs/temporal.md, "An unseen view").
 * With --jitter J (default OB_JITTER_POSITIONS_DEFAULT) both variants render the G-buffer jittered
 * over J sub-pixel points, and every path frame's reference is AO_R averaged over the same J
 * points (the pixel footprint the accumulation converges to); --jitter off grades the pixel
 * centres. The still camera's static noise then includes the jitter's own change (aliasing),
 * which accumulation is there to remove.
 * "Off" is the spatial filter alone with the same moving noise (a history of one frame: every
 * method's noise turns with the frame index as under --temporal on, nothing is kept), so both
 * variants have the same noise and only the accumulation differs. */
#ifndef OB_APP_FLICKER_H
#define OB_APP_FLICKER_H

#include "cli_options.h"

enum { FLICKER_STILL_FRAMES = 64 };

typedef struct cli_flicker_variant {
    double static_noise;    /* mean per-pixel std-dev over the still frames */
    double warped;          /* mean |AO_t - reproject(AO_t-1)|, the method's own, averaged over the path */
    double warped_excess;   /* warped minus the reference's */
    double rmse_last, rmse_worst, rmse_mean; /* over the frames that see something; last = the
                                              * last of those; NaN when none does */
    int worst_frame;
    double *rmse_frames;    /* every path frame's RMSE (path_frames of them; NaN for a frame that sees
                             * nothing), malloc'd: free it */
    int frames_seen;        /* frames that see something: the ones in the means, worst and last */
    double temporal_ms;     /* median GPU ms of the accumulation pass along the path (0 off) */
    float *worst_ao;        /* the worst frame's AO (W x H, bottom row first), malloc'd: free it */
} cli_flicker_variant;

typedef struct cli_flicker_row {
    const cli_config *config;
    cli_flicker_variant off, on;
} cli_flicker_row;

typedef struct cli_flicker_desc {
    const cli_common *common;   /* size, --path/--orbit, --path-frames, --temporal-* */
    ob_renderer *renderer;      /* its scene set */
    const ob_scene *scene;
    const char *scene_key;      /* the scene as the command line named it (reference cache key) */
    ob_camera base;             /* the camera an orbit turns */
    float radius;
    int spp;
    bool no_cache;
} cli_flicker_desc;

typedef struct cli_flicker_reference {
    double warped;              /* the reference's own mean |AO_t - reproject(AO_t-1)| along the path
                                 * (over the pairs of frames that share pixels; NaN: none do) */
    int frames;
    int frames_empty;           /* frames that see nothing (only with --allow-empty) */
    int jitter;                 /* the jitter positions both variants ran with and the reference is
                                 * averaged over (0: the pixel centres) */
} cli_flicker_reference;

/* Every row of configs (count of them) off and on into rows (count). 0 or an exit code. */
int cli_flicker_run(const cli_flicker_desc *d, const cli_config *configs, int count, cli_flicker_row *rows,
                    cli_flicker_reference *ref);
void cli_flicker_free(cli_flicker_row *rows, int count);

#endif
