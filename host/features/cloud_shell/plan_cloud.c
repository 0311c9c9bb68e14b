/* plan_cloud.c — the cloud shell and observer in the plan (atmo/plan_cloud.h).
 *
 * Bulk optics per render wavelength from the Mie table of the scene's droplet size distribution
 * (mie_table_get: built once, then read from the disk cache): sigma_ext = (sigma_ext / LWC) x
 * LWC (1/m), the single-scattering albedo and the asymmetry g. The three 4pi-normalised tables
 * have their own angle grids (finer for the shorter wavelength, where x is larger); they are
 * resampled by linear interpolation onto the grid of the longest one and packed as float4 rows
 * (P_0, P_1, P_2, theta in radians) into the buffer cloud_phase_table (a host table: copied to
 * the device before the passes; one zero row when the scene has an observer but no cloud), with
 * its sampling CDF in cloud_phase_cdf (atmo_plan_phase_cdf: the format phase_table.h samples,
 * shared with the fBm layer); the plan owns both (atmo_plan_free releases them). With
 * cloud.phase=hg the asymmetry is cloud.hg_g at every wavelength, or the table's g where that
 * is 0.
 *
 * The observer's centre is placed camera-relative in the world's axes, as the kernels' 3-D
 * visibility sources take it (kernels/cloud_shell/observer.h): distance_m horizontally from the
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

/* int P sin(theta) dtheta over the rows' segment [a, b] of channel k, with P linear in theta
 * between the rows (as phase_rows_eval interpolates), in closed form:
 *     P_a (cos a - cos b) + (P_b - P_a) / (b - a) (sin b - sin a - (b - a) cos b) */
static double segment_integral(const float4 *lo, const float4 *hi, int k)
{
    double a = lo->w, b = hi->w, pa = (&lo->x)[k], pb = (&hi->x)[k];
    double slope = b > a ? (pb - pa) / (b - a) : 0.0;
    return pa * (cos(a) - cos(b)) + slope * (sin(b) - sin(a) - (b - a) * cos(b));
}

/* atmo_plan_phase_cdf (atmo/plan_cloud.h): each channel normalised so its interpolant
 * integrates to exactly 4 pi (the Mie table's trapezoids leave ~1e-4, which a furnace of many
 * scatterings would see as an albedo above 1), then the sampling CDF of the middle channel
 * from the same segment integrals. */
int atmo_plan_phase_cdf(float4 *rows, int n, atmo_plan *p, float **out, atmo_err *e)
{
    float *cdf = malloc(sizeof *cdf * (size_t)n);
    if (!cdf)
        return atmo_fail(e, ATMO_ERR_RUNTIME, "out of memory for a cloud's phase CDF");
    for (int k = 0; k < 3; k++) {
        double total = 0.0;
        for (int j = 1; j < n; j++)
            total += 2.0 * M_PI * segment_integral(&rows[j - 1], &rows[j], k);
        double scale = total > 0.0 ? 4.0 * M_PI / total : 1.0;
        for (int j = 0; j < n; j++)
            (&rows[j].x)[k] = (float)((double)(&rows[j].x)[k] * scale);
    }
    double acc = 0.0, total = 0.0;
    for (int j = 1; j < n; j++)
        total += segment_integral(&rows[j - 1], &rows[j], 1);
    cdf[0] = 0.0f;
    for (int j = 1; j < n; j++) {
        acc += segment_integral(&rows[j - 1], &rows[j], 1);
        cdf[j] = (float)(acc / (total > 0.0 ? total : 1.0));
    }
    cdf[n - 1] = 1.0f;
    *out = cdf;
    return atmo_plan_own(p, cdf, e);
}

int atmo_plan_mie_optics(const atmo_scene *s, const char *key, const char *dsd, int sun_disc,
                         atmo_plan *p, atmo_mie_optics *out, atmo_err *e)
{
    int rc = ATMO_OK;
    mie_table t[3];
    memset(t, 0, sizeof t);
    memset(out, 0, sizeof *out);
    mie_dsd d;
    atmo_err why;
    if (mie_dsd_parse(dsd, &d, &why))
        return atmo_fail(e, ATMO_ERR_USAGE, "%s = '%s': %s", key, dsd, why.msg);
    mie_table_options opt;
    memset(&opt, 0, sizeof opt);
    opt.sun_radius_deg = sun_disc ? s->sun.angular_radius_deg : 0.0;
    for (int i = 0; i < 3; i++) {
        double n, k, lambda = s->render.wavelengths_nm[i];
        if ((rc = mie_water_index(lambda, &n, &k, e)) ||
            (rc = mie_table_get(&d, lambda, n, k, &opt, p->cache_tables, &t[i], NULL, e)))
            goto cleanup;
        out->sigma_ext_per_lwc[i] = t[i].bulk.sigma_ext_per_lwc;
        out->albedo[i] = t[i].bulk.albedo;
        out->g[i] = t[i].bulk.g;
    }
    /* Jendersie-d'Eon's fit holds for 5-50 um */
    out->diameter_um = fmin(fmax(2.0 * t[1].bulk.r_eff_um, 5.0), 50.0);
    if ((rc = pack_tables(t, &out->rows, &out->count, e)))
        goto cleanup;
    if ((rc = atmo_plan_own(p, out->rows, e)))
        out->rows = NULL;
cleanup:
    for (int i = 0; i < 3; i++)
        mie_table_free(&t[i]);
    return rc;
}

int atmo_plan_cloud(const atmo_scene *s, atmo_plan *p, atmo_err *e)
{
    int rc = ATMO_OK;
    if (s->cloud.enabled && s->clouds.enabled)
        return atmo_fail(e, ATMO_ERR_USAGE,
                         "cloud.enabled (the homogeneous shell) and clouds.enabled (the fBm layer) "
                         "exclude each other; set one of them to false");
    int m = s->atmosphere.method;
    if (s->observer.enabled && m != ATMO_METHOD_SINGLE && m != ATMO_METHOD_MARCH)
        return atmo_fail(e, ATMO_ERR_USAGE,
                         "observer.enabled works with atmosphere.method=single or march only "
                         "(got %s); set one of those",
                         p->method);
    if (m != ATMO_METHOD_SINGLE && m != ATMO_METHOD_MARCH && m != ATMO_METHOD_REFERENCE)
        return atmo_fail(e, ATMO_ERR_USAGE,
                         "cloud.enabled works with atmosphere.method=single, march or reference "
                         "(got %s); set one of those",
                         p->method);
    if (s->cloud.enabled && s->cloud.top_m <= s->cloud.bottom_m)
        return atmo_fail(e, ATMO_ERR_USAGE,
                         "cloud.top_m (%g) must be above cloud.bottom_m (%g); raise the top",
                         s->cloud.top_m, s->cloud.bottom_m);
    atmo_gpu_cloud *g = &p->gpu.cloud;
    g->steps = ATMO_CLOUD_STEPS;
    g->phase = s->cloud.phase;
    if (s->observer.enabled)
        g->observer = observer_centre(s, &p->gpu);

    if (s->cloud.enabled) {
        atmo_mie_optics o;
        if ((rc = atmo_plan_mie_optics(s, "cloud.dsd",
                                        atmo_param_find("cloud.dsd")->names[s->cloud.dsd],
                                        s->cloud.sun_disc, p, &o, e)))
            return rc;
        int own_g = s->cloud.phase == ATMO_CLOUD_PHASE_HG && s->cloud.hg_g != 0.0;
        for (int i = 0; i < 3; i++) {
            (&g->extinction.x)[i] = (float)(o.sigma_ext_per_lwc[i] * s->cloud.lwc_g_m3);
            (&g->albedo.x)[i] = (float)o.albedo[i];
            (&g->g.x)[i] = (float)(own_g ? s->cloud.hg_g : o.g[i]);
        }
        g->diameter_um = (float)o.diameter_um;
        g->sun_guiding = (float)s->cloud.sun_guiding;
        g->base_m = (float)s->cloud.bottom_m;
        g->top_m = (float)s->cloud.top_m;
        float *cdf = NULL;
        if ((rc = atmo_plan_phase_cdf(o.rows, o.count, p, &cdf, e)) ||
            (rc = atmo_plan_add_buffer(p, "cloud_phase_table", "float4",
                                       sizeof(float4) * (size_t)o.count, 0, o.rows, e)))
            return rc;
        rc = atmo_plan_add_buffer(p, "cloud_phase_cdf", "float", sizeof(float) * (size_t)o.count,
                                  0, cdf, e);
        g->table_size = o.count;
    } else {
        /* observer only: an empty shell at the ground and a one-row zero table, so the
         * cloud's phase (weighted by its zero scattering) is 0, not a read before the table */
        static const float4 zero_row;
        static const float zero_cdf;
        g->base_m = g->top_m = 0.0f;
        g->table_size = 1;
        if ((rc = atmo_plan_add_buffer(p, "cloud_phase_table", "float4", sizeof zero_row, 0,
                                       &zero_row, e)))
            return rc;
        rc = atmo_plan_add_buffer(p, "cloud_phase_cdf", "float", sizeof zero_cdf, 0, &zero_cdf,
                                  e);
    }
    return rc;
}
