/* Internal error recording: every public entry point that fails calls ob_set_error once. */
#ifndef OB_BASE_ERROR_H
#define OB_BASE_ERROR_H

#include "obscura/obscura.h"

#if defined(__GNUC__)
#define OB_PRINTF(a, b) __attribute__((format(printf, a, b)))
#else
#define OB_PRINTF(a, b)
#endif

/* Record err with a printf-style one-line message; returns err so callers can
 * `return ob_set_error(...)`. */
ob_error ob_set_error(ob_error err, const char *fmt, ...) OB_PRINTF(2, 3);
/* The last error and its message without clearing it (ob_get_error clears): how library code
 * passes a failure it did not make up the chain. */
ob_error ob_peek_error(const char **message);


#endif
