/* test_path_air — the air as a volume medium of the path tracer (path.air = medium:
 * kernels/media/media_walk.h's free flight with the air, kernels/render/volume_stage.h,
 * kernels/render/path.h).
 * labels: render kernel stat slow
 *
 * 1. Clear sky against the Monte Carlo table (oracle: tests/data/reference_sky.csv, method
 *    `reference`, all orders of scattering with the ground's reflections, camera at the ground,
 *    the sun's disc excluded; relative standard errors <= 0.3 %). The sky-noon preset in path
 *    mode with path.air = medium, the camera at the ground (0, 0, 0), the planet's ground sphere
 *    of the atmosphere's ground albedo, no terrain, clouds or objects; for each sun zenith of
 *    SUNS and each view of the table more than 10 degrees from the sun (the sun's disc and the
 *    aureole's steep gradient stay out of the 1-degree frame), a 4 x 4 image of field of view
 *    1 degree aimed at the view (pitch 90 - view zenith, yaw minus the view's azimuth from the
 *    sun, the sun at azimuth 0), independent samples (path.sampler = random); every other view
 *    with path.air_collisions = 8 (the floor on the walk's collisions), the others with the
 *    default 0, so both ways of placing the sun's estimates (render/path.h's path_flight) face
 *    the table. The frame's mean
 *    estimates the view's radiance (the sky's curvature over half a degree changes it by < 1e-4
 *    of itself); its standard error is the pixels' (independent) combined,
 *    sqrt(sum se_i^2) / 16. Per view and channel z = (L - L_ref) / sqrt(se^2 + se_ref^2) must
 *    satisfy |z| < 4.4 (two-sided p ~ 1e-5 each; ~100 tests, family-wise p ~ 1e-3); the RMS of
 *    the z values must lie within 1 +- 0.5 (a z spread far below 1 would mean the standard
 *    errors are overstated, and the per-view test could not fail); and per channel the mean of
 *    the views' z, whose standard deviation is 1 / sqrt(views) (each view has a seed of its
 *    own, so their errors are independent), must lie within 4.4 / sqrt(views): a bias common
 *    to the views (~0.4 % of the radiance at 4096 samples a pixel) fails it where no single
 *    view would. The estimator's noise (relative standard deviation of one sample, the median
 *    over the views) is printed.
 * 2. Determinism (oracle: the renderer's contract). One view rendered with tiles of 16 and one
 *    launch per sample and with tiles of 3 and no batch bound is bitwise the same.
 * 3. Bad input (oracle: the scene's contract): path.air = medium with path.sky = uniform (a
 *    world without air) fails to plan with a usage error. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "testlib.h"
#include "testscene.h"

#define MAX_ROWS 128
#define N_SUNS 3
#define FRAME 4 /* pixels a side */

static const double suns[N_SUNS] = {30, 60, 80};

static void set(atmo_scene *s, const char *fmt, double v)
{
    char buf[128];
    snprintf(buf, sizeof buf, fmt, v);
    test_scene_set(s, buf);
}

/* The angle (degrees) between the view and the sun of a row. */
static double sun_angle(const test_sky_row *r)
{
    double ts = r->sun_zenith * M_PI / 180, tv = r->view_zenith * M_PI / 180;
    double c = sin(tv) * sin(ts) * cos(r->view_azimuth * M_PI / 180) + cos(tv) * cos(ts);
    return acos(fmin(fmax(c, -1.0), 1.0)) * 180 / M_PI;
}

/* The clear-sky scene aimed at row r's view, `samples` per pixel, with its own seed. */
static void view_scene(atmo_scene *s, const test_sky_row *r, int samples, int seed)
{
    test_scene_preset(s, "sky-noon");
    test_scene_set(s, "render.mode=path");
    test_scene_set(s, "path.air=medium");
    test_scene_set(s, "path.sampler=random");
    test_scene_set(s, "camera.position_m=0,0,0");
    test_scene_set(s, "camera.fov_deg=1");
    test_scene_set(s, "sun.azimuth_deg=0");
    set(s, "sun.zenith_deg=%g", r->sun_zenith);
    set(s, "camera.pitch_deg=%g", 90.0 - r->view_zenith);
    set(s, "camera.yaw_deg=%g", -r->view_azimuth);
    test_scene_image(s, FRAME, FRAME, samples, seed);
}

static void test_against_table(const test_sky_row *rows, int n)
{
    double z2 = 0.0, z_sum[3] = {0, 0, 0}, noise[MAX_ROWS] = {0};
    int tests = 0, views = 0;
    printf("sun  view      L/L_ref - 1 (%%) at 680/550/440 nm          z\n");
    for (int i = 0; i < n; i++) {
        const test_sky_row *r = &rows[i];
        int wanted = 0;
        for (int k = 0; k < N_SUNS; k++)
            wanted |= r->sun_zenith == suns[k];
        if (!wanted || sun_angle(r) <= 10.0)
            continue;
        atmo_scene s;
        view_scene(&s, r, 4096, 100 + i);
        if (views % 2)
            test_scene_set(&s, "path.air_collisions=8");
        test_image im = test_render(&s, 0, 0);
        double L[3] = {0, 0, 0}, var[3] = {0, 0, 0}, z[3], err[3];
        for (int p = 0; p < FRAME * FRAME; p++)
            for (int c = 0; c < 3; c++) {
                L[c] += im.mean[3 * p + c] / (FRAME * FRAME);
                var[c] += (double)im.se[3 * p + c] * im.se[3 * p + c] / (FRAME * FRAME) /
                          (FRAME * FRAME);
            }
        for (int c = 0; c < 3; c++) {
            z[c] = (L[c] - r->L[c]) / sqrt(var[c] + r->se[c] * r->se[c]);
            err[c] = L[c] / r->L[c] - 1.0;
            if (!(fabs(z[c]) < 4.4))
                fprintf(stderr, "sun %g view %g,%g channel %d: %.6g against %.6g (z = %.2f)\n",
                        r->sun_zenith, r->view_zenith, r->view_azimuth, c, L[c], r->L[c], z[c]);
            CHECK(fabs(z[c]) < 4.4);
            z2 += z[c] * z[c];
            z_sum[c] += z[c];
            tests++;
        }
        /* the green channel's relative standard deviation of one sample */
        noise[views++] = sqrt(var[1] * FRAME * FRAME * im.n) / L[1];
        printf("%3g %3g,%3g  %+6.2f %+6.2f %+6.2f   %+5.2f %+5.2f %+5.2f\n", r->sun_zenith,
               r->view_zenith, r->view_azimuth, 100 * err[0], 100 * err[1], 100 * err[2], z[0],
               z[1], z[2]);
        test_image_free(&im);
    }
    double rms = sqrt(z2 / tests);
    for (int i = 1; i < views; i++) /* insertion sort for the median */
        for (int j = i; j > 0 && noise[j] < noise[j - 1]; j--) {
            double t = noise[j];
            noise[j] = noise[j - 1], noise[j - 1] = t;
        }
    printf("%d views, %d tests: RMS z %.2f; relative standard deviation of one sample (550 nm, "
           "median over the views) %.2f\n",
           views, tests, rms, noise[views / 2]);
    CHECK(views >= 3 * N_SUNS);
    CHECK(rms > 0.5 && rms < 1.5);
    for (int c = 0; c < 3; c++) {
        double mean_z = z_sum[c] / views;
        printf("channel %d: mean z %+.2f (bound %.2f)\n", c, mean_z, 4.4 / sqrt(views));
        CHECK(fabs(mean_z) < 4.4 / sqrt(views));
    }
}

static void test_determinism(const test_sky_row *r)
{
    atmo_scene s;
    view_scene(&s, r, 8, 7);
    test_image a = test_render(&s, 16, 1), b = test_render(&s, 3, 0);
    CHECK(memcmp(a.mean, b.mean, sizeof(float) * 3 * FRAME * FRAME) == 0);
    test_image_free(&a);
    test_image_free(&b);
}

static void test_bad_input(void)
{
    atmo_scene s;
    atmo_plan p;
    atmo_err e;
    test_scene_preset(&s, "sky-noon");
    test_scene_set(&s, "render.mode=path");
    test_scene_set(&s, "path.air=medium");
    test_scene_set(&s, "path.sky=uniform");
    int rc = atmo_plan_make(&s, &p, &e);
    CHECK(rc == ATMO_ERR_USAGE && strstr(e.msg, "path.air=medium"));
    if (rc == ATMO_OK)
        atmo_plan_free(&p);
}

int main(void)
{
    atmo_cl cl;
    test_cl_open(&cl); /* exits 77 without OpenCL */
    atmo_cl_close(&cl);
    static test_sky_row rows[MAX_ROWS];
    int n = test_reference_sky(rows, MAX_ROWS);
    CHECK(n == 65);
    test_bad_input();
    test_determinism(&rows[20]);
    test_against_table(rows, n);
    return test_finish();
}
