/* plan_cloud.c — the cloud shell and observer in the plan (atmo/plan_cloud.h).
 *
 * Bulk optics per render wavelength from the Mie table of the scene's droplet size distribution
 * (mie_table_get: built once, then read from the disk cache): sigma_ext = (sigma_ext / LWC) x
 * LWC (1/m), the single-scattering albedo and the asymmetry g. The three 4pi-normalised tables
 * have their own angle grids (finer for the shorter wavelength, where x is larger); they are
 * resampled by linear interpolation onto the grid of the longest one and packed as float4 rows
 * (P_0, P_1, P_2, theta in radians), uploaded into LUT buffer 0 behind the transmittance LUT;
 * the plan owns the packed rows (atmo_plan_free releases them).
 *
 * The observer's centre is placed camera-relative in the world's axes, as the kernels' 3-D
 * visibility sources take it (kernels/media/observer.h): distance_m horizontally from the
 * camera away from the sun's azimuth and height_m along the camera's local vertical,
 *     c = -distance e_s + height up,  e_s = the horizontal unit vector toward the sun
 * (with the sun at the zenith, the horizontal axis medium_ray_from_cosines takes, so a probe's
 * frame and the observer agree). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "atmo/mie.h"
#include "atmo/plan_cloud.h"

/* The observer's centre (see the top of the file) from the float camera frame the kernels see. */
static float4 observer_centre(const atmo_scene *s, const atmo_gpu_scene *g)
{
    double up[3] = {g->camera.local_up.x, g->camera.local_up.y, g->camera.local_up.z}, sun[3];
    double sun_f[3] = {g->sun_direction.x, g->sun_direction.y, g->sun_direction.z};
    double k = up[0] * sun_f[0] + up[1] * sun_f[1] + up[2] * sun_f[2], len = 0.0;
    for (int i = 0; i < 3; i++)
        sun[i] = sun_f[i] - k * up[i], len += sun[i] * sun[i];
    if (len < 1e-12) { /* the sun at the zenith: up x (x or z axis), as the kernels take it */
        double axis[3] = {fabs(up[0]) < 0.6 ? 1.0 : 0.0, 0.0, fabs(up[0]) < 0.6 ? 0.0 : 1.0};
        sun[0] = up[1] * axis[2] - up[2] * axis[1];
        sun[1] = up[2] * axis[0] - up[0] * axis[2];
        sun[2] = up[0] * axis[1] - up[1] * axis[0];
        len = sun[0] * sun[0] + sun[1] * sun[1] + sun[2] * sun[2];
    }
    len = sqrt(len);
    float4 o;
    o.x = (float)(-s->observer.distance_m * sun[0] / len + s->observer.height_m * up[0]);
    o.y = (float)(-s->observer.distance_m * sun[1] / len + s->observer.height_m * up[1]);
    o.z = (float)(-s->observer.distance_m * sun[2] / len + s->observer.height_m * up[2]);
    o.w = (float)s->observer.radius_m;
    return o;
}

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

/* Insert a fragment before the composition of the media (kernels/media/media.h). */
static int insert_fragment(atmo_plan *p, const char *name, atmo_err *e)
{
    int at = p->fragment_count;
    for (int i = 0; i < p->fragment_count; i++)
        if (strcmp(p->fragments[i], "kernels/media/media.h") == 0) {
            at = i;
            break;
        }
    if (p->fragment_count + 3 > ATMO_PLAN_MAX_FRAGMENTS)
        return atmo_fail(e, ATMO_ERR_RUNTIME, "too many kernel fragments (a build bug)");
    memmove(&p->fragments[at + 1], &p->fragments[at],
            sizeof p->fragments[0] * (size_t)(p->fragment_count - at));
    p->fragments[at] = name;
    p->fragment_count++;
    return ATMO_OK;
}

int atmo_plan_cloud(const atmo_scene *s, atmo_plan *p, atmo_err *e)
{
    int rc = ATMO_OK;
    mie_table t[3];
    memset(t, 0, sizeof t);
    if (!s->cloud.enabled && !s->observer.enabled)
        return ATMO_OK;
    if (s->atmosphere.method != ATMO_METHOD_SINGLE && s->atmosphere.method != ATMO_METHOD_MARCH)
        return atmo_fail(e, ATMO_ERR_USAGE,
                         "cloud.enabled/observer.enabled work with atmosphere.method=single or "
                         "march only (got %s); set one of those",
                         p->method);
    if (s->cloud.enabled && s->cloud.top_m <= s->cloud.bottom_m)
        return atmo_fail(e, ATMO_ERR_USAGE,
                         "cloud.top_m (%g) must be above cloud.bottom_m (%g); raise the top",
                         s->cloud.top_m, s->cloud.bottom_m);
    atmo_gpu_scene *g = &p->gpu;
    g->cloud_steps = ATMO_CLOUD_STEPS;
    g->cloud_phase = s->cloud.phase;
    if (s->observer.enabled)
        g->observer = observer_centre(s, g);

    if (s->cloud.enabled) {
        const char *dsd_name = atmo_param_find("cloud.dsd")->names[s->cloud.dsd];
        double sun_radius = s->cloud.sun_disc ? s->sun.angular_radius_deg : 0.0;
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
            (&g->cloud_extinction.x)[i] = (float)(t[i].bulk.sigma_ext_per_lwc * s->cloud.lwc_g_m3);
            (&g->cloud_albedo.x)[i] = (float)t[i].bulk.albedo;
            (&g->cloud_g.x)[i] = (float)t[i].bulk.g;
            diameter_um = 2.0 * t[1].bulk.r_eff_um;
        }
        /* Jendersie-d'Eon's fit holds for 5-50 um */
        g->cloud_g.w = (float)fmin(fmax(diameter_um, 5.0), 50.0);
        g->cloud_extinction.w = (float)s->cloud.bottom_m;
        g->cloud_albedo.w = (float)s->cloud.top_m;
        if (p->upload_count == ATMO_PLAN_MAX_UPLOADS) {
            rc = atmo_fail(e, ATMO_ERR_RUNTIME, "too many plan uploads (a build bug)");
            goto cleanup;
        }
        float4 *rows = NULL;
        int count = 0;
        if ((rc = pack_tables(t, &rows, &count, e)))
            goto cleanup;
        size_t offset = (p->lut_bytes[0] + 15) / 16 * 16;
        atmo_plan_upload up = {0, offset, sizeof(float4) * (size_t)count, rows, rows};
        p->uploads[p->upload_count++] = up;
        p->lut_bytes[0] = offset + up.bytes;
        g->cloud_table_offset = (int)(offset / sizeof(float4));
        g->cloud_table_size = count;
    } else {
        /* observer only: an empty shell at the ground */
        g->cloud_extinction.w = g->cloud_albedo.w = 0.0f;
    }
    if ((rc = insert_fragment(p, "kernels/media/observer.h", e)) ||
        (rc = insert_fragment(p, "kernels/media/cloud_shell.h", e)))
        goto cleanup;
    size_t used = strlen(p->defines);
    snprintf(p->defines + used, sizeof p->defines - used, "%s-DATMO_CLOUD", used ? " " : "");
cleanup:
    for (int i = 0; i < 3; i++)
        mie_table_free(&t[i]);
    return rc;
}
