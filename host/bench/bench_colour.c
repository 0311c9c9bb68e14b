/* bench_colour.c — `atmo bench colour`: the colour difference between the 3-wavelength mode and
 * the spectral mode, and what the spectral mode costs.
 *
 * Sky: the sky-noon preset (camera at the ground), sun zenith 0, 30, 60, 80 and 88 deg, views at
 * zenith 0, 30, 60, 80 and 85 deg toward, across and away from the sun, through probe sessions
 * (atmo/probe.h; 64 samples per view, which averages the deterministic methods' random march
 * offset away) with the `fast` method (`march`, then `single`, where it is not built yet).
 * 3-wavelength colour: Bruneton's sky constants, linear sRGB = k_sky,c · L(680, 550, 440 nm)
 * (colour.h), the image of render.quantity=luminance. Spectral colour: XYZ = sum_i W_i L(lambda_i)
 * over 15, 30 and 48 bands (spectral_render.h), each triplet of bands one probe session.
 * Difference: CIE76 ΔE*ab = |Lab_3 - Lab_N| (CIE 1976 L*a*b*), with the reference white the
 * solar white point (the images are white-balanced to the sun) scaled to the luminance of the
 * zenith view in the 48-band spectrum, so the zenith sky has L* = 100 at every sun zenith
 * (brighter views, toward a low sun, exceed 100). CIE76 rather than CIEDE2000: the differences
 * are small, and CIE76 is the plain Euclidean distance that readers can recompute from the CSV.
 * Also the worst ΔE of 15 and 30 bands against 48 (the spectral mode's own convergence).
 * Time: seconds of precompute + probing per mode and sun zenith, kernels already built (the
 * spectral mode costs one 3-wavelength evaluation per triplet of bands).
 * Writes DIR/colour.csv and DIR/colour.svg (gnuplot: ΔE against sun zenith, one series per
 * band count, mean and worst over views; time per band count). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "atmo/clock.h"
#include "atmo/bench.h"
#include "atmo/colour.h"
#include "atmo/fileio.h"
#include "atmo/probe.h"
#include "atmo/spectral_render.h"

#define COLOUR_VIEWS 15
#define COLOUR_SUNS 5
#define COLOUR_COUNTS 3

static const double colour_suns_deg[COLOUR_SUNS] = {0, 30, 60, 80, 88};
static const int colour_bands[COLOUR_COUNTS] = {15, 30, 48};

typedef struct colour_row {
    double sun_zenith;
    int bands;
    double mean_de, max_de;
    double max_de_48;          /* worst over views against the 48-band spectrum: convergence */
    double seconds_3, seconds_n;
} colour_row;

/* Radiance at three wavelengths for the views, with the method and the sun of the scene. */
static int run_probe(const atmo_scene *base, const double wl[3], const float4 *rays, int n,
                   const char *device, double (*L)[3], double *seconds, char *device_name,
                   atmo_err *e)
{
    atmo_scene s = *base;
    for (int c = 0; c < 3; c++)
        s.render.wavelengths_nm[c] = wl[c];
    atmo_plan plan;
    atmo_probe probe = {0};
    int rc = atmo_plan_make(&s, &plan, e);
    if (!rc)
        rc = atmo_probe_open(&probe, &plan, device, e);
    double t0 = atmo_now_seconds();
    if (!rc)
        rc = atmo_probe_rays(&probe, rays, n, 64, L, NULL, e);
    *seconds += probe.seconds_precompute + (atmo_now_seconds() - t0);
    if (!rc)
        snprintf(device_name, 256, "%s", atmo_session_get_info(probe.session)->device_name);
    atmo_probe_close(&probe);
    return rc;
}

static double lab_f(double t)
{
    const double d = 6.0 / 29.0;
    return t > d * d * d ? cbrt(t) : t / (3.0 * d * d) + 4.0 / 29.0;
}

static void xyz_to_lab(const double xyz[3], const double white[3], double lab[3])
{
    double fx = lab_f(xyz[0] / white[0]), fy = lab_f(xyz[1] / white[1]);
    double fz = lab_f(xyz[2] / white[2]);
    lab[0] = 116.0 * fy - 16.0;
    lab[1] = 500.0 * (fx - fy);
    lab[2] = 200.0 * (fy - fz);
}

static double delta_e(const double xyz_a[3], const double xyz_b[3], const double white[3])
{
    double a[3], b[3];
    xyz_to_lab(xyz_a, white, a);
    xyz_to_lab(xyz_b, white, b);
    return sqrt((a[0] - b[0]) * (a[0] - b[0]) + (a[1] - b[1]) * (a[1] - b[1]) +
                (a[2] - b[2]) * (a[2] - b[2]));
}

static const char *pick_method(atmo_err *e)
{
    static const char *const methods[] = {"fast", "march", "single"};
    for (int i = 0; i < 3; i++) {
        atmo_scene s;
        atmo_plan plan;
        char buf[64];
        atmo_scene_defaults(&s);
        snprintf(buf, sizeof buf, "atmosphere.method=%s", methods[i]);
        if (atmo_scene_assign(&s, buf, "bench", e) == ATMO_OK && atmo_plan_make(&s, &plan, e) == ATMO_OK)
            return methods[i];
        fprintf(stderr, "bench colour: method %s unavailable (%s)\n", methods[i], e->msg);
    }
    return NULL;
}

static int write_outputs(const char *dir, const char *method, const colour_row *rows, int n,
                           const char *device_name, atmo_err *e)
{
    char csv[4096], svg[4096], tmp[ATMO_TMP_PATH_MAX];
    snprintf(csv, sizeof csv, "%s/colour.csv", dir);
    snprintf(svg, sizeof svg, "%s/colour.svg", dir);
    FILE *f = atmo_atomic_open(csv, tmp, e);
    if (!f)
        return ATMO_ERR_RUNTIME;
    fprintf(f, "# CIE76 delta E*ab between the 3-wavelength luminance mode and the spectral mode, "
               "white = solar white at the zenith luminance of 48 bands; seconds = precompute + "
               "probe\nmethod,sun_zenith_deg,bands,mean_delta_e,max_delta_e,seconds_3_wavelengths,"
               "seconds_spectral,max_delta_e_vs_48_bands,device\n");
    for (int i = 0; i < n; i++)
        fprintf(f, "%s,%g,%d,%.4f,%.4f,%.4f,%.4f,%.4f,\"%s\"\n", method, rows[i].sun_zenith,
                rows[i].bands, rows[i].mean_de, rows[i].max_de, rows[i].seconds_3,
                rows[i].seconds_n, rows[i].max_de_48, device_name);
    int rc = atmo_atomic_commit(f, tmp, csv, e);
    if (rc)
        return rc;
    char *script = NULL;
    size_t size = 0;
    if (!(f = open_memstream(&script, &size)))
        return atmo_fail(e, ATMO_ERR_RUNTIME, "out of memory for the chart script of %s", svg);
    fprintf(f, "set datafile separator ','\nset grid\nset key top left\n"
               "set multiplot layout 1,2 title 'spectral vs 3-wavelength colour, method %s (%s)'\n"
               "set xlabel 'sun zenith (deg)'\nset ylabel 'CIE76 Delta E*ab'\n"
               "set title 'colour difference over 15 views'\nplot ",
            method, device_name);
    for (int b = 0; b < COLOUR_COUNTS; b++)
        fprintf(f, "%s'%s' using ($3 == %d ? $2 : 1/0):4 with linespoints lt %d title '%d bands, mean', "
                   "'' using ($3 == %d ? $2 : 1/0):5 with linespoints lt %d dt 2 title '%d bands, worst'",
                b ? ", " : "", csv, colour_bands[b], b + 1, colour_bands[b], colour_bands[b], b + 1,
                colour_bands[b]);
    fprintf(f, "\nset xlabel 'bands (3 = the 3-wavelength mode)'\nset ylabel 'seconds'\n"
               "set title 'precompute + probe time per sun zenith'\nset xrange [0:52]\n"
               "plot '%s' using 3:7 with points pt 7 title 'spectral', '' using (3):6 with points "
               "pt 5 title '3 wavelengths'\nunset multiplot\n",
            csv);
    rc = bench_plot_close(f, &script, svg, 1000, 450, e);
    if (rc)
        return rc;
    printf("wrote %s and %s\n", csv, svg);
    return ATMO_OK;
}

/* The scene of sun zenith colour_suns_deg[is] (sky-noon, the method, radiance) and its
 * COLOUR_VIEWS probe rays (view zeniths 0, 30, 60, 80, 85 deg by azimuths 0, 90, 180 deg from
 * the sun) as (r, mu, mu_s, nu). */
static int sun_scene(const char *method, int is, atmo_scene *s, float4 rays[COLOUR_VIEWS],
                     atmo_err *e)
{
    static const double view_zenith[] = {0, 30, 60, 80, 85}, view_azimuth[] = {0, 90, 180};
    char buf[64];
    int rc;
    atmo_scene_defaults(s);
    if ((rc = atmo_scene_apply_preset(s, "sky-noon", e)))
        return rc;
    snprintf(buf, sizeof buf, "atmosphere.method=%s", method);
    if ((rc = atmo_scene_assign(s, buf, "bench", e)))
        return rc;
    snprintf(buf, sizeof buf, "sun.zenith_deg=%g", colour_suns_deg[is]);
    if ((rc = atmo_scene_assign(s, buf, "bench", e)))
        return rc;
    s->render.quantity = ATMO_QUANTITY_RADIANCE;
    atmo_plan plan;
    if ((rc = atmo_plan_make(s, &plan, e)))
        return rc;
    double r = plan.gpu.camera.local_up.w, ts = colour_suns_deg[is] * M_PI / 180;
    atmo_plan_free(&plan);
    for (int i = 0; i < COLOUR_VIEWS; i++) {
        double tv = view_zenith[i / 3] * M_PI / 180, pv = view_azimuth[i % 3] * M_PI / 180;
        float4 q = {(float)r, (float)cos(tv), (float)cos(ts),
                    (float)(sin(tv) * sin(ts) * cos(pv) + cos(tv) * cos(ts))};
        rays[i] = q;
    }
    return ATMO_OK;
}

/* The views' XYZ in the 3-wavelength mode (Bruneton's sky constants), the probe's seconds
 * added to *seconds. */
static int probe_three(atmo_scene *s, const float4 *rays, const char *device,
                       double xyz[COLOUR_VIEWS][3], double *seconds, char *device_name,
                       atmo_err *e)
{
    double L[COLOUR_VIEWS][3], k[3];
    int rc = run_probe(s, s->render.wavelengths_nm, rays, COLOUR_VIEWS, device, L, seconds,
                       device_name, e);
    if (rc)
        return rc;
    atmo_luminance_factors(s->render.wavelengths_nm, -3.0, k);
    for (int i = 0; i < COLOUR_VIEWS; i++) {
        double rgb[3] = {k[0] * L[i][0], k[1] * L[i][1], k[2] * L[i][2]};
        atmo_linear_srgb_to_xyz(rgb, xyz[i]);
    }
    return ATMO_OK;
}

/* The views' XYZ from n spectral bands, probed three at a time, the seconds added. */
static int probe_bands(atmo_scene *s, int n, const float4 *rays, const char *device,
                       double xyz[COLOUR_VIEWS][3], double *seconds, char *device_name,
                       atmo_err *e)
{
    static double band_L[ATMO_SPECTRAL_MAX_BANDS + 2][COLOUR_VIEWS]; /* + padding */
    double centres[ATMO_SPECTRAL_MAX_BANDS], w[ATMO_SPECTRAL_MAX_BANDS][3];
    atmo_spectral_bands(n, centres);
    atmo_spectral_xyz_weights(n, centres, w);
    for (int t = 0; t < (n + 2) / 3; t++) {
        double wl[3], L[COLOUR_VIEWS][3];
        for (int c = 0; c < 3; c++)
            wl[c] = centres[3 * t + c < n ? 3 * t + c : n - 1];
        int rc = run_probe(s, wl, rays, COLOUR_VIEWS, device, L, seconds, device_name, e);
        if (rc)
            return rc;
        for (int i = 0; i < COLOUR_VIEWS; i++)
            for (int c = 0; c < 3; c++)
                band_L[3 * t + c][i] = L[i][c];
    }
    for (int i = 0; i < COLOUR_VIEWS; i++) {
        xyz[i][0] = xyz[i][1] = xyz[i][2] = 0.0;
        for (int b = 0; b < n; b++)
            for (int c = 0; c < 3; c++)
                xyz[i][c] += w[b][c] * band_L[b][i];
    }
    return ATMO_OK;
}

/* A row's colour differences: each view's 3-wavelength XYZ and the 48-band XYZ against this
 * band count's, white the solar white at the zenith's 48-band luminance. */
static void colour_differences(colour_row *row, double xyz3[COLOUR_VIEWS][3],
                               double xyz48[COLOUR_VIEWS][3], double xyz[COLOUR_VIEWS][3],
                               const double white[3])
{
    row->mean_de = row->max_de = row->max_de_48 = 0.0;
    for (int i = 0; i < COLOUR_VIEWS; i++) {
        double de = delta_e(xyz3[i], xyz[i], white);
        row->mean_de += de / COLOUR_VIEWS;
        row->max_de = fmax(row->max_de, de);
        row->max_de_48 = fmax(row->max_de_48, delta_e(xyz48[i], xyz[i], white));
    }
}

int bench_colour(const char *dir, const char *device, int quick, atmo_err *e)
{
    const char *method = pick_method(e);
    if (!method)
        return atmo_fail(e, ATMO_ERR_RUNTIME, "no atmosphere method available for bench colour");
    colour_row rows[COLOUR_SUNS * COLOUR_COUNTS];
    char device_name[256] = "?";
    int n_rows = 0, rc;
    for (int is = 0; is < COLOUR_SUNS; is++) {
        if (quick && is % 2)
            continue;
        atmo_scene s;
        float4 rays[COLOUR_VIEWS];
        double xyz3[COLOUR_VIEWS][3], seconds_3 = 0.0;
        if ((rc = sun_scene(method, is, &s, rays, e)) ||
            (rc = probe_three(&s, rays, device, xyz3, &seconds_3, device_name, e)))
            return rc;
        /* spectral, largest band count first: its zenith view sets the white */
        double white[3] = {0, 0, 0}, xyz48[COLOUR_VIEWS][3];
        for (int ib = COLOUR_COUNTS - 1; ib >= 0; ib--) {
            int n = colour_bands[ib];
            double seconds_n = 0.0, xyz[COLOUR_VIEWS][3];
            if ((rc = probe_bands(&s, n, rays, device, xyz, &seconds_n, device_name, e)))
                return rc;
            if (ib == COLOUR_COUNTS - 1) {
                double wp[3], wxyz[3];
                atmo_solar_white_point(wp);
                atmo_linear_srgb_to_xyz(wp, wxyz);
                for (int c = 0; c < 3; c++)
                    white[c] = wxyz[c] * xyz[0][1] / wxyz[1]; /* view 0 is the zenith */
                memcpy(xyz48, xyz, sizeof xyz48);
            }
            colour_row *row = &rows[n_rows++];
            row->sun_zenith = colour_suns_deg[is];
            row->bands = n;
            colour_differences(row, xyz3, xyz48, xyz, white);
            row->seconds_3 = seconds_3;
            row->seconds_n = seconds_n;
            fprintf(stderr, "bench colour: %s sun zenith %2g deg, %2d bands: delta E mean %.3f, "
                            "worst %.3f (against 48 bands %.3f); %.2fs (3 wavelengths %.2fs)\n",
                    method, row->sun_zenith, n, row->mean_de, row->max_de, row->max_de_48,
                    seconds_n, seconds_3);
        }
    }
    return write_outputs(dir, method, rows, n_rows, device_name, e);
}
