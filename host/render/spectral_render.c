/* spectral_render.c — the spectral mode (atmo/spectral_render.h): band centres, the CMF
 * quadrature weights, XYZ <-> linear sRGB, and the render of a scene as triplets of bands.
 *
 * CMFs as in colour.c (Bruneton 2017's recipe): the CIE 1931 2° table linear between its 5 nm
 * nodes, zero at and beyond 360 and 830 nm, summed at 1 nm from 360 to 829 nm. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "atmo/colour.h"
#include "atmo/plan.h"
#include "atmo/spectral.h"
#include "atmo/spectral_render.h"

/* IEC 61966-2-1, the matrix colour.c uses (the tests check that the two agree). */
static const double spectral_xyz_to_srgb[3][3] = {
    {3.2406, -1.5372, -0.4986},
    {-0.9689, 1.8758, 0.0415},
    {0.0557, -0.2040, 1.0570},
};

void atmo_spectral_bands(int n, double *centres_nm)
{
    double h = (ATMO_SPECTRAL_LAMBDA_MAX_NM - ATMO_SPECTRAL_LAMBDA_MIN_NM) / n;
    for (int i = 0; i < n; i++)
        centres_nm[i] = ATMO_SPECTRAL_LAMBDA_MIN_NM + (i + 0.5) * h;
}

static void spectral_cmf(const spectral_table *cmf, double lambda_nm, double xyz[3])
{
    int inside = lambda_nm > ATMO_SPECTRAL_LAMBDA_MIN_NM && lambda_nm < ATMO_SPECTRAL_LAMBDA_MAX_NM;
    for (int k = 0; k < 3; k++)
        xyz[k] = inside ? spectral_table_lookup(cmf, k + 1, lambda_nm) : 0.0;
}

/* Cardinal weights phi[0..3] of the cubic through nodes c[m..m+3] at lambda (Lagrange). */
static void spectral_cubic(const double *c, int m, double lambda, double phi[4])
{
    for (int a = 0; a < 4; a++) {
        phi[a] = 1.0;
        for (int b = 0; b < 4; b++)
            if (b != a)
                phi[a] *= (lambda - c[m + b]) / (c[m + a] - c[m + b]);
    }
}

void atmo_spectral_xyz_weights(int n, const double *c, double (*w)[3])
{
    const spectral_table *cmf = spectral_table_get("data/cie1931_2deg_cmf.csv");
    for (int i = 0; i < n; i++)
        w[i][0] = w[i][1] = w[i][2] = 0.0;
    int j = 0; /* interval [c_j, c_j+1] holding lambda */
    for (int lambda = (int)ATMO_SPECTRAL_LAMBDA_MIN_NM; lambda < (int)ATMO_SPECTRAL_LAMBDA_MAX_NM;
         lambda++) {
        double xyz[3], s = spectral_solar_irradiance(lambda);
        spectral_cmf(cmf, lambda, xyz);
        while (j < n - 2 && lambda >= c[j + 1])
            j++;
        double phi[4] = {1.0, 0.0, 0.0, 0.0};
        int m;
        if (lambda <= c[0] || lambda >= c[n - 1]) {
            /* constant beyond the end centres (where the CMFs are below 1e-3 of their peak) */
            m = lambda <= c[0] ? 0 : n - 1;
        } else if (n < 4) {
            m = j; /* linear: too few nodes for a cubic */
            phi[1] = (lambda - c[j]) / (c[j + 1] - c[j]);
            phi[0] = 1.0 - phi[1];
        } else {
            /* the cubic through the two centres around lambda and one more on each side,
             * shifted inward at the ends */
            m = j - 1 < 0 ? 0 : j - 1 > n - 4 ? n - 4 : j - 1;
            spectral_cubic(c, m, lambda, phi);
        }
        for (int a = 0; a < 4 && m + a < n; a++) {
            double f = phi[a] * s / spectral_solar_irradiance(c[m + a]);
            for (int k = 0; k < 3; k++)
                w[m + a][k] += f * xyz[k];
        }
    }
    for (int i = 0; i < n; i++)
        for (int k = 0; k < 3; k++)
            w[i][k] *= ATMO_MAX_LUMINOUS_EFFICACY;
}

void atmo_xyz_to_linear_srgb(const double xyz[3], double rgb[3])
{
    for (int c = 0; c < 3; c++)
        rgb[c] = spectral_xyz_to_srgb[c][0] * xyz[0] + spectral_xyz_to_srgb[c][1] * xyz[1] +
                 spectral_xyz_to_srgb[c][2] * xyz[2];
}

void atmo_linear_srgb_to_xyz(const double rgb[3], double xyz[3])
{
    /* the inverse by cofactors: inv = adj(M) / det(M) */
    const double(*m)[3] = spectral_xyz_to_srgb;
    double inv[3][3];
    for (int r = 0; r < 3; r++)
        for (int c = 0; c < 3; c++) {
            int r1 = (c + 1) % 3, r2 = (c + 2) % 3, c1 = (r + 1) % 3, c2 = (r + 2) % 3;
            inv[r][c] = m[r1][c1] * m[r2][c2] - m[r1][c2] * m[r2][c1];
        }
    double det = m[0][0] * inv[0][0] + m[0][1] * inv[1][0] + m[0][2] * inv[2][0];
    for (int r = 0; r < 3; r++)
        xyz[r] = (inv[r][0] * rgb[0] + inv[r][1] * rgb[1] + inv[r][2] * rgb[2]) / det;
}

int atmo_spectral_render(const atmo_scene *s, int cache_luts, const atmo_render_settings *rs,
                         atmo_render_result *result, atmo_err *e)
{
    int n = s->render.spectral_bands, rc;
    memset(result, 0, sizeof *result);
    if (n == 0)
        return atmo_fail(e, ATMO_ERR_USAGE, "spectral render without render.spectral_bands; set "
                                            "it to 15 or more");
    if ((rc = atmo_scene_check_spectral_bands(n, e)))
        return rc;
    double centres[ATMO_SPECTRAL_MAX_BANDS] = {0}, rgb_w[ATMO_SPECTRAL_MAX_BANDS][3];
    double(*xyz_w)[3] = rgb_w; /* converted in place below */
    atmo_spectral_bands(n, centres);
    atmo_spectral_xyz_weights(n, centres, xyz_w);
    for (int i = 0; i < n; i++) {
        double xyz[3] = {xyz_w[i][0], xyz_w[i][1], xyz_w[i][2]};
        atmo_xyz_to_linear_srgb(xyz, rgb_w[i]);
    }

    double *sum = NULL;
    float *band_rgb = NULL;
    size_t pixels = (size_t)s->image.width * (size_t)s->image.height;
    int triplets = (n + 2) / 3;
    atmo_session *session = NULL;
    int lut_cache_hits = 1;
    if (!(sum = calloc(pixels * 3, sizeof *sum)) ||
        !(band_rgb = malloc(pixels * 3 * sizeof *band_rgb))) {
        rc = atmo_fail(e, ATMO_ERR_RUNTIME, "out of memory for a %dx%d spectral image",
                       s->image.width, s->image.height);
        goto cleanup;
    }
    /* one session, one program: each triplet only changes the scene struct, the host tables
     * and the LUTs */
    for (int t = 0; t < triplets; t++) {
        atmo_scene st = *s;
        int band[3];
        for (int c = 0; c < 3; c++) {
            band[c] = 3 * t + c < n ? 3 * t + c : n - 1; /* pad with the last centre */
            st.render.wavelengths_nm[c] = centres[band[c]];
        }
        st.render.quantity = ATMO_QUANTITY_RADIANCE;
        st.render.spectral_bands = 0;
        atmo_plan plan;
        if ((rc = atmo_plan_make_cached(&st, cache_luts, cache_luts, &plan, e)))
            goto cleanup;
        double seconds_before = 0.0;
        if (session) {
            const atmo_session_info *in = atmo_session_get_info(session);
            seconds_before = in->seconds_precompute + in->seconds_render;
            rc = atmo_session_set_scene(session, &plan, e);
        } else {
            rc = atmo_session_open(&session, &plan, rs, e);
        }
        atmo_step step = {plan.samples, 0.0, NULL, NULL, rs->cancel};
        atmo_step_status status;
        if (!rc) /* the precompute has copied the plan's host tables to the device */
            rc = atmo_session_step(session, &step, &status, e);
        atmo_plan_free(&plan);
        if (rc)
            goto cleanup;
        if (!status.complete) {
            rc = atmo_fail(e, ATMO_INTERRUPTED_EMPTY,
                           "interrupted in spectral triplet %d of %d; a partial set of bands has "
                           "no meaningful colour, so no image is written",
                           t + 1, triplets);
            goto cleanup;
        }
        if ((rc = atmo_session_read(session, band_rgb, NULL, NULL, e)))
            goto cleanup;
        for (int c = 0; c < 3; c++) {
            if (3 * t + c >= n)
                continue; /* padding */
            const double *w = rgb_w[band[c]];
            for (size_t p = 0; p < pixels; p++) {
                double L = band_rgb[3 * p + (size_t)c];
                for (int k = 0; k < 3; k++)
                    sum[3 * p + (size_t)k] += w[k] * L;
            }
        }
        unsigned nonfinite = result->nonfinite + atmo_session_get_info(session)->nonfinite;
        lut_cache_hits &= atmo_session_get_info(session)->lut_cache_hit;
        atmo_render_result_from_session(session, result);
        result->nonfinite = nonfinite;
        result->lut_cache_hit = lut_cache_hits;
        if (rs->progress) {
            const atmo_session_info *in = atmo_session_get_info(session);
            fprintf(stderr, "spectral: triplet %d/%d (%.1f, %.1f, %.1f nm) rendered in %.2fs\n",
                    t + 1, triplets, st.render.wavelengths_nm[0], st.render.wavelengths_nm[1],
                    st.render.wavelengths_nm[2],
                    in->seconds_precompute + in->seconds_render - seconds_before);
        }
    }
    if (!(result->rgb = malloc(pixels * 3 * sizeof *result->rgb))) {
        rc = atmo_fail(e, ATMO_ERR_RUNTIME, "out of memory for a %dx%d spectral image",
                       s->image.width, s->image.height);
        goto cleanup;
    }
    for (size_t i = 0; i < pixels * 3; i++)
        result->rgb[i] = (float)sum[i];
    rc = ATMO_OK;
cleanup:
    atmo_session_close(session);
    free(band_rgb);
    free(sum);
    return rc;
}
