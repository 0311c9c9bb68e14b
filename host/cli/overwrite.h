/* overwrite.h — the commands' safe default for outputs (overwrite.c): a file that exists is
 * kept unless the user says --force. */
#ifndef ATMO_OVERWRITE_H
#define ATMO_OVERWRITE_H
#include "atmo/status.h"

/* ATMO_OK when `path` may be written: it does not exist, it is not a regular file (a device or
 * a FIFO holds nothing to lose), or `force` is set. Otherwise ATMO_ERR_USAGE with one line
 * naming the option, the file and --force. */
int overwrite_check(const char *option, const char *path, int force, atmo_err *e);

#endif
