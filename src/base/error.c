#include "base/error.h"

#include <stdarg.h>
#include <stdio.h>

static _Thread_local ob_error last_error = OB_OK;
static _Thread_local char last_message[1024] = "";
/* Reading (ob_get_error) clears last_error but keeps last_message, so that a log line written
 * after the check can still quote it; the next error or ob_clear_error replaces it. */

/* Process-wide, as glfwSetErrorCallback: set it before making contexts, not while other threads
 * may be failing. */
static ob_error_callback error_callback = NULL;
static void *error_callback_user = NULL;

static const char *const error_names[] = {
#define OB_X_NAME(code, msg) #code,
    OB_ERRORS(OB_X_NAME)
#undef OB_X_NAME
};

static const char *const error_messages[] = {
#define OB_X_MSG(code, msg) msg,
    OB_ERRORS(OB_X_MSG)
#undef OB_X_MSG
};

ob_error ob_set_error(ob_error err, const char *fmt, ...)
{
    last_error = err;
    if (fmt) {
        va_list ap;
        va_start(ap, fmt);
        vsnprintf(last_message, sizeof last_message, fmt, ap);
        va_end(ap);
    } else {
        snprintf(last_message, sizeof last_message, "%s",
                 (unsigned)err < OB_ERROR_COUNT ? error_messages[err] : "unknown error");
    }
    /* One line: the CLI prints it as is. */
    for (char *c = last_message; *c; ++c) {
        if (*c == '\n' || *c == '\r') *c = ' ';
    }
    if (error_callback && err != OB_OK) error_callback(err, last_message, error_callback_user);
    return err;
}

ob_error ob_peek_error(const char **message)
{
    if (message) *message = last_message;
    return last_error;
}

ob_error ob_get_error(const char **message)
{
    ob_error err = last_error;
    last_error = OB_OK;
    if (message) *message = last_message;
    return err;
}

void ob_set_error_callback(ob_error_callback callback, void *user)
{
    error_callback = callback;
    error_callback_user = user;
}

const char *ob_error_name(ob_error err)
{
    return (unsigned)err < OB_ERROR_COUNT ? error_names[err] : "OB_ERR_?";
}

void ob_clear_error(void)
{
    last_error = OB_OK;
    last_message[0] = '\0';
}
