/* plan_cloud.c — the cloud shell and observer in the plan (atmo/plan_cloud.h).
 *
 * Bulk optics per render wavelength from the Mie table of the scene's droplet size distribution
 * (mie_table_get: built once, then read from the disk cache): sigma_ext = (sigma_ext / LWC) x
 * LWC (1/m), the single-scattering albedo and the asymmetry g. The three 4pi-normalised tables
 * have their own angle grids (finer for the shorter wavelength, where x is larger); they are
 * resampled by linear interpolation onto the grid of the longest one and packed as float4 rows
 * (P_0, P_1, P_2, theta in radians) into the buffer cloud_phase_table (a host table: copied to
 * the device before the passes; one zero row when the scene has an observer but no cloud).
 *
 * The packed rows must outlive the render (plan.h's host_data); the plan has no destructor, so they
 * are kept for the life of the process in a small list keyed by their parameters, which also
 * spares re-packing when a program plans the same cloud twice. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "atmo/mie.h"
#include "atmo/plan_cloud.h"

typedef struct cloud_rows {
    struct cloud_rows *next;
    char dsd[32];
    double wavelengths_nm[3], sun_radius_deg;
    int count;
    float4 *rows;
} cloud_rows;

static cloud_rows *cloud_rows_kept;

static int pack_tables(const mie_table t[3], float4 **out, int *count, atmo_err *e)
{
    int m = 0;
    for (int i = 1; i < 3; i++)
        if (t[i].n > t[m].n)
            m = i;
    float4 *rows = malloc(sizeof *rows * (size_t)t[m].n);
    if (!rows)
        return atmo_fail(e, ATMO_ERR_RUNTIME, "out of memory packing the cloud's phase tables");
    for (int j = 0; j < t[m].n; j++) {
        double theta = t[m].theta_deg[j];
        rows[j].x = (float)mie_table_eval(&t[0], theta);
        rows[j].y = (float)mie_table_eval(&t[1], theta);
        rows[j].z = (float)mie_table_eval(&t[2], theta);
        rows[j].w = (float)(theta * M_PI / 180.0);
    }
    *out = rows;
    *count = t[m].n;
    return ATMO_OK;
}

int atmo_plan_cloud(const atmo_scene *s, atmo_plan *p, atmo_err *e)
{
    int rc = ATMO_OK;
    mie_table t[3];
    memset(t, 0, sizeof t);
    if (s->atmosphere.method != ATMO_METHOD_SINGLE && s->atmosphere.method != ATMO_METHOD_MARCH)
        return atmo_fail(e, ATMO_ERR_USAGE,
                         "cloud.enabled/observer.enabled work with atmosphere.method=single or "
                         "march only (got %s); set one of those",
                         p->method);
    if (s->cloud.enabled && s->cloud.top_m <= s->cloud.bottom_m)
        return atmo_fail(e, ATMO_ERR_USAGE,
                         "cloud.top_m (%g) must be above cloud.bottom_m (%g); raise the top",
                         s->cloud.top_m, s->cloud.bottom_m);
    atmo_gpu_cloud *g = &p->gpu.cloud;
    g->steps = ATMO_CLOUD_STEPS;
    g->phase = s->cloud.phase;
    if (s->observer.enabled) {
        float4 o = {(float)-s->observer.distance_m, (float)s->observer.height_m, 0.0f,
                    (float)s->observer.radius_m};
        g->observer = o;
    }

    if (s->cloud.enabled) {
        const char *dsd_name = atmo_param_find("cloud.dsd")->names[s->cloud.dsd];
        double sun_radius = s->cloud.sun_disc ? s->sun.angular_radius_deg : 0.0;
        cloud_rows *kept = cloud_rows_kept;
        while (kept && !(strcmp(kept->dsd, dsd_name) == 0 && kept->sun_radius_deg == sun_radius &&
                         memcmp(kept->wavelengths_nm, s->render.wavelengths_nm,
                                sizeof kept->wavelengths_nm) == 0))
            kept = kept->next;
        mie_dsd d;
        if (mie_dsd_preset(dsd_name, &d))
            return atmo_fail(e, ATMO_ERR_RUNTIME, "cloud.dsd=%s is not a Mie preset (a build bug)",
                             dsd_name);
        mie_table_options opt;
        memset(&opt, 0, sizeof opt);
        opt.sun_radius_deg = sun_radius;
        double diameter_um = 0.0;
        for (int i = 0; i < 3; i++) {
            double n, k, lambda = s->render.wavelengths_nm[i];
            if ((rc = mie_water_index(lambda, &n, &k, e)) ||
                (rc = mie_table_get(&d, lambda, n, k, &opt, 1, &t[i], NULL, e)))
                goto cleanup;
            (&g->extinction.x)[i] = (float)(t[i].bulk.sigma_ext_per_lwc * s->cloud.lwc_g_m3);
            (&g->albedo.x)[i] = (float)t[i].bulk.albedo;
            (&g->g.x)[i] = (float)t[i].bulk.g;
            diameter_um = 2.0 * t[1].bulk.r_eff_um;
        }
        /* Jendersie-d'Eon's fit holds for 5-50 um */
        g->diameter_um = (float)fmin(fmax(diameter_um, 5.0), 50.0);
        g->base_m = (float)s->cloud.bottom_m;
        g->top_m = (float)s->cloud.top_m;
        if (!kept) {
            if (!(kept = calloc(1, sizeof *kept))) {
                rc = atmo_fail(e, ATMO_ERR_RUNTIME, "out of memory planning the cloud");
                goto cleanup;
            }
            if ((rc = pack_tables(t, &kept->rows, &kept->count, e))) {
                free(kept);
                goto cleanup;
            }
            snprintf(kept->dsd, sizeof kept->dsd, "%s", dsd_name);
            memcpy(kept->wavelengths_nm, s->render.wavelengths_nm, sizeof kept->wavelengths_nm);
            kept->sun_radius_deg = sun_radius;
            kept->next = cloud_rows_kept;
            cloud_rows_kept = kept;
        }
        rc = atmo_plan_add_buffer(p, "cloud_phase_table", "float4",
                                  sizeof(float4) * (size_t)kept->count, 0, kept->rows, e);
        g->table_size = kept->count;
    } else {
        /* observer only: an empty shell at the ground; the table is one zero row, never read */
        static const float4 zero_row;
        g->base_m = g->top_m = 0.0f;
        rc = atmo_plan_add_buffer(p, "cloud_phase_table", "float4", sizeof zero_row, 0,
                                  &zero_row, e);
    }
cleanup:
    for (int i = 0; i < 3; i++)
        mie_table_free(&t[i]);
    return rc;
}
