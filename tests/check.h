/* A small test runner in the cglm style: explicit tolerances, a failure count as exit status, and
 * the closing line "N passed, N failed" that CI reads. */
#ifndef OB_TEST_CHECK_H
#define OB_TEST_CHECK_H

#include <math.h>
#include <stdio.h>

#include "obscura/eval.h"

static int check_passed = 0;
static int check_failed = 0;

#define CHECK(cond, ...)                                                          \
    do {                                                                          \
        if (cond) {                                                               \
            ++check_passed;                                                       \
        } else {                                                                  \
            ++check_failed;                                                       \
            fprintf(stderr, "FAIL %s:%d: %s: ", __FILE__, __LINE__, #cond);       \
            fprintf(stderr, __VA_ARGS__);                                         \
            fputc('\n', stderr);                                                  \
        }                                                                         \
    } while (0)

/* |a - b| <= tol */
#define CHECK_NEAR(a, b, tol, what)                                                          \
    CHECK(fabs((double)(a) - (double)(b)) <= (double)(tol), "%s: %.6g vs %.6g (tol %.3g)", what, \
          (double)(a), (double)(b), (double)(tol))

/* The headless GL context every GPU suite starts with; NULL after one line on stderr naming why. */
static inline ob_context *check_context(void)
{
    ob_context *ctx = ob_make_context(NULL);
    if (!ctx) {
        const char *msg = NULL;
        ob_get_error(&msg);
        fprintf(stderr, "no context: %s\n", msg);
    }
    return ctx;
}

static inline int check_finish(const char *suite)
{
    printf("%s: %d passed, %d failed\n", suite, check_passed, check_failed);
    return check_failed > 255 ? 255 : check_failed;
}

#endif
