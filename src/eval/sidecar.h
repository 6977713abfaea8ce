/* Scene sidecar JSON (format documented at the top of sidecar.c). */
#ifndef OB_SCENE_SIDECAR_H
#define OB_SCENE_SIDECAR_H

#include <stddef.h>

#include "obscura/eval.h"

/* Validate a sidecar completely and report the two keys the loader needs before importing: the
 * "model" path as written (copied into model_out, "" when absent; model_out may be NULL) and the
 * "up" axis (OB_UP_DEFAULT when absent; up_out may be NULL). Checking everything here means a
 * typo fails before a 100k-triangle import, not after. Errors: OB_ERR_IO, OB_ERR_SIDECAR. */
ob_error ob_sidecar_peek(const char *path, char *model_out, size_t model_len, ob_up_axis *up_out);

/* The ground a sidecar's "ground": {} adds, under a model that has no sidecar
 * (ob_scene_desc.automatic_ground), its material named OB_AUTOMATIC_GROUND_MATERIAL. Errors:
 * OB_ERR_SIDECAR naming `model` (no horizontal extent), OB_ERR_OUT_OF_MEMORY. */
ob_error ob_scene_add_automatic_ground(ob_scene *s, const char *model);

#endif
