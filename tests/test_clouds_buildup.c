/* test_clouds_buildup — the cloud marcher's multiple-scattering terms with the build-up
 * (kernels/clouds/cloud_march.h, "Build-up"; host build of the shared headers) converge to the
 * integral they stand for as the steps shrink, the build-up's one-pass sum included.
 * labels: unit
 * composes: atmosphere clouds clouds_majorant clouds_tracked clouds_medium visibility clouds_march medium reference
 *
 * Oracle: a double-precision host quadrature (midpoint rule, 2 m along the view ray, 10 m toward
 * the sun; the field's finest octave has 200 m features) of
 *     L = int T(0, t) sigma_s(t) E [p_0 T_0 + B(t) (b p_1 (T_1 - T_0) + d R e^{-k_d tau_sun} / (4 pi))] dt
 * over tests/support_clouds.c's overcast deck (the atmosphere off, Henyey-Greenstein g 0.85,
 * albedo 0.9512, E = 1), with two octaves (a 0.2, b 0.99, c 0.7) and the diffuse orders (d 6.81):
 * T_0 = e^{-tau_sun}, T_1 the octave's transmittance with the deep decay, p_1 Henyey-Greenstein
 * at g c, and
 *     B(t) = [(1 - e^{-tau_front(t)}) + (1 - e^{-tau_back(t)}) + (1 - e^{-tau_sun(t)})] / 3
 * with tau_front the view ray's optical depth from the camera to t and tau_back from t to the
 * layer's top, both summed by the quadrature itself (two passes), where the marcher learns
 * tau_back only at its end and takes it as a second sum. The octave's transmittance, the
 * diffusion exponent k_d and the similarity albedo R are the kernel's own functions of tau_sun:
 * the model is what the marcher defines; the test checks that it integrates it.
 * The marcher (method single's use_ms = 0: no sky; 16 stratified jitters) at (step, light
 * steps) = (400 m, 4), (200 m, 8), (100 m, 16), (50 m, 32): its error must fall at every
 * refinement and end below 1 %, as single scattering's does on the same ray
 * (test_clouds_march: 0.04 % at the finest). The same quadrature without the build-up (B = 1,
 * T_1 in place of T_1 - T_0) must lie more than 10 % from the marcher's finest, so the test
 * tells the two apart. The numbers are printed. */
#include <math.h>
#include <stdio.h>
#include "kernels_composed.h"
#include "atmo/scene.h"
#include "testclouds.h"
#include "testclouds_oracle.h"
#include "testlib.h"

#define LUTS                                                                                       \
    lut, lut, lut, lut, lut, lut, NULL, NULL, NULL, lut, lut, cdf, grid, NULL, NULL, NULL, NULL
#define OCTAVE_A 0.2f
#define OCTAVE_B 0.99f
#define OCTAVE_C 0.7f
#define DIFFUSE_D 6.81f

static double henyey_greenstein(double g, double nu)
{
    return (1.0 - g * g) / (4.0 * M_PI * pow(1.0 + g * g - 2.0 * g * nu, 1.5));
}

int main(void)
{
    static float4 lut[16]; /* optical depth 0 everywhere: the atmosphere is off */
    float cdf[2] = {0.0f, 1.0f};
    static float grid[CLOUDS_GRID_NX * CLOUDS_GRID_NY * CLOUDS_GRID_NZ];
    atmo_gpu_scene s;
    test_overcast_scene(&s);
    atmo_gpu_clouds *c = &s.clouds;
    test_clouds_fill_grid(&s, grid);
    c->ms_octaves = 2, c->ms_a = OCTAVE_A, c->ms_b = OCTAVE_B, c->ms_c = OCTAVE_C;
    c->ms_d = DIFFUSE_D;

    /* the view of test_clouds_march: 60 degrees up, 100 degrees of azimuth away from the sun */
    double el = 60.0 * M_PI / 180.0, az = 100.0 * M_PI / 180.0;
    vec3 dir = v3((float)(cos(el) * cos(az)), (float)sin(el), (float)(cos(el) * sin(az)));
    medium_ray m = medium_ray_from_camera(&s, dir);
    float lo[2], hi[2];
    int parts = geometry_shell_parts(s.atmosphere.bottom_radius, c->bottom_m, c->top_m, m.r, m.mu,
                                   0.0f, 1e7f, lo, hi);
    CHECK(parts == 1);

    /* the oracle: the first pass sums the view's optical depth, the second integrates */
    const double dt = 2.0, w = c->albedo.y, nu = m.nu;
    double tau_total = 0.0;
    for (double t = lo[0] + 0.5 * dt; t < hi[0]; t += dt)
        tau_total += test_clouds_sigma(&s, &m, t) * dt;
    float k_d = clouds_diffusion_exponent(c).y, R = clouds_similarity_albedo(c).y;
    double p0 = henyey_greenstein(c->g.y, nu), p1 = henyey_greenstein(c->g.y * OCTAVE_C, nu);
    double L = 0.0, L_plain = 0.0, tau_front = 0.0;
    for (double t = lo[0] + 0.5 * dt; t < hi[0]; t += dt) {
        double sig = test_clouds_sigma(&s, &m, t);
        /* the view's optical depth to the step's midpoint, and behind it to the layer's top */
        double front = tau_front + 0.5 * sig * dt, back = tau_total - front;
        if (sig > 0.0) {
            double tau_sun = test_clouds_sun_depth(&s, &m, t), t0 = exp(-tau_sun);
            double t1 = clouds_octave_channel((float)tau_sun, OCTAVE_A, k_d);
            double diffuse = DIFFUSE_D * R * exp(-k_d * tau_sun) / (4.0 * M_PI);
            double B = ((1.0 - exp(-front)) + (1.0 - exp(-back)) + (1.0 - t0)) / 3.0;
            double weight = exp(-front) * sig * w * dt;
            L += weight * (p0 * t0 + B * (OCTAVE_B * p1 * fmax(t1 - t0, 0.0) + diffuse));
            L_plain += weight * (p0 * t0 + OCTAVE_B * p1 * t1 + diffuse);
        }
        tau_front += sig * dt;
    }
    printf("oracle: view optical depth %.3f; with the build-up %.6e, without it %.6e\n",
           tau_total, L, L_plain);
    CHECK(tau_total > 0.5 && tau_total < 9.0); /* a cloud the march crosses (T_MIN e^-9.2) */

    const float steps_m[] = {400.0f, 200.0f, 100.0f, 50.0f};
    const int light[] = {4, 8, 16, 32};
    double previous = INFINITY, finest = 0.0;
    for (int k = 0; k < 4; k++) {
        c->step_m = steps_m[k];
        c->light_steps = light[k];
        double sum = test_clouds_marcher_mean(&s, LUTS, &m, 16);
        double err = fabs(sum / L - 1.0);
        printf("marcher step %.0f m, %d light steps: %.6e, error %.3f %%\n", steps_m[k],
               light[k], sum, 100.0 * err);
        CHECK(err < previous);
        previous = err, finest = sum;
    }
    CHECK(previous < 0.01);
    printf("the quadrature without the build-up is %+.1f %% from the marcher\n",
           100.0 * (L_plain / finest - 1.0));
    CHECK(fabs(L_plain / finest - 1.0) > 0.10);
    return test_finish();
}
