/* libFuzzer target: the common options of the rendering commands (app/cli_options.c), the
 * parser every command runs before it makes a GL context: cli_common_option over an argv, then
 * cli_common_finish and cli_common_configs, as cmd_render, cmd_compare... call them. The input
 * is the argv, its arguments split at NUL bytes; its first byte picks what the command takes
 * (CLI_TAKES_*). Nothing here opens a context, loads a scene or exits: --scene, --sidecar and
 * --env are only stored by the parser, and --settings (read by cli_common_finish) is pointed at
 * settings this target wrote, a file or a directory, so that an input never reads the machine's
 * files (a FIFO, /dev/zero). Seeds: tests/fuzz/corpus_cli (make fuzz, make test-fuzz). */
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "cli_options.h"

enum { MAX_ARGS = 128 };

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

static char settings_dir[64], settings_file[96];

static void write_text(const char *path, const char *text)
{
    FILE *f = fopen(path, "w");
    if (!f) abort();
    fputs(text, f);
    fclose(f);
}

/* Settings for --settings, once: ssao's in a file, ssao's and hbao's in a directory. */
static void make_settings(void)
{
    if (settings_dir[0]) return;
    snprintf(settings_dir, sizeof settings_dir, "/tmp/ob_fuzz_cli_XXXXXX");
    if (!mkdtemp(settings_dir)) abort();
    char path[128];
    snprintf(settings_file, sizeof settings_file, "%s/ssao.json", settings_dir);
    write_text(settings_file, "{\"method\": \"ssao\", \"params\": {\"radius_scale\": 1.5, \"intensity\": 1.2}}\n");
    snprintf(path, sizeof path, "%s/hbao.json", settings_dir);
    write_text(path, "{\"method\": \"hbao\", \"params\": {\"radius_scale\": 0.75}}\n");
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    if (size < 1) return 0;
    make_settings();
    static const unsigned takes[] = {
        CLI_TAKES_SCENE | CLI_TAKES_CAMERA | CLI_TAKES_GPU | CLI_TAKES_PATH,                   /* render */
        CLI_TAKES_SCENE | CLI_TAKES_CAMERA | CLI_TAKES_LISTS | CLI_TAKES_GPU,                  /* sheet */
        CLI_TAKES_CAMERA | CLI_TAKES_LISTS | CLI_TAKES_GPU | CLI_TAKES_PATH,                   /* compare */
        CLI_TAKES_SCENE | CLI_TAKES_LISTS | CLI_TAKES_GPU | CLI_TAKES_PATH,                    /* bench */
        CLI_TAKES_GPU,                                                                         /* tune */
        CLI_TAKES_SCENE | CLI_TAKES_CAMERA | CLI_TAKES_PATH,                                   /* view */
    };
    static const char *const names[] = {"render", "sheet", "compare", "bench", "tune", "view"};
    const int kind = data[0] % (int)(sizeof takes / sizeof takes[0]);
    /* Each argument its own exact allocation: a read past one's NUL is an ASan report. */
    char *argv[MAX_ARGS + 1] = {0};
    int argc = 0;
    argv[argc++] = strdup(names[kind]);
    for (size_t at = 1; at < size && argc < MAX_ARGS;) {
        const uint8_t *nul = memchr(data + at, 0, size - at);
        size_t len = nul ? (size_t)(nul - (data + at)) : size - at;
        char *a = malloc(len + 1);
        if (!a) break;
        memcpy(a, data + at, len);
        a[len] = '\0';
        argv[argc++] = a;
        at += len + 1;
    }
    cli_common *c = calloc(1, sizeof *c); /* 150 KB: not on the stack */
    if (!c) abort();
    cli_common_init(c, names[kind], takes[kind]);
    int code = EXIT_OK;
    for (int i = 1; i < argc && code == EXIT_OK; ++i) {
        int r = cli_common_option(c, argc, argv, &i);
        if (r > 0) code = r;
        if (i >= argc) __builtin_trap(); /* a value taken past the end of argv */
        /* CLI_NOT_MINE: the command's own option, which its own parser would take */
    }
    if (code == EXIT_OK) {
        if (c->settings_path) c->settings_path = c->settings_path[0] == 'd' ? settings_dir : settings_file;
        code = cli_common_finish(c);
    }
    if (code == EXIT_OK) {
        cli_config *configs = NULL;
        int count = 0;
        if (cli_common_configs(c, &configs, &count) == EXIT_OK) {
            if (count < 1 || count > CLI_MAX_CONFIGS) __builtin_trap();
            for (int k = 0; k < count; ++k)
                if (!memchr(configs[k].label, 0, sizeof configs[k].label) || !memchr(configs[k].stem, 0, sizeof configs[k].stem))
                    __builtin_trap();
            free(configs);
        }
    }
    ob_clear_error();
    free(c);
    for (int i = 0; i < argc; ++i) free(argv[i]);
    return 0;
}
