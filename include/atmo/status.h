/* status.h — how atmo functions report failure.
 *
 * Functions that can fail return an int status and fill an atmo_err with one line for the user:
 * what was wrong, where, and how to fix it. The status doubles as the process exit code:
 *   ATMO_OK (0), ATMO_ERR_RUNTIME (1: OpenCL, I/O, out of memory), ATMO_ERR_USAGE (2: bad
 *   arguments, bad scene, bad value), ATMO_INTERRUPTED_PARTIAL (3: stopped by a signal or a
 *   cancel token after some samples; the partial result is kept and marked partial) and
 *   ATMO_INTERRUPTED_EMPTY (4: stopped before any result, e.g. during the precompute; nothing
 *   half-computed is kept, cached or written). */
#ifndef ATMO_STATUS_H
#define ATMO_STATUS_H
#include <stddef.h>

enum {
    ATMO_OK = 0,
    ATMO_ERR_RUNTIME = 1,
    ATMO_ERR_USAGE = 2,
    ATMO_INTERRUPTED_PARTIAL = 3,
    ATMO_INTERRUPTED_EMPTY = 4
};

typedef struct atmo_err {
    char msg[1024];
} atmo_err;

/* Format the message into e (when e is not NULL) and return code. */
int atmo_fail(atmo_err *e, int code, const char *fmt, ...) __attribute__((format(printf, 3, 4)));

#endif
