/* mie_cache.c — phase tables cached on disk, keyed by every parameter that shapes them.
 *
 * A table of a cumulus at one wavelength takes ~1 s to integrate (hundreds of Mie solutions over
 * the radius quadrature); a loaded one takes ~1 ms. The key is a canonical text of the inputs:
 * the format/numerics version MIE_TABLE_CACHE_VERSION, the distribution (all fields of mie_dsd,
 * %.17g so distinct doubles give distinct text), wavelength, refractive index and the table
 * options. The file, <cache dir>/mie-table-<FNV-1a 64 of the key>.bin, is a self-verifying
 * cache file (atmo/cache_file.h) holding that text as its key; it is used only when it verifies
 * and the key text matches exactly, anything else is warned about, deleted, rebuilt and
 * rewritten. Payload: int n, then theta_deg, mu, P, cdf (n doubles each), norm, and the mie_bulk
 * record as bytes (its size is part of the key). A built table with a NaN or Inf is an error and
 * is never stored. A failure to write the cache is not an error: the table is still returned.
 *
 * Bump MIE_TABLE_CACHE_VERSION whenever the solver, the size integration or the grid change the
 * numbers, so old files stop matching. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "atmo/cache_file.h"
#include "atmo/cl_runtime.h"
#include "atmo/fileio.h"
#include "atmo/mie.h"

#define MIE_TABLE_CACHE_VERSION 3
#define MIE_CACHE_KEY_MAX 1024

static unsigned long long mie_fnv1a(const char *s)
{
    unsigned long long h = 1469598103934665603ull;
    for (; *s; s++)
        h = (h ^ (unsigned char)*s) * 1099511628211ull;
    return h;
}

static void mie_cache_key(const mie_dsd *d, double wavelength_nm, double n, double k,
                            const mie_table_options *opt, char *key)
{
    mie_table_options o = opt ? *opt : (mie_table_options){0};
    snprintf(key, MIE_CACHE_KEY_MAX,
             "atmo-mie-table v%d bulk%zu\n"
             "dsd %d %.17g %.17g %.17g %.17g %.17g %.17g %.17g %.17g %.17g\n"
             "lambda_nm %.17g index %.17g %.17g\n"
             "grid %.17g %.17g %.17g %d sun %.17g dx %.17g tol %.17g\n",
             MIE_TABLE_CACHE_VERSION, sizeof(mie_bulk), (int)d->kind, d->radius_um, d->r_eff_um,
             d->v_eff, d->r_g_um, d->sigma_g, d->alpha, d->b, d->gamma, d->r_max_um,
             wavelength_nm, n, k, o.fine_step_deg, o.fine_zone_deg, o.coarse_step_deg, o.uniform,
             o.sun_radius_deg, o.max_dx,
             o.max_dx > 0.0 ? 0.0 : (o.tolerance > 0.0 ? o.tolerance : MIE_DSD_TOLERANCE));
}

/* The payload: int n, then theta_deg, mu, P, cdf (n doubles each), norm, the mie_bulk bytes. */
static size_t payload_bytes(int n)
{
    return sizeof(int) + 4 * sizeof(double) * (size_t)n + sizeof(double) + sizeof(mie_bulk);
}

/* Read the table stored under `key`; 0 on success, -1 when there is none or it was damaged
 * (atmo_cache_file_read has then warned and deleted it). */
static int mie_cache_load(const char *path, const char *key, mie_table *t)
{
    void *data = NULL;
    size_t bytes = 0;
    int n = 0;
    memset(t, 0, sizeof *t);
    if (atmo_cache_file_read(path, "mie-table", key, strlen(key), &data, &bytes) != 0)
        return -1;
    const unsigned char *p = data;
    if (bytes >= sizeof n)
        memcpy(&n, p, sizeof n);
    if (n < 2 || bytes != payload_bytes(n)) {
        atmo_cache_file_reject(path, "its table size does not match its length");
        free(data);
        return -1;
    }
    p += sizeof n;
    t->n = n;
    double **arrays[] = {&t->theta_deg, &t->mu, &t->P, &t->cdf};
    for (int i = 0; i < 4; i++) {
        *arrays[i] = malloc(sizeof(double) * (size_t)n);
        if (!*arrays[i]) {
            mie_table_free(t);
            free(data);
            return -1;
        }
        memcpy(*arrays[i], p, sizeof(double) * (size_t)n);
        p += sizeof(double) * (size_t)n;
    }
    memcpy(&t->norm, p, sizeof t->norm);
    memcpy(&t->bulk, p + sizeof t->norm, sizeof t->bulk);
    free(data);
    return 0;
}

static void mie_cache_store(const char *path, const char *key, const mie_table *t)
{
    size_t n = (size_t)t->n, bytes = payload_bytes(t->n);
    unsigned char *data = malloc(bytes), *p = data;
    if (!data)
        return;
    memcpy(p, &t->n, sizeof t->n);
    p += sizeof t->n;
    const double *arrays[] = {t->theta_deg, t->mu, t->P, t->cdf};
    for (int i = 0; i < 4; i++, p += sizeof(double) * n)
        memcpy(p, arrays[i], sizeof(double) * n);
    memcpy(p, &t->norm, sizeof t->norm);
    memcpy(p + sizeof t->norm, &t->bulk, sizeof t->bulk);
    atmo_cache_file_write(path, "mie-table", key, strlen(key), data, bytes);
    free(data);
}

/* A table with a NaN or Inf anywhere is an error naming it, never cached or used. */
static int check_finite(const mie_table *t, double wavelength_nm, atmo_err *e)
{
    const mie_bulk *b = &t->bulk;
    const double *arrays[] = {t->theta_deg, t->mu, t->P, t->cdf};
    const char *names[] = {"angle", "cosine", "phase function", "CDF"};
    double bulk[] = {t->norm, b->qext, b->qsca, b->qback, b->albedo, b->g, b->sigma_ext_per_lwc,
                     b->sigma_sca_per_lwc, b->r_eff_um, b->v_eff};
    for (int i = 0; i < 4; i++) {
        long at = atmo_first_nonfinite_double(arrays[i], (size_t)t->n);
        if (at >= 0)
            return atmo_fail(e, ATMO_ERR_RUNTIME,
                             "the Mie phase table at %g nm has a non-finite %s value (entry %ld "
                             "of %d); it is not cached or used",
                             wavelength_nm, names[i], at, t->n);
    }
    if (atmo_first_nonfinite_double(bulk, sizeof bulk / sizeof bulk[0]) >= 0)
        return atmo_fail(e, ATMO_ERR_RUNTIME,
                         "the Mie phase table at %g nm has non-finite bulk optics (Q, albedo, g "
                         "or normalisation); it is not cached or used",
                         wavelength_nm);
    return ATMO_OK;
}

int mie_table_cache_path(const mie_dsd *d, double wavelength_nm, double n, double k,
                         const mie_table_options *opt, char *path, size_t size)
{
    char key[MIE_CACHE_KEY_MAX], dir[ATMO_TMP_PATH_MAX / 2];
    if (atmo_cache_dir(dir, sizeof dir) != 0)
        return -1;
    mie_cache_key(d, wavelength_nm, n, k, opt, key);
    snprintf(path, size, "%s/mie-table-%016llx.bin", dir, mie_fnv1a(key));
    return 0;
}

int mie_table_get(const mie_dsd *d, double wavelength_nm, double n, double k,
                  const mie_table_options *opt, int use_cache, mie_table *t, int *hit, atmo_err *e)
{
    char key[MIE_CACHE_KEY_MAX], path[ATMO_TMP_PATH_MAX / 2 + 64];
    int cached = use_cache && mie_table_cache_path(d, wavelength_nm, n, k, opt, path, sizeof path) == 0;
    if (hit)
        *hit = 0;
    if (cached) {
        mie_cache_key(d, wavelength_nm, n, k, opt, key);
        if (mie_cache_load(path, key, t) == 0) {
            if (hit)
                *hit = 1;
            return ATMO_OK;
        }
    }
    int rc = mie_table_build(d, wavelength_nm, n, k, opt, t, e);
    if (rc == ATMO_OK && (rc = check_finite(t, wavelength_nm, e)))
        mie_table_free(t);
    if (rc == ATMO_OK && cached)
        mie_cache_store(path, key, t);
    return rc;
}
