/* atmo_fail: the one place where error messages are formatted.
 *
 * A message longer than atmo_err's buffer (a path of a few KiB in it) loses its middle, not
 * its end: the first and the last parts are kept around "...", so the message still says what
 * was wrong at its start and the reason and the fix at its end. */
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "atmo/status.h"

int atmo_fail(atmo_err *e, int code, const char *fmt, ...)
{
    if (!e)
        return code;
    va_list ap, again;
    va_start(ap, fmt);
    va_copy(again, ap);
    int n = vsnprintf(e->msg, sizeof e->msg, fmt, ap);
    va_end(ap);
    size_t cap = sizeof e->msg;
    char *full = n >= (int)cap ? malloc((size_t)n + 1) : NULL;
    if (full) {
        vsnprintf(full, (size_t)n + 1, fmt, again);
        size_t head = (cap - 4) / 2, tail = cap - 4 - head;
        memcpy(e->msg, full, head);
        memcpy(e->msg + head, "...", 3);
        memcpy(e->msg + head + 3, full + (size_t)n - tail, tail);
        e->msg[cap - 1] = '\0';
        free(full);
    }
    va_end(again);
    return code;
}
