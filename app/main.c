/* obscura: the command dispatch. Each subcommand lives in its own file (render.c, list.c, ...);
 * the helpers they share are in cli.c and cli_options.c. */
#include <stdio.h>
#include <string.h>

#include "cli.h"
#include "suggest.h"

static void usage(FILE *f)
{
    fputs("usage: obscura <command> [options]\n"
          "\n"
          "Screen-space ambient occlusion, rendered headless on the GPU (EGL) or llvmpipe.\n"
          "\n"
          "commands:\n"
          "  render   render a scene with an AO method to PNG (and the AO map to PFM/PNG)\n"
          "  list     list AO methods with their parameters, and the scenes (--json for JSON)\n"
          "  sheet    a labelled contact sheet: final image and AO map of each method, with timings\n"
          "  compare  every method against the ray-traced ground truth: HTML report + results.json\n"
          "  bench    GPU time per pass of every method over samples and radius (Belonogov 2018 tables)\n"
          "  tune     one method's parameters against the ground truth on training views, checked on\n"
          "           validation views; writes a settings file for --settings\n"
          "  view     interactive viewer: camera, presets, live parameters, profiler, test mode\n"
          "  merge    the reports of compare's shards (compare --shard K/N) into the whole run's report\n"
          "  dataset  per view the G-buffer (depth, normals, albedo) and the ray-traced AO_R as PFM\n"
          "           with a JSON manifest, to train learned AO on (--shard K/N splits the views)\n"
          "\n"
          "Run `obscura <command> --help` for a command's options.\n"
          "\n"
          "exit codes: 0 ok, 1 GL/shader/runtime failure, 2 bad argument, 3 missing or corrupt\n"
          "model/sidecar, 4 output not writable, 5 no OpenGL 4.5 context\n",
          f);
}

int main(int argc, char **argv)
{
    if (argc < 2) {
        usage(stderr);
        return EXIT_USAGE;
    }
    const char *cmd = argv[1];
    if (!strcmp(cmd, "--help") || !strcmp(cmd, "-h") || !strcmp(cmd, "help")) {
        usage(stdout);
        return EXIT_OK;
    }
    if (!strcmp(cmd, "--version")) {
        printf("obscura %s\n", OB_VERSION_STRING);
        return EXIT_OK;
    }
    if (!strcmp(cmd, "render")) return cmd_render(argc - 1, argv + 1);
    if (!strcmp(cmd, "list")) return cmd_list(argc - 1, argv + 1);
    if (!strcmp(cmd, "sheet")) return cmd_sheet(argc - 1, argv + 1);
    if (!strcmp(cmd, "compare")) return cmd_compare(argc - 1, argv + 1);
    if (!strcmp(cmd, "bench")) return cmd_bench(argc - 1, argv + 1);
    if (!strcmp(cmd, "view")) {
        cli_guard_shader_cache(); /* the viewer makes its own (GLFW) context */
        return cmd_view(argc - 1, argv + 1);
    }
    if (!strcmp(cmd, "tune")) return cmd_tune(argc - 1, argv + 1);
    if (!strcmp(cmd, "dataset")) return cmd_dataset(argc - 1, argv + 1);
    if (!strcmp(cmd, "merge")) return cmd_merge(argc - 1, argv + 1);
    static const char *const commands[] = {"render", "list", "sheet", "compare", "bench", "view", "tune", "dataset", "merge"};
    char hint[96];
    fprintf(stderr, "obscura: unknown command '%s'%s (commands: render, list, sheet, compare, bench, view, tune, dataset, merge; see obscura --help)\n",
            cmd, ob_suggest_text(cmd, strlen(cmd), commands, 9, hint, sizeof hint));
    return EXIT_USAGE;
}
