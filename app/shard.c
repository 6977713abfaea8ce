/* Work units split over shards (shard.h). */
#include "shard.h"

#include <cjson/cJSON.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cli.h"

int cli_shard_parse(const char *option, const char *text, cli_shard *s)
{
    long k = -1, n = -1;
    char tail = '\0';
    /* %n-free: sscanf's count of fields and a trailing character catch "1/2x" and "1/". */
    if (sscanf(text, "%ld/%ld%c", &k, &n, &tail) != 2 || n < 1 || n > CLI_MAX_SHARDS || k < 0 || k >= n)
        return cli_fail(EXIT_USAGE, "%s: expected K/N with 0 <= K < N <= %d (K: this process's 0-based index, as "
                                    "Slurm's SLURM_ARRAY_TASK_ID), got '%s'",
                        option, CLI_MAX_SHARDS, text);
    s->index = (int)k;
    s->count = (int)n;
    return EXIT_OK;
}

typedef struct unit_cost {
    double cost;
    int unit;
} unit_cost;

static int by_cost(const void *a, const void *b)
{
    const unit_cost *x = a, *y = b;
    if (x->cost != y->cost) return x->cost > y->cost ? -1 : 1;
    return (x->unit > y->unit) - (x->unit < y->unit);
}

void cli_shard_assign(const double *cost, int units, int shards, int *owner)
{
    unit_cost *order = malloc((size_t)(units > 0 ? units : 1) * sizeof *order);
    double *load = calloc((size_t)(shards > 0 ? shards : 1), sizeof *load);
    if (!order || !load) {
        /* No memory for the sort: round robin, still the same on every machine. */
        for (int u = 0; u < units; ++u) owner[u] = shards > 0 ? u % shards : 0;
        free(order);
        free(load);
        return;
    }
    for (int u = 0; u < units; ++u) order[u] = (unit_cost){cost[u] > 0.0 ? cost[u] : 0.0, u};
    qsort(order, (size_t)units, sizeof *order, by_cost);
    for (int i = 0; i < units; ++i) {
        int best = 0;
        for (int s = 1; s < shards; ++s)
            if (load[s] < load[best]) best = s;
        owner[order[i].unit] = best;
        load[best] += order[i].cost;
    }
    free(order);
    free(load);
}

void cli_shard_json(cJSON *root, const cli_shard *s, const char *const *views, const int *owner, int count)
{
    cJSON *sh = cJSON_AddObjectToObject(root, "shard");
    cli_json_add_number(sh, "index", s->index);
    cli_json_add_number(sh, "count", s->count);
    cJSON *all = cJSON_AddArrayToObject(sh, "views");
    for (int u = 0; u < count; ++u) {
        cJSON *e = cJSON_CreateObject();
        cJSON_AddStringToObject(e, "view", views[u]);
        cli_json_add_number(e, "shard", owner[u]);
        cJSON_AddItemToArray(all, e);
    }
}
