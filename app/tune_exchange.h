/* `obscura tune --shard K/N --exchange DIR`: one tuning run over N processes that share its views
 * (each loads, traces and renders only its own) and exchange each evaluation's per-view errors
 * through files in a folder they all see. tune's search is a sequence of evaluations, each the
 * mean MSE over a set of views, each choice depending on the last total; so the shards run the
 * same sequence in step: at evaluation i each writes its views' MSEs, waits for every other
 * shard's, and sums all of them in view order, as the unsharded run does. Every shard then makes
 * the same choices, bit for bit, with no coordinator: no shard is special but shard 0, which alone
 * writes --out.
 *
 * The folder: DIR/RUN/, RUN the run id (tune_run_id), so that runs sharing DIR never meet. In it:
 *   eval-I.shard-K     shard K's MSE of each of its views in evaluation I (a text record, below);
 *   failed.shard-K     shard K stopped with an error: its message, so the others stop at once;
 *   .NAME.tmp-XXXXXX   a record being written; renamed to NAME when whole, so a reader never sees
 *                      half of one.
 * A record: lines "obscura tune exchange 1", "version V" (obscura's), "run RUN", "shard K/N", then
 * "evaluation I", "set training|validation|check", "views C" and C lines "view U MSE RADIUS" (U the
 * view's index in the run: training, then validation, then check views as the command line gives
 * them; MSE and the view's AO radius as C99 hex floats, %a: exact), or "failed MESSAGE"; last "end".
 * A record that is not whole, not of this run, build, evaluation or shard, or not of the views that
 * shard owns is one line naming the file, exit 3.
 *
 * A shard removes its record of evaluation I once every shard has written I + 1 (each read all of
 * I before writing I + 1), so a run keeps about two records per shard; a finished run leaves its
 * last evaluation's. An earlier attempt's records would be read as this one's, and no shard can
 * tell them apart by content (the same command makes the same records): so a shard refuses to
 * start (exit 4, "remove it") when the folder holds anything an attempt that has just begun cannot
 * have written yet: a record of its own, or any record past evaluation 0 (no shard passes
 * evaluation 0 before every shard has written it). */
#ifndef OB_APP_TUNE_EXCHANGE_H
#define OB_APP_TUNE_EXCHANGE_H

#include <stdbool.h>

#include "shard.h"

enum { TUNE_RUN_ID_LEN = 16 };

typedef struct tune_exchange {
    cli_shard shard;      /* this process: K of N */
    const int *owner;     /* owner[u]: the shard of each of the run's views (cli_shard_assign) */
    int units;            /* the run's views */
    double timeout_s;     /* --exchange-timeout: the longest wait for one evaluation's records */
    char run[TUNE_RUN_ID_LEN + 1];
    char dir[4096];       /* DIR/RUN */
    int next;             /* the number of the next evaluation */
    bool open;            /* dir exists: a failure is recorded there */
    bool *have;           /* per shard, during a wait: its record was read */
} tune_exchange;

/* The run id: 16 hex digits of a 64-bit FNV-1a hash of the tune command's arguments, each with its
 * terminating NUL, apart from --shard, --exchange, --exchange-timeout and --out with their values
 * (which differ between the shards of one run, or change nothing the shards exchange). argv[0] is
 * the command's name and is left out. */
void tune_run_id(int argc, char **argv, char out[TUNE_RUN_ID_LEN + 1]);

/* Makes DIR and DIR/RUN as needed and checks that DIR/RUN holds nothing of an earlier attempt
 * (above). 0; EXIT_OUTPUT when the folder cannot be made or holds an earlier attempt's records;
 * EXIT_INPUT when another shard has already recorded a failure. x->open is set once the folder
 * exists, even when the check fails (tune_exchange_fail then records the refusal there). */
int tune_exchange_open(tune_exchange *x, const char *root, const cli_shard *shard, const char *run,
                       const int *owner, int units, double timeout_s);

/* The next evaluation over the views first .. first + count - 1 (one set, named by `set`): mse[i]
 * and radius[i] hold this shard's views' values on entry (the others' entries are ignored) and
 * every view's on return. Writes this shard's record, then polls (every 10 ms, the interval growing
 * to 200 ms) until every other shard's is there and reads each as it comes. 0, or the exit code of
 * the one line printed: EXIT_INPUT for a record that is not what it should be, a shard that
 * recorded a failure, or shards that wrote nothing within the timeout (each named); EXIT_OUTPUT
 * when this shard's record cannot be written. */
int tune_exchange_share(tune_exchange *x, const char *set, int first, int count, double *mse, float *radius);

/* failed.shard-K with the message (cli_last_failure's line), so that the other shards stop at the
 * next wait instead of waiting out the timeout. Nothing when the folder was never made; a failure
 * to write it is ignored (the others then time out). */
void tune_exchange_fail(tune_exchange *x, const char *message);

void tune_exchange_close(tune_exchange *x);

#endif
