/* Internal error recording: every public entry point that fails calls ob_set_error once. */
#ifndef OB_BASE_ERROR_H
#define OB_BASE_ERROR_H

#include "obscura/scene.h"

#if defined(__GNUC__)
#define OB_PRINTF(a, b) __attribute__((format(printf, a, b)))
#else
#define OB_PRINTF(a, b)
#endif

/* The internal functions of libobscura that libobscura-eval calls (the error slot, the scene
 * builder): exported from libobscura.so but declared in no installed header, so not API. The two
 * libraries are built from one tree and shipped at one version (libobscura-eval's package depends
 * on the same version of libobscura's); tests/test_exports.sh lists them from these marks. */
#if defined(__GNUC__)
#define OB_EVAL_SHARED __attribute__((visibility("default")))
#else
#define OB_EVAL_SHARED
#endif

/* Record err with a printf-style one-line message; returns err so callers can
 * `return ob_set_error(...)`. */
OB_EVAL_SHARED ob_error ob_set_error(ob_error err, const char *fmt, ...) OB_PRINTF(2, 3);
/* The last error and its message without clearing it (ob_get_error clears): how library code
 * passes a failure it did not make up the chain. */
OB_EVAL_SHARED ob_error ob_peek_error(const char **message);


#endif
