/* The progress helper (base/progress.h), compiled into libobscura (hidden) and into the CLI. */
#include "progress.h"

#include <stdio.h>
#include <string.h>
#include <time.h>
#include <unistd.h>

enum { BAR_WIDTH = 30 };

static double now_s(void)
{
    struct timespec ts = {0, 0};
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

/* "1m02s"; a negative or absurd time (nothing done yet) as "?". */
static void clock_text(double s, char *out, size_t n)
{
    if (!(s >= 0.0) || s > 359999.0) {
        snprintf(out, n, "?");
        return;
    }
    int t = (int)(s + 0.5);
    snprintf(out, n, "%dm%02ds", t / 60, t % 60);
}

/* Called with the lock held. */
static void show(ob_progress *p, const char *what)
{
    const int pct = (int)(p->done * 100 / p->total);
    const double el = now_s() - p->start;
    /* The ETA from the mean rate so far: units may differ in cost (bench's methods do), so it is a
     * guide, but it never makes the percentage itself move backwards. */
    const double eta = p->done > 0 ? el / (double)p->done * (double)(p->total - p->done) : -1.0;
    char elapsed[16], left[16];
    clock_text(el, elapsed, sizeof elapsed);
    clock_text(eta, left, sizeof left);
    const char *sep = what && *what ? " " : "";
    if (p->tty) {
        if (!p->each && pct <= p->shown && !(p->done == p->total && p->open)) return;
        char bar[BAR_WIDTH + 1];
        const int fill = pct * BAR_WIDTH / 100;
        for (int i = 0; i < BAR_WIDTH; ++i) bar[i] = i < fill ? '#' : '.';
        bar[BAR_WIDTH] = '\0';
        /* \x1b[K clears what a longer earlier line left to the right. */
        fprintf(stderr, "\r%s [%s] %3d %% %lld/%lld%s%.40s elapsed %s ETA %s\x1b[K", p->label, bar, pct, p->done,
                p->total, sep, what ? what : "", elapsed, left);
        p->shown = pct;
        p->open = true;
        if (p->done == p->total) {
            fputc('\n', stderr);
            p->open = false;
        }
    } else {
        const int quarter = pct / 25;
        if (!p->each && quarter <= p->shown) return;
        fprintf(stderr, "%s: %d %% (%lld/%lld)%s%.60s, elapsed %s, ETA %s\n", p->label, pct, p->done, p->total, sep,
                what ? what : "", elapsed, left);
        p->shown = quarter;
    }
    fflush(stderr);
}

void ob_progress_begin(ob_progress *p, const char *label, long long total)
{
    memset(p, 0, sizeof *p);
    snprintf(p->label, sizeof p->label, "%s", label ? label : "progress");
    p->total = total > 0 ? total : 1;
    p->shown = -1;
    p->tty = isatty(STDERR_FILENO) == 1;
    p->start = now_s();
    p->begun = true;
    pthread_mutex_init(&p->lock, NULL);
    pthread_mutex_lock(&p->lock);
    show(p, NULL);
    pthread_mutex_unlock(&p->lock);
}

void ob_progress_advance(ob_progress *p, long long units, const char *what)
{
    if (units <= 0) return;
    pthread_mutex_lock(&p->lock);
    /* More units than announced (a caller's estimate was low) stop at 100 %, never past it. */
    p->done = p->done + units < p->total ? p->done + units : p->total;
    show(p, what);
    pthread_mutex_unlock(&p->lock);
}

void ob_progress_break(ob_progress *p)
{
    pthread_mutex_lock(&p->lock);
    if (p->tty && p->open) {
        fputs("\r\x1b[K", stderr);
        p->open = false;
        /* Redraw at the next advance even if the percentage has not moved. */
        p->shown = -1;
        fflush(stderr);
    }
    pthread_mutex_unlock(&p->lock);
}

void ob_progress_end(ob_progress *p)
{
    if (!p->begun) return;
    p->begun = false;
    pthread_mutex_lock(&p->lock);
    if (p->tty && p->open) {
        fputc('\n', stderr);
        p->open = false;
        fflush(stderr);
    }
    pthread_mutex_unlock(&p->lock);
    pthread_mutex_destroy(&p->lock);
}
