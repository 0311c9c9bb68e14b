/* cache_file.h — cached products (kernel binaries, LUTs, Mie tables) in files that verify
 * themselves (host/base/cache_file.c).
 *
 * A cache file is a fixed header, the key, then the payload:
 *   magic "atmo-cache-file1" (16 bytes), kind (16 bytes, NUL-padded: "kernel", "mie-table" or a
 *   feature's name), uint64 key length, uint64 payload length, uint64 FNV-1a-64 checksum of the
 *   key and the payload, the key bytes, the payload bytes; nothing after.
 * A reader trusts a file only when the magic, the kind, the key, both lengths (against the
 * file's size) and the checksum all match; anything else is damage: one warning line on stderr,
 * the file is deleted, and the caller recomputes and rewrites it. Writes go through
 * include/atmo/fileio.h (fsync, atomic rename), so a crash leaves the old file or the new one.
 * FNV-1a finds every single-byte change, truncation and extension (the lengths); it is not a
 * defence against a deliberate forgery. */
#ifndef ATMO_CACHE_FILE_H
#define ATMO_CACHE_FILE_H
#include <stddef.h>
#include "atmo/status.h"

#define ATMO_CACHE_KIND_MAX 16
/* Part of every product key, so files of another layout are never looked up. */
#define ATMO_CACHE_FORMAT "atmo-cache-file1"

/* Write the product atomically; a failure returns ATMO_ERR_RUNTIME (callers may ignore it: a
 * missing file only costs the next run a recomputation). */
int atmo_cache_file_write(const char *path, const char *kind, const void *key, size_t key_bytes,
                          const void *payload, size_t payload_bytes);
/* Read a product: 0 with *payload (malloc'd, caller frees) and *payload_bytes; 1 when there is
 * no file; -1 when the file is damaged or belongs to another key (warned and deleted). */
int atmo_cache_file_read(const char *path, const char *kind, const void *key, size_t key_bytes,
                         void **payload, size_t *payload_bytes);
/* Check a file on its own (atmo cache verify): 0 valid, with its kind; -1 damaged, with why. */
int atmo_cache_file_check(const char *path, char kind[ATMO_CACHE_KIND_MAX], const char **why);
/* One warning line naming the file and why, then delete it (a damaged or refused product). */
void atmo_cache_file_reject(const char *path, const char *why);

/* Index of the first NaN or Inf among n values, or -1 when all are finite. */
long atmo_first_nonfinite_float(const float *v, size_t n);
long atmo_first_nonfinite_double(const double *v, size_t n);

#endif
