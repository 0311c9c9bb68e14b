/* fileio.h — output files are either complete or absent.
 *
 * Every writer opens a temporary file beside the target ("<path>.tmp.<pid>"), writes, and then
 * fsyncs it, renames it over the target and fsyncs the directory; on any error the temporary
 * file is removed. Writers that go through a library wanting a path (OpenEXR) write to the
 * temporary path and call commit/abort. Taking a temporary path also removes the
 * "<path>.tmp.<pid>" files left by writers that were killed (their pid is no running process). */
#ifndef ATMO_FILEIO_H
#define ATMO_FILEIO_H
#include <stdio.h>
#include "atmo/status.h"

#define ATMO_TMP_PATH_MAX 4096

/* Remove the temporary files of path whose writer is no running process; returns how many. */
int atmo_remove_stale_tmp(const char *path);
/* atmo_remove_stale_tmp, then the temporary path for `path` into tmp (ATMO_TMP_PATH_MAX). */
void atmo_tmp_path(const char *path, char *tmp);
/* fopen(tmp, "wb") of atmo_tmp_path's name, with an error naming the target path. */
FILE *atmo_atomic_open(const char *path, char *tmp, atmo_err *e);
/* Flush, fsync and close f (or fsync tmp when f is NULL), rename tmp to path and fsync the
 * directory; on failure remove tmp. */
int atmo_atomic_commit(FILE *f, const char *tmp, const char *path, atmo_err *e);
/* Close f (if not NULL) and remove tmp. */
void atmo_atomic_abort(FILE *f, const char *tmp);
/* Write a whole text to path atomically. */
int atmo_write_text_file(const char *path, const char *text, atmo_err *e);

#endif
