/* The project's views in two sets (scenes/views.json in the data directory): "choose" views, the
 * ones defaults and `tune --train` may be chosen on, and "check" views, never used for a choice
 * and reported beside them (docs/methods.md, "Choose and check views"). */
#ifndef OB_APP_GRADED_VIEWS_H
#define OB_APP_GRADED_VIEWS_H

#include <stdbool.h>

#define CLI_VIEW_SET_MAX 64

typedef struct cli_view_sets {
    char choose[CLI_VIEW_SET_MAX][128];
    char check[CLI_VIEW_SET_MAX][128];
    int choose_count, check_count;
    char path[1024]; /* the file read */
} cli_view_sets;

/* Reads <data dir>/scenes/views.json. EXIT_OK, else an exit code after one line on stderr naming
 * the file and what is wrong with it (missing when `required`, not JSON, a set that is not an
 * array of "scene:camera" strings, a view in both sets, more than CLI_VIEW_SET_MAX). Not
 * `required` (compare's labels), a file that cannot be read gives two empty sets. */
int cli_view_sets_load(cli_view_sets *out, bool required);
/* "choose" or "check" for a view given as SCENE:CAMERA (compared as written), else NULL. */
const char *cli_view_set_of(const cli_view_sets *s, const char *view);

#endif
