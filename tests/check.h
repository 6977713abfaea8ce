/* A small test runner in the cglm style: explicit tolerances, a failure count as exit status, and
 * the closing line "N passed, N failed" that CI reads. */
#ifndef OB_TEST_CHECK_H
#define OB_TEST_CHECK_H

#include <math.h>
#include <stdio.h>

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

static inline int check_finish(const char *suite)
{
    printf("%s: %d passed, %d failed\n", suite, check_passed, check_failed);
    return check_failed > 255 ? 255 : check_failed;
}

#endif
