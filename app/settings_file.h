/* Tuned settings files: what `obscura tune --out` writes and `--settings FILE|DIR` loads in render,
 * view, compare, bench and sheet. One JSON object per method:
 *
 *   {"method": "hbao", "params": {"radius_scale": 1.25, "intensity": 1.1, "noise": "ign"},
 *    "tuned": {...how: training and validation views, errors before and after, evaluations}}
 *
 * Numbers for float and int parameters, option names for enums, "on"/"off" for booleans; every
 * value is checked against the method's table on load (one line naming the file, exit 2). */
#ifndef OB_SETTINGS_FILE_H
#define OB_SETTINGS_FILE_H

#include <stdbool.h>
#include <stddef.h>

#include "obscura/eval.h"

enum { CLI_MAX_TUNED_PARAMS = OB_MAX_PARAMS + 1, CLI_MAX_TUNED_FILES = 32 };

typedef struct cli_tuned {
    int method;                                      /* registry index */
    int count;
    char assignments[CLI_MAX_TUNED_PARAMS][96];      /* "hbao.intensity=1.1", applied in order */
    char path[512];
} cli_tuned;

/* One file, or every *.json in a directory (a directory with none is an error; two files for
 * one method too). 0 or the exit code of the one line printed. */
int cli_tuned_load(const char *path, cli_tuned *out, int max, int *count);
/* Apply t's assignments to settings of t's method. 0 or an exit code. */
int cli_tuned_apply(const cli_tuned *t, ob_settings *s);

#endif
