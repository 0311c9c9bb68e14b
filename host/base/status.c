/* atmo_fail: the one place where error messages are formatted. */
#include <stdarg.h>
#include <stdio.h>
#include "atmo/status.h"

int atmo_fail(atmo_err *e, int code, const char *fmt, ...)
{
    if (e) {
        va_list ap;
        va_start(ap, fmt);
        vsnprintf(e->msg, sizeof e->msg, fmt, ap);
        va_end(ap);
    }
    return code;
}
