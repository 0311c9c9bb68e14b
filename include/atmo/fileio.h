/* fileio.h — output files are either complete or absent.
 *
 * Every writer opens a temporary file beside the target ("<path>.tmp.<pid>"), writes, and then
 * renames it over the target; on any error the temporary file is removed. Writers that go through
 * a library wanting a path (OpenEXR) write to the temporary path and call commit/abort. */
#ifndef ATMO_FILEIO_H
#define ATMO_FILEIO_H
#include <stdio.h>
#include "atmo/status.h"

#define ATMO_TMP_PATH_MAX 4096

/* The temporary path for `path`, into tmp (ATMO_TMP_PATH_MAX bytes). */
void atmo_tmp_path(const char *path, char *tmp);
/* fopen(tmp, "wb") with an error naming the target path. */
FILE *atmo_atomic_open(const char *path, char *tmp, atmo_err *e);
/* Close f (if not NULL) and rename tmp to path; on failure remove tmp. */
int atmo_atomic_commit(FILE *f, const char *tmp, const char *path, atmo_err *e);
/* Close f (if not NULL) and remove tmp. */
void atmo_atomic_abort(FILE *f, const char *tmp);
/* Write a whole text to path atomically. */
int atmo_write_text_file(const char *path, const char *text, atmo_err *e);

#endif
