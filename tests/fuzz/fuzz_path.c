/* libFuzzer target: camera paths (issue 17), the sidecar's "paths" (src/eval/sidecar.c's
 * parse_path) applied to a built-in scene, then every accepted path evaluated along its span as
 * render/compare/bench --path evaluate it (src/scene/path.c), at and beyond its ends. Seeds:
 * tests/fuzz/corpus_path, sidecars with paths (make fuzz, make test-fuzz). */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "obscura/eval.h"
#include "eval/import.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    char path[] = "/tmp/ob_fuzz_path_XXXXXX";
    int fd = mkstemp(path);
    if (fd < 0) return 0;
    if (write(fd, data, size) == (ssize_t)size) {
        ob_scene *s = ob_scene_builtin("corner");
        if (s && ob_scene_apply_sidecar(s, path) == OB_OK) {
            static const float us[] = {0.0f, 0.25f, 1.0f / 3.0f, 0.5f, 0.999f, 1.0f, -1.0f, 2.0f, NAN, INFINITY};
            for (int p = 0; p < ob_query_path_count(s); ++p) {
                const char *name = ob_query_path_name(s, p);
                for (size_t k = 0; k < sizeof us / sizeof us[0]; ++k) {
                    ob_camera cam;
                    /* Every listed path is found, at any u, and the camera carries its name. */
                    if (ob_camera_on_path(s, name, us[k], &cam) != OB_OK || strcmp(cam.name, name) != 0)
                        __builtin_trap();
                    (void)ob_check_camera(&cam); /* what the renderer would be given */
                    ob_camera turned = ob_camera_orbit(&cam, 360.0f * us[k]);
                    (void)ob_check_camera(&turned);
                }
            }
            ob_camera none;
            (void)ob_camera_on_path(s, "no such path", 0.5f, &none);
        }
        ob_clear_error();
        ob_destroy_scene(s);
    }
    close(fd);
    unlink(path);
    return 0;
}
