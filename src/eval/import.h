/* The evaluation library's scene builders from files (import.c with Assimp, sidecar.c), on the
 * core's scene container (scene/scene.h). */
#ifndef OB_EVAL_IMPORT_H
#define OB_EVAL_IMPORT_H

#include "obscura/eval.h"
#include "scene/scene.h"

/* assimp; with desc's allow_external_files and max_memory (0 = the default). */
ob_scene *ob_scene_import(const char *path, ob_up_axis up, bool allow_external_files, uint64_t max_memory);
/* The same with the caller's share of max_memory (ob_scene_desc.reserved_memory, reserved_what):
 * the geometry, the textures and it must fit together. */
ob_scene *ob_scene_import_within(const char *path, ob_up_axis up, bool allow_external_files, uint64_t max_memory,
                                 uint64_t reserved, const char *reserved_what);
/* Apply a sidecar JSON (cameras, lights, ao_radius, ground) to a loaded scene. */
ob_error ob_scene_apply_sidecar(ob_scene *s, const char *json_path);

#endif
