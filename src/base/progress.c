/* The progress helper (base/progress.h), compiled into libobscura (hidden) and into the CLI. */
#include "progress.h"

#include <stdio.h>
#include <string.h>
#include <sys/ioctl.h>
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

/* A terminal's bar, redrawn in place over the line the cursor is on. Called with the lock held. */
static void draw_bar(ob_progress *p, const char *what, int pct, const char *elapsed, const char *left)
{
    char bar[BAR_WIDTH + 1];
    const int fill = pct * BAR_WIDTH / 100;
    for (int i = 0; i < BAR_WIDTH; ++i) bar[i] = i < fill ? '#' : '.';
    bar[BAR_WIDTH] = '\0';
    const char *sep = what && *what ? " " : "";
    char line[400];
    snprintf(line, sizeof line, "%s [%s] %3d %% %lld/%lld%s%.100s elapsed %s ETA %s", p->label, bar, pct, p->done,
             p->total, sep, what ? what : "", elapsed, left);
    /* A line wider than the terminal wraps, and '\r' then redraws only its last row: the rows
     * above pile up. Cut it to the width (at a UTF-8 boundary): the ETA goes first, then the step. */
    struct winsize ws;
    if (ioctl(STDERR_FILENO, TIOCGWINSZ, &ws) == 0 && ws.ws_col > 20 && ws.ws_col < sizeof line) {
        size_t cut = ws.ws_col - 1;
        while (cut > 0 && ((unsigned char)line[cut] & 0xC0) == 0x80) --cut;
        if (cut < strlen(line)) line[cut] = '\0';
    }
    /* \x1b[K clears what a longer earlier line left to the right. */
    fprintf(stderr, "\r%s\x1b[K", line);
    p->shown = pct;
    p->open = true;
}

/* The percentage, and the elapsed time and ETA as text. Called with the lock held. */
static int measure(const ob_progress *p, char *elapsed, char *left, size_t n)
{
    const double el = now_s() - p->start;
    /* The ETA from the mean rate so far: units may differ in cost (bench's methods do), so it is a
     * guide, but it never makes the percentage itself move backwards. */
    const double eta = p->done > 0 ? el / (double)p->done * (double)(p->total - p->done) : -1.0;
    clock_text(el, elapsed, n);
    clock_text(eta, left, n);
    return (int)(p->done * 100 / p->total);
}

/* Called with the lock held. */
static void show(ob_progress *p, const char *what)
{
    char elapsed[16], left[16];
    const int pct = measure(p, elapsed, left, sizeof elapsed);
    if (p->tty) {
        if (!p->each && pct <= p->shown && !(p->done == p->total && p->open)) return;
        draw_bar(p, what, pct, elapsed, left);
        if (p->done == p->total) {
            fputc('\n', stderr);
            p->open = false;
        }
    } else {
        const int quarter = pct / 25;
        if (!p->each && quarter <= p->shown) return;
        const char *sep = what && *what ? " " : "";
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

void ob_progress_hold(ob_progress *p, const char *what)
{
    pthread_mutex_lock(&p->lock);
    if (p->tty) {
        char elapsed[16], left[16];
        const int pct = measure(p, elapsed, left, sizeof elapsed);
        draw_bar(p, what, pct, elapsed, left);
        fputc('\n', stderr);
        p->open = false;
        /* The next advance draws a fresh line below the nested job's, even at the same percent. */
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
