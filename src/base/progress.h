/* Progress of a long job on stderr, one helper for every long job there is: the reference renderer
 * (here in the library) and the CLI's compare, tune, bench and the viewer's test mode (which
 * compile src/base/progress.c into the CLI too: the library's copy is hidden, so the two never
 * meet).
 *
 * On a terminal: one bar redrawn in place with '\r', closed with a newline when the job ends
 * (ob_progress_hold ends it early, before a nested job's bar, so the two never share a line).
 * Anywhere else (a log, a pipe, `make demo > log`): no '\r' at all, one labelled line when the
 * job crosses 0, 25, 50, 75 and 100 %, each line whole, so nothing written between them is
 * swallowed and a log reads top to bottom.
 *
 * Never backwards: the count only grows, and the test, the print and the update of what was shown
 * happen under one lock, so the threads of the reference renderer cannot print out of order
 * (issue 20 saw 97 % -> 94 % -> 100 %: a thread moved the shown percentage first and printed it
 * later, after a faster thread had printed a higher one). */
#ifndef OB_BASE_PROGRESS_H
#define OB_BASE_PROGRESS_H

#include <pthread.h>
#include <stdbool.h>

typedef struct ob_progress {
    char label[96];
    long long total, done;
    int shown;      /* terminal: the last percentage drawn; log: the last quarter printed (0..4); -1 none */
    bool tty;       /* stderr is a terminal */
    bool open;      /* terminal: a bar is drawn and its line not yet ended */
    bool begun;     /* between begin and end */
    bool each;      /* set after begin: show every advance (a log gets one line per step, a terminal
                     * redraws with each step's name) instead of whole percents and quarters */
    double start;   /* CLOCK_MONOTONIC seconds at begin */
    pthread_mutex_t lock;
} ob_progress;

/* Start a job of `total` work units (>= 1; less is taken as 1) and show its 0 %. */
void ob_progress_begin(ob_progress *p, const char *label, long long total);
/* `units` more done (thread-safe); `what` (may be NULL) names the unit just finished. */
void ob_progress_advance(ob_progress *p, long long units, const char *what);
/* Before other stderr output while a job runs: a terminal's open bar is wiped so the line that
 * follows starts at column 0 (the bar comes back at the next advance). Nothing in a log. */
void ob_progress_break(ob_progress *p);
/* Before a nested job that draws its own bar (compare's reference): a terminal's bar is drawn
 * once more naming `what` (the step about to run) and its line ended, so it stays on screen above
 * the nested bar rather than being wiped by it; the next advance starts a fresh line below. On a
 * terminal the outer job is therefore always visible: its line, the nested bar's line, then the
 * outer bar again, moving at every step. Nothing in a log (the nested job's lines name it). */
void ob_progress_hold(ob_progress *p, const char *what);
/* The job is over (finished or abandoned): a terminal's bar line is ended. Safe on a zeroed
 * ob_progress that never began and a second time, so an error path can always call it. */
void ob_progress_end(ob_progress *p);

#endif
