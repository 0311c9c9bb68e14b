/* mie_cache.c — phase tables cached on disk, keyed by every parameter that shapes them.
 *
 * A table of a cumulus at one wavelength takes ~1 s to integrate (hundreds of Mie solutions over
 * the radius quadrature); a loaded one takes ~1 ms. The key is a canonical text of the inputs:
 * the format/numerics version MIE_TABLE_CACHE_VERSION, the distribution (all fields of mie_dsd,
 * %.17g so distinct doubles give distinct text), wavelength, refractive index and the table
 * options. The file, <cache dir>/mie-table-<FNV-1a 64 of the key>.bin, starts with that text and
 * is used only when the text matches exactly (a hash collision or a stale file is a miss) and the
 * size is right; anything else is rebuilt and rewritten atomically (include/atmo/fileio.h).
 * Contents after the key: int n, then theta_deg, mu, P, cdf (n doubles each), norm, and the
 * mie_bulk record as bytes (its size is part of the key). A failure to write the cache is not an
 * error: the table is still returned.
 *
 * Bump MIE_TABLE_CACHE_VERSION whenever the solver, the size integration or the grid change the
 * numbers, so old files stop matching. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "atmo/cl_runtime.h"
#include "atmo/fileio.h"
#include "atmo/mie.h"

#define MIE_TABLE_CACHE_VERSION 2
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

/* Read a table whose key text is `key`; 0 on success, -1 on any mismatch or short file. */
static int mie_cache_load(const char *path, const char *key, mie_table *t)
{
    size_t klen = strlen(key);
    char stored[MIE_CACHE_KEY_MAX];
    int n = 0, rc = -1;
    memset(t, 0, sizeof *t);
    FILE *f = fopen(path, "rb");
    if (!f)
        return -1;
    if (fread(stored, 1, klen, f) != klen || memcmp(stored, key, klen) != 0 ||
        fread(&n, sizeof n, 1, f) != 1 || n < 2 || n > 100000000)
        goto done;
    t->n = n;
    double **arrays[] = {&t->theta_deg, &t->mu, &t->P, &t->cdf};
    for (int i = 0; i < 4; i++) {
        *arrays[i] = malloc(sizeof(double) * (size_t)n);
        if (!*arrays[i] || fread(*arrays[i], sizeof(double), (size_t)n, f) != (size_t)n)
            goto done;
    }
    if (fread(&t->norm, sizeof t->norm, 1, f) != 1 || fread(&t->bulk, sizeof t->bulk, 1, f) != 1 ||
        fgetc(f) != EOF) /* trailing bytes: not a file this code wrote */
        goto done;
    rc = 0;
done:
    fclose(f);
    if (rc)
        mie_table_free(t);
    return rc;
}

static void mie_cache_store(const char *path, const char *key, const mie_table *t)
{
    char tmp[ATMO_TMP_PATH_MAX];
    atmo_err e;
    FILE *f = atmo_atomic_open(path, tmp, &e);
    if (!f)
        return;
    size_t n = (size_t)t->n;
    int ok = fwrite(key, 1, strlen(key), f) == strlen(key) && fwrite(&t->n, sizeof t->n, 1, f) == 1 &&
             fwrite(t->theta_deg, sizeof(double), n, f) == n &&
             fwrite(t->mu, sizeof(double), n, f) == n && fwrite(t->P, sizeof(double), n, f) == n &&
             fwrite(t->cdf, sizeof(double), n, f) == n &&
             fwrite(&t->norm, sizeof t->norm, 1, f) == 1 &&
             fwrite(&t->bulk, sizeof t->bulk, 1, f) == 1;
    if (ok)
        atmo_atomic_commit(f, tmp, path, &e);
    else
        atmo_atomic_abort(f, tmp);
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
    if (rc == ATMO_OK && cached)
        mie_cache_store(path, key, t);
    return rc;
}
