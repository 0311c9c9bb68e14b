/* cache_file.c — self-verifying cache files: header, key, payload, checksum (atmo/cache_file.h).
 *
 * The checksum is FNV-1a 64 (Fowler, Noll, Vo): h = (h xor byte) * 1099511628211 from the basis
 * 14695981039346656037, over the key bytes then the payload bytes. Each step is a bijection of h
 * for a fixed byte, so two inputs of equal length that differ in one byte always differ in h;
 * the stored lengths catch truncation and extension. */
#include <errno.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include "atmo/cache_file.h"
#include "atmo/fileio.h"

#define MAGIC_BYTES 16

typedef struct header {
    char magic[MAGIC_BYTES];
    char kind[ATMO_CACHE_KIND_MAX];
    uint64_t key_bytes, payload_bytes, checksum;
} header;

static uint64_t fnv1a(uint64_t h, const void *data, size_t n)
{
    const unsigned char *p = data;
    for (size_t i = 0; i < n; i++)
        h = (h ^ p[i]) * 1099511628211ull;
    return h;
}

static uint64_t checksum(const void *key, size_t key_bytes, const void *payload, size_t n)
{
    return fnv1a(fnv1a(14695981039346656037ull, key, key_bytes), payload, n);
}

int atmo_cache_file_write(const char *path, const char *kind, const void *key, size_t key_bytes,
                          const void *payload, size_t payload_bytes)
{
    header h;
    memset(&h, 0, sizeof h);
    memcpy(h.magic, ATMO_CACHE_FORMAT, MAGIC_BYTES);
    snprintf(h.kind, sizeof h.kind, "%s", kind);
    h.key_bytes = key_bytes;
    h.payload_bytes = payload_bytes;
    h.checksum = checksum(key, key_bytes, payload, payload_bytes);
    char tmp[ATMO_TMP_PATH_MAX];
    FILE *f = atmo_atomic_open(path, tmp, NULL);
    if (!f)
        return ATMO_ERR_RUNTIME;
    if (fwrite(&h, sizeof h, 1, f) != 1 || fwrite(key, 1, key_bytes, f) != key_bytes ||
        fwrite(payload, 1, payload_bytes, f) != payload_bytes) {
        atmo_atomic_abort(f, tmp);
        return ATMO_ERR_RUNTIME;
    }
    return atmo_atomic_commit(f, tmp, path, NULL);
}

/* Read and verify the whole file; 0 with key and payload malloc'd, 1 absent, -1 with why. */
static int load(const char *path, header *h, unsigned char **key, unsigned char **payload,
                const char **why)
{
    *key = *payload = NULL;
    struct stat st;
    if (stat(path, &st) != 0)
        return 1;
    FILE *f = atmo_open_regular(path, why); /* a FIFO would block the reader for ever */
    if (!f)
        return -1;
    int rc = -1;
    if (fstat(fileno(f), &st) != 0)
        *why = "cannot stat it";
    else if (fread(h, sizeof *h, 1, f) != 1 || memcmp(h->magic, ATMO_CACHE_FORMAT, MAGIC_BYTES))
        *why = (size_t)st.st_size < sizeof *h ? "shorter than its header" : "no cache-file magic";
    else if (h->kind[ATMO_CACHE_KIND_MAX - 1] != 0)
        *why = "its kind is not a name";
    else if (h->key_bytes > (uint64_t)st.st_size || h->payload_bytes > (uint64_t)st.st_size ||
             sizeof *h + h->key_bytes + h->payload_bytes != (uint64_t)st.st_size)
        *why = (uint64_t)st.st_size < sizeof *h + h->key_bytes + h->payload_bytes
                   ? "truncated (shorter than its header says)"
                   : "extended (longer than its header says)";
    else if (!(*key = malloc(h->key_bytes + 1)) || !(*payload = malloc(h->payload_bytes + 1)))
        *why = "out of memory reading it";
    else if (fread(*key, 1, h->key_bytes, f) != h->key_bytes ||
             fread(*payload, 1, h->payload_bytes, f) != h->payload_bytes)
        *why = "read error";
    else if (checksum(*key, h->key_bytes, *payload, h->payload_bytes) != h->checksum)
        *why = "checksum mismatch";
    else
        rc = 0;
    fclose(f);
    if (rc) {
        free(*key);
        free(*payload);
        *key = *payload = NULL;
    }
    return rc;
}

void atmo_cache_file_reject(const char *path, const char *why)
{
    if (remove(path) == 0)
        fprintf(stderr, "atmo: cache file %s is damaged (%s); removed, recomputing it\n", path,
                why);
    else
        fprintf(stderr, "atmo: cache file %s is damaged (%s) and cannot be removed (%s); "
                        "recomputing without it (delete it, or run atmo cache verify)\n",
                path, why, strerror(errno));
}

int atmo_cache_file_read(const char *path, const char *kind, const void *key, size_t key_bytes,
                         void **payload, size_t *payload_bytes)
{
    header h;
    unsigned char *stored_key, *data;
    const char *why = "";
    int rc = load(path, &h, &stored_key, &data, &why);
    if (rc == 0 && strcmp(h.kind, kind) != 0)
        why = "another kind of product", rc = -1;
    else if (rc == 0 && (h.key_bytes != key_bytes || memcmp(stored_key, key, key_bytes) != 0))
        why = "its key does not match its name", rc = -1;
    free(stored_key);
    if (rc == -1)
        atmo_cache_file_reject(path, why);
    if (rc) {
        free(data);
        return rc;
    }
    *payload = data;
    *payload_bytes = (size_t)h.payload_bytes;
    return 0;
}

int atmo_cache_file_check(const char *path, char kind[ATMO_CACHE_KIND_MAX], const char **why)
{
    header h;
    unsigned char *key, *data;
    *why = "";
    int rc = load(path, &h, &key, &data, why);
    free(key);
    free(data);
    if (rc == 1) {
        *why = "cannot open it";
        return -1;
    }
    if (rc == 0)
        memcpy(kind, h.kind, ATMO_CACHE_KIND_MAX);
    return rc;
}

long atmo_first_nonfinite_float(const float *v, size_t n)
{
    for (size_t i = 0; i < n; i++)
        if (!isfinite(v[i]))
            return (long)i;
    return -1;
}

long atmo_first_nonfinite_double(const double *v, size_t n)
{
    for (size_t i = 0; i < n; i++)
        if (!isfinite(v[i]))
            return (long)i;
    return -1;
}
