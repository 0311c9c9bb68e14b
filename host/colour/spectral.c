/* spectral.c — parse the embedded CSV tables of data/ and interpolate them.
 *
 * The tables are parsed all together at the first lookup and kept until exit (a handful of
 * kilobytes). The parse runs under pthread_once: threads of one process ask for tables at the
 * same time (the viewer's render thread plans a scene while its window thread computes the
 * sun's white point), and each must see every table complete; after the parse the cache is only
 * read, so lookups need no lock. The CSVs have one header line, then rows of comma-separated
 * numbers in increasing wavelength (data/README.md). */
#include <pthread.h>
#include <stdlib.h>
#include <string.h>
#include "atmo/embedded.h"
#include "atmo/spectral.h"

#define SPECTRAL_MAX_TABLES 8

static struct {
    const char *name;
    spectral_table table;
} spectral_cache[SPECTRAL_MAX_TABLES];
static int spectral_cache_count;
static pthread_once_t spectral_once = PTHREAD_ONCE_INIT;

static int spectral_parse(const char *text, spectral_table *t)
{
    const char *p = strchr(text, '\n');
    if (!p)
        return -1;
    int columns = 1;
    for (const char *q = text; q < p; q++)
        columns += *q == ',';
    int rows = 0;
    for (const char *q = p + 1; *q; q++)
        rows += *q == '\n';
    t->values = malloc(sizeof(double) * (size_t)(rows * columns));
    if (!t->values)
        return -1;
    t->columns = columns;
    t->rows = 0;
    p++;
    while (*p && t->rows < rows) {
        char *end;
        for (int c = 0; c < columns; c++) {
            t->values[t->rows * columns + c] = strtod(p, &end);
            if (end == p)
                return -1;
            p = end + (*end == ',');
        }
        while (*p == '\r' || *p == '\n')
            p++;
        t->rows++;
    }
    return t->rows > 1 ? 0 : -1;
}

/* Every embedded table into the cache; one that does not parse is left out (lookups of it
 * give NULL). */
static void spectral_parse_all(void)
{
    for (const struct atmo_embedded_file *f = atmo_data_files;
         f->name && spectral_cache_count < SPECTRAL_MAX_TABLES; f++) {
        spectral_table *t = &spectral_cache[spectral_cache_count].table;
        if (spectral_parse(f->text, t) != 0) {
            free(t->values);
            memset(t, 0, sizeof *t);
            continue;
        }
        spectral_cache[spectral_cache_count++].name = f->name;
    }
}

const spectral_table *spectral_table_get(const char *name)
{
    pthread_once(&spectral_once, spectral_parse_all);
    for (int i = 0; i < spectral_cache_count; i++)
        if (strcmp(spectral_cache[i].name, name) == 0)
            return &spectral_cache[i].table;
    return NULL;
}

double spectral_table_lookup(const spectral_table *t, int c, double lambda_nm)
{
    const double *v = t->values;
    int n = t->rows, w = t->columns;
    if (lambda_nm <= v[0])
        return v[c];
    if (lambda_nm >= v[(n - 1) * w])
        return v[(n - 1) * w + c];
    int lo = 0, hi = n - 1; /* binary search for the bracketing rows */
    while (hi - lo > 1) {
        int mid = (lo + hi) / 2;
        if (v[mid * w] <= lambda_nm)
            lo = mid;
        else
            hi = mid;
    }
    double l0 = v[lo * w], l1 = v[hi * w];
    double t01 = (lambda_nm - l0) / (l1 - l0);
    return v[lo * w + c] + (v[hi * w + c] - v[lo * w + c]) * t01;
}

double spectral_solar_irradiance(double lambda_nm)
{
    return spectral_table_lookup(spectral_table_get("data/astm_g173_extraterrestrial.csv"), 1,
                                 lambda_nm);
}

double spectral_ozone_cross_section_m2(double lambda_nm)
{
    return spectral_table_lookup(spectral_table_get("data/ozone_cross_section.csv"), 1, lambda_nm);
}

double spectral_ozone_peak_density_per_m3(double dobson, double tent_width_m)
{
    const double molecules_per_m2_per_du = 2.687e20;
    /* a tent of unit peak and total width w integrates to w/2 */
    return dobson * molecules_per_m2_per_du / (0.5 * tent_width_m);
}
