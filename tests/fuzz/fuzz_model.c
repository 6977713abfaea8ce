/* libFuzzer target: the model loader (model_io.c's checks, Assimp through the confinement, the
 * import and the bounds check). The first byte picks the extension the bytes are saved under,
 * so one corpus reaches every reader the checks know plus a few without one.
 * Build and run: README "Untrusted models" (make fuzz). */
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <unistd.h>

#include "obscura/eval.h"
#include "eval/import.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    static const char *ext[] = {".ply", ".obj", ".gltf", ".glb", ".stl", ".off", ".fbx", ".dae", ".pk3", ".bsp"};
    if (size < 1) return 0;
    char dir[] = "/tmp/ob_fuzz_model_XXXXXX";
    if (!mkdtemp(dir)) return 0;
    char path[64] = "";
    snprintf(path, sizeof path, "%s/m%s", dir, ext[data[0] % (sizeof ext / sizeof ext[0])]);
    FILE *f = fopen(path, "wb");
    if (f) {
        fwrite(data + 1, 1, size - 1, f);
        fclose(f);
        /* A small ceiling: the fuzzer's own RSS limit (-rss_limit_mb) is for real leaks. */
        ob_scene *s = ob_scene_import(path, OB_UP_Y, false, 256u << 20);
        ob_destroy_scene(s);
    }
    unlink(path);
    rmdir(dir);
    return 0;
}
