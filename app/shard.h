/* A deterministic slice of a run's work units for one of N processes (`--shard K/N`): every
 * process that is given the same units and N computes the same assignment, so N processes on N
 * machines (a Slurm job array, GNU parallel, a loop over ssh) do every unit exactly once, and none
 * of them talks to another. */
#ifndef OB_APP_SHARD_H
#define OB_APP_SHARD_H

#include <stdbool.h>

enum { CLI_MAX_SHARDS = 4096 };

typedef struct cli_shard {
    int index, count; /* K and N: 0 <= K < N; {0, 1} is the whole run */
} cli_shard;

/* "K/N" (0 <= K < N <= CLI_MAX_SHARDS, Slurm's 0-based array index) into s. 0, or EXIT_USAGE after
 * one line naming `option`. */
int cli_shard_parse(const char *option, const char *text, cli_shard *s);

/* owner[u] for each of the `units` work units: the shard that runs it. Longest expected cost
 * first, each to the shard with the least cost so far (ties: the lower shard), units of equal
 * cost in their own order: balanced by cost, not by count, and the same on every machine (no
 * floating-point sum depends on the order the shards run in). cost[u] >= 0. */
void cli_shard_assign(const double *cost, int units, int shards, int *owner);

/* root.shard = {"index": K, "count": N, "views": [{"view": views[u], "shard": owner[u]}, ...]}:
 * which unit went where, as compare's results.json and dataset's manifest.json record it. */
struct cJSON;
void cli_shard_json(struct cJSON *root, const cli_shard *s, const char *const *views, const int *owner, int count);

#endif
