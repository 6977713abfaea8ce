/* libFuzzer target: the scene sidecar parser (sidecar.c), applied to a built-in scene as
 * ob_load_scene applies it. Build and run: README "Untrusted models" (make fuzz). */
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <unistd.h>

#include "obscura/eval.h"
#include "eval/import.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    char path[] = "/tmp/ob_fuzz_sidecar_XXXXXX";
    int fd = mkstemp(path);
    if (fd < 0) return 0;
    if (write(fd, data, size) == (ssize_t)size) {
        ob_scene *s = ob_scene_builtin("corner");
        if (s) (void)ob_scene_apply_sidecar(s, path);
        ob_destroy_scene(s);
    }
    close(fd);
    unlink(path);
    return 0;
}
