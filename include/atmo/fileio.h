/* fileio.h — output files are either complete or absent, and never replace what is not theirs.
 *
 * Every writer opens a temporary file beside the target ("<path>.tmp.<pid>"), writes, and then
 * fsyncs it, renames it over the target and fsyncs the directory; on any error the temporary
 * file is removed. Writers that go through a library wanting a path (OpenEXR) write to the
 * temporary path and call commit/abort. Taking a temporary path also removes the
 * "<path>.tmp.<pid>" files left by writers that were killed (their pid is no running process).
 *
 * What an output path names decides how it is written (atmo_output_target):
 *   - nothing yet, or a regular file: the atomic rename above;
 *   - a symbolic link (through any chain) to a regular file: the file it points to is replaced
 *     atomically, the link stays;
 *   - "-" (standard output), a FIFO or a character device: written through. The whole output is
 *     first written to a temporary file in $TMPDIR (/tmp without it), then copied into the
 *     stream, so a reader sees the complete output or nothing;
 *   - anything else (a directory, a block device, a socket, a link to none of the above, a
 *     dangling link) is refused.
 * Inputs are opened without blocking and must be regular files (atmo_open_regular), so a FIFO
 * given as an input is refused instead of waiting forever for a writer. */
#ifndef ATMO_FILEIO_H
#define ATMO_FILEIO_H
#include <stdio.h>
#include "atmo/status.h"

#define ATMO_TMP_PATH_MAX 4096

/* How `path` is written: ATMO_OK with the file that a rename replaces in target
 * (ATMO_TMP_PATH_MAX bytes: path itself, or the regular file a link resolves to) and *stream 0,
 * or the stream to write through in target ("-" or the path) and *stream 1; ATMO_ERR_USAGE
 * with one line naming `option` (when not NULL) and the path otherwise. */
int atmo_output_target(const char *option, const char *path, char *target, int *stream,
                       atmo_err *e);
/* Open an input for reading without blocking on it: NULL with errno set and *why (when not
 * NULL) a short reason ("not a regular file (a FIFO)", or strerror) unless it is a regular
 * file. The returned stream reads normally (blocking). */
FILE *atmo_open_regular(const char *path, const char **why);
/* The same for a file descriptor: -1 with errno and *why, or an fd open O_RDONLY on a regular
 * file, blocking. */
int atmo_open_regular_fd(const char *path, const char **why);

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
