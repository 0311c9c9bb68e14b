/* test_mie_cache.c — phase tables through the on-disk cache (host/mie/mie_cache.c).
 * labels: unit
 *
 * Oracle: the table built directly (mie_table_build). A cache hit must give bitwise the same
 * grid, P, CDF, normalisation and bulk properties (the file stores the doubles themselves, so
 * anything but equality is a bug); a changed parameter must miss; a truncated or foreign file
 * must be rebuilt, not trusted; use_cache = 0 neither reads nor writes. */
#include <stdlib.h>
#include <string.h>
#include <unistd.h>
#include "atmo/mie.h"
#include "testlib.h"

static int same_table(const mie_table *a, const mie_table *b)
{
    size_t n = (size_t)a->n * sizeof(double);
    return a->n == b->n && memcmp(a->theta_deg, b->theta_deg, n) == 0 &&
           memcmp(a->mu, b->mu, n) == 0 && memcmp(a->P, b->P, n) == 0 &&
           memcmp(a->cdf, b->cdf, n) == 0 && a->norm == b->norm &&
           memcmp(&a->bulk, &b->bulk, sizeof a->bulk) == 0;
}

int main(void)
{
    char dir[] = "/tmp/atmo-mie-cache-XXXXXX";
    if (!mkdtemp(dir))
        return 1;
    setenv("ATMO_CACHE_DIR", dir, 1);
    mie_dsd d;
    mie_dsd_preset("stratus", &d);
    mie_table_options opt = {.coarse_step_deg = 0.5, .fine_step_deg = 0.2}; /* keeps it fast */
    mie_table ref, t1, t2, t3;
    atmo_err e;
    int hit = -1;
    CHECK(mie_table_build(&d, 650.0, 1.331, 1e-8, &opt, &ref, &e) == ATMO_OK);

    CHECK(mie_table_get(&d, 650.0, 1.331, 1e-8, &opt, 1, &t1, &hit, &e) == ATMO_OK);
    CHECK(hit == 0);
    CHECK(same_table(&t1, &ref));
    CHECK(mie_table_get(&d, 650.0, 1.331, 1e-8, &opt, 1, &t2, &hit, &e) == ATMO_OK);
    CHECK(hit == 1);
    CHECK(same_table(&t2, &ref));
    mie_table_free(&t2);

    /* any parameter changes the key: index, wavelength, options, distribution */
    CHECK(mie_table_get(&d, 650.0, 1.331, 2e-8, &opt, 1, &t2, &hit, &e) == ATMO_OK && hit == 0);
    mie_table_free(&t2);
    mie_table_options opt2 = opt;
    opt2.sun_radius_deg = 0.265;
    CHECK(mie_table_get(&d, 650.0, 1.331, 1e-8, &opt2, 1, &t2, &hit, &e) == ATMO_OK && hit == 0);
    CHECK(t2.P[0] < ref.P[0]); /* the sun disc flattens the forward peak: really another table */
    mie_table_free(&t2);
    mie_table_options opt3 = opt;
    opt3.tolerance = 5e-4; /* the accuracy target is part of the key */
    CHECK(mie_table_get(&d, 650.0, 1.331, 1e-8, &opt3, 1, &t2, &hit, &e) == ATMO_OK && hit == 0);
    mie_table_free(&t2);
    opt3.tolerance = MIE_DSD_TOLERANCE; /* the default spelled out is the same table */
    CHECK(mie_table_get(&d, 650.0, 1.331, 1e-8, &opt3, 1, &t2, &hit, &e) == ATMO_OK && hit == 1);
    CHECK(same_table(&t2, &ref));
    mie_table_free(&t2);
    mie_dsd d2 = d;
    d2.v_eff = 0.11;
    CHECK(mie_table_get(&d2, 650.0, 1.331, 1e-8, &opt, 1, &t2, &hit, &e) == ATMO_OK && hit == 0);
    mie_table_free(&t2);

    /* a truncated file is a miss, rebuilt and rewritten */
    char path[4096];
    CHECK(mie_table_cache_path(&d, 650.0, 1.331, 1e-8, &opt, path, sizeof path) == 0);
    CHECK(truncate(path, 100) == 0);
    CHECK(mie_table_get(&d, 650.0, 1.331, 1e-8, &opt, 1, &t3, &hit, &e) == ATMO_OK && hit == 0);
    CHECK(same_table(&t3, &ref));
    mie_table_free(&t3);
    CHECK(mie_table_get(&d, 650.0, 1.331, 1e-8, &opt, 1, &t3, &hit, &e) == ATMO_OK && hit == 1);
    CHECK(same_table(&t3, &ref));
    mie_table_free(&t3);

    /* use_cache = 0 builds even when a file exists */
    CHECK(mie_table_get(&d, 650.0, 1.331, 1e-8, &opt, 0, &t3, &hit, &e) == ATMO_OK && hit == 0);
    CHECK(same_table(&t3, &ref));
    mie_table_free(&t3);

    mie_table_free(&t1);
    mie_table_free(&ref);
    char cmd[256];
    snprintf(cmd, sizeof cmd, "rm -rf '%s'", dir);
    CHECK(system(cmd) == 0);
    return test_finish();
}
