/* test_cloud_shell_thin — a cloud shell of negligible optical depth changes the sky by about its
 * optical depth, for every method (kernels/cloud_shell/cloud_shell.h in the medium integrator and the
 * Monte Carlo reference), and a shell that no ray meets changes nothing.
 * labels: kernel
 * composes: atmosphere cloud visibility cloud_march medium
 *
 * Oracle: the closed-form bound on what a medium of optical depth tau can do to the light.
 * The sky (default atmosphere, sun zenith 50 deg, camera on the ground, views at zenith 0, 60
 * and 85 deg) is probed with and without the shell 1000-2000 m of cumulus at cloud.lwc_g_m3
 * 1e-6 (tau = 1.6e-4 at 550 nm, the plan's extinction times 1000 m), phase HG g = 0.5.
 *  - Loss: every light path of single scattering (and the march's multiple-scattering source,
 *    attenuated by the shell along the sun's chord) crosses the shell along at most the view
 *    ray's chord and one sun chord, so its transmittance falls by at most the factor
 *    e^{-(tau_v + tau_s)}: tau_v = sigma x the view ray's chord through the shell, tau_s =
 *    sigma x the longest sun chord from a point of the ray (both in double on the host), and
 *    the radiance falls by at most (1 - e^{-(tau_v + tau_s)}) L_clear.
 *  - Gain: the shell scatters at most its view optical depth's share of its source,
 *    (1 - e^{-tau_v}) omega E P(nu), E the sun's irradiance above the atmosphere and P the
 *    phase weight of the kernels' octave model, sum_{i < N} b^i HG(nu; g c^i) (N, b, c of
 *    cloud_shell.h; octave 0 is the exact HG phase). The reference scatters the true phase p
 *    <= P, plus the sky's light, which the margin (P - p) E covers: the test checks that it
 *    exceeds every clear-sky radiance of the views.
 * So L_shell - L_clear lies in [-(1 - e^{-(tau_v + tau_s)}) L_clear, (1 - e^{-tau_v}) omega E P]
 * (about -2.6 tau L_clear .. +0.4 % here), plus the estimator's error:
 *  - methods single and march sample every piece at a jittered point; the two scenes get the
 *    same random numbers (common random numbers, testprobe.h), so they differ only in how
 *    finely the air is sampled inside the shell, where the shell's walk refines the air grid.
 *    That changes the radiance by at most the grid's own quadrature error, estimated here as
 *    three times the change of the clear sky when its grid is refined 4x (32 -> 128 segments;
 *    a first-order rule's error is 4/3 of that change, the factor covers a second part of the
 *    ray refined on its own).
 *  - the reference: z = excess beyond the bound / sqrt(se_clear^2 + se_shell^2) < 4, se from
 *    independent batches (with common random numbers the two estimates are positively
 *    correlated, so the combined se overstates the difference's; the test is conservative).
 * A shell the rays never meet (camera at 3000 m above the shell 1000-2000 m, views upward,
 * sun above the horizon, so neither a view ray nor a sun ray from it crosses the shell) must
 * leave single and march bitwise unchanged; the reference's random walks can still reach it
 * (tau 1.6e-4 changes their light by far less than its noise), so it is held to |z| < 4.
 * Methods fast and lut refuse the shell at plan time (a usage error naming cloud.enabled):
 * checked, so this test notices when they start to accept it and then must cover them. */
#include <math.h>
#include <stdio.h>
#include <string.h>
#include "kernels_composed.h"
#include "testlib.h"
#include "testprobe.h"
#include "testscene.h"

#define DEG (M_PI / 180.0)
#define SUN_ZENITH_DEG 50.0
#define BASE_M 1000.0
#define TOP_M 2000.0
#define HG_G 0.5
#define VIEWS 3
#define ABOVE_VIEWS 2
#define DET_SAMPLES 64
#define REF_BATCHES 32
#define REF_SAMPLES 1024

static const double view_zenith[VIEWS] = {0.0, 60.0, 85.0}, view_azimuth[VIEWS] = {0.0, 90.0, 180.0};

static void scene_for(atmo_scene *s, const char *method, int shell, int view_steps)
{
    char set[96];
    test_scene_preset(s, "sky-noon");
    snprintf(set, sizeof set, "atmosphere.method=%s", method);
    test_scene_set(s, set);
    snprintf(set, sizeof set, "sun.zenith_deg=%.17g", SUN_ZENITH_DEG);
    test_scene_set(s, set);
    snprintf(set, sizeof set, "render.view_steps=%d", view_steps);
    test_scene_set(s, set);
    if (!shell)
        return;
    test_scene_set(s, "cloud.enabled=true");
    test_scene_set(s, "cloud.dsd=cumulus");
    test_scene_set(s, "cloud.lwc_g_m3=1e-6");
    test_scene_set(s, "cloud.phase=hg");
    snprintf(set, sizeof set, "cloud.hg_g=%g", HG_G);
    test_scene_set(s, set);
    snprintf(set, sizeof set, "cloud.bottom_m=%g", BASE_M);
    test_scene_set(s, set);
    snprintf(set, sizeof set, "cloud.top_m=%g", TOP_M);
    test_scene_set(s, set);
}

/* Length of the half-line from radius r with cosine mu inside the sphere of radius rs. */
static double inside(double r, double mu, double rs)
{
    double b = r * mu, disc = b * b - (r * r - rs * rs);
    if (disc <= 0.0)
        return 0.0;
    double q = sqrt(disc), t0 = -b - q, t1 = -b + q;
    return fmax(t1, 0.0) - fmax(t0, 0.0);
}

static double shell_chord(double R, double r, double mu)
{
    return inside(r, mu, R + TOP_M) - inside(r, mu, R + BASE_M);
}

/* The view ray's chord through the shell and the longest sun chord from its points (the ray
 * sampled every 10 m up to the top of the atmosphere or the ground). */
static void chords(const atmo_gpu_atmosphere *a, float4 ray, double *view, double *sun)
{
    double R = a->bottom_radius, r = ray.x, mu = ray.y, mu_s = ray.z, nu = ray.w;
    *view = shell_chord(R, r, mu);
    double end = inside(r, mu, a->top_radius), ground = r * r * (mu * mu - 1) + R * R;
    if (mu < 0.0 && ground >= 0.0)
        end = -r * mu - sqrt(ground);
    *sun = 0.0;
    for (double t = 0.0; t <= end; t += 10.0) {
        double rt = sqrt(r * r + t * t + 2.0 * r * t * mu);
        *sun = fmax(*sun, shell_chord(R, rt, (r * mu_s + t * nu) / rt));
    }
}

static double hg(double nu, double g)
{
    return (1.0 - g * g) / (4.0 * M_PI * pow(1.0 + g * g - 2.0 * g * nu, 1.5));
}

/* The octave model's phase weight sum_{i<N} b^i HG(nu; g c^i) (cloud_shell.h). */
static double octave_phase(double nu, double g)
{
    double P = 0.0, b = 1.0, c = 1.0;
    for (int i = 0; i < ATMO_CLOUD_OCTAVES; i++) {
        P += b * hg(nu, g * c);
        b *= CLOUD_OCTAVE_B;
        c *= CLOUD_OCTAVE_C;
    }
    return P;
}

static float4 ray_at(double r, double zenith_deg, double azimuth_deg)
{
    double mu = cos(zenith_deg * DEG), mu_s = cos(SUN_ZENITH_DEG * DEG);
    double nu = mu * mu_s + sqrt(1 - mu * mu) * sqrt(1 - mu_s * mu_s) * cos(azimuth_deg * DEG);
    float4 q = {(float)r, (float)mu, (float)mu_s, (float)nu};
    return q;
}

static void probe(atmo_cl *cl, const char *method, int shell, int view_steps, const float4 *rays,
                  int n, double (*mean)[3], double (*se)[3], atmo_plan *keep)
{
    atmo_scene s;
    atmo_plan p;
    scene_for(&s, method, shell, view_steps);
    test_plan(&s, &p);
    int reference = strcmp(method, "reference") == 0, bad[VIEWS];
    test_probe t;
    test_probe_open(&t, cl, &p);
    test_probe_rays(&t, rays, n, reference ? REF_BATCHES : 1,
                    reference ? REF_SAMPLES : DET_SAMPLES, TEST_PROBE_COMMON, mean, se, NULL, bad);
    test_probe_close(&t);
    for (int i = 0; i < n; i++)
        CHECK(bad[i] == 0);
    if (keep)
        *keep = p;
    else
        atmo_plan_free(&p);
}

/* The shell the views cross: L_shell - L_clear within the bound plus the estimator's error. */
static void crossing(atmo_cl *cl, const char *method)
{
    int reference = strcmp(method, "reference") == 0;
    atmo_plan shell;
    float4 rays[VIEWS];
    double clear[VIEWS][3], with[VIEWS][3], fine[VIEWS][3], se_c[VIEWS][3], se_s[VIEWS][3];
    double R = 6360e3;
    for (int v = 0; v < VIEWS; v++)
        rays[v] = ray_at(R, view_zenith[v], view_azimuth[v]);
    probe(cl, method, 0, 32, rays, VIEWS, clear, se_c, NULL);
    probe(cl, method, 1, 32, rays, VIEWS, with, se_s, &shell);
    if (!reference)
        probe(cl, method, 0, 128, rays, VIEWS, fine, NULL, NULL);
    const atmo_gpu_cloud *c = &shell.gpu.cloud;
    const atmo_gpu_atmosphere *a = &shell.gpu.atmosphere;
    CHECK(fabs(a->bottom_radius - R) < 1.0);
    const float *sigma = &c->extinction.x, *omega = &c->albedo.x, *E = &a->solar_irradiance.x;
    printf("%s: shell tau(550 nm) %.3e\n", method, sigma[1] * (TOP_M - BASE_M));
    for (int v = 0; v < VIEWS; v++) {
        double l_view, l_sun;
        chords(a, rays[v], &l_view, &l_sun);
        double P = octave_phase(rays[v].w, HG_G), p = hg(rays[v].w, HG_G);
        double eps_rel = 0.0;
        for (int k = 0; k < 3 && !reference; k++)
            eps_rel = fmax(eps_rel, fabs(clear[v][k] / fine[v][k] - 1.0));
        for (int k = 0; k < 3; k++) {
            double tau_v = sigma[k] * l_view, tau_s = sigma[k] * l_sun;
            double lo = -(-expm1(-(tau_v + tau_s))) * clear[v][k];
            double hi = -expm1(-tau_v) * omega[k] * E[k] * P;
            double d = with[v][k] - clear[v][k];
            double excess = fmax(lo - d, d - hi);
            if (reference) {
                CHECK((P - p) * E[k] > clear[v][k]); /* the skylight margin, see the header */
                double z = excess / sqrt(se_c[v][k] * se_c[v][k] + se_s[v][k] * se_s[v][k]);
                CHECK(z < 4.0);
                if (k == 1)
                    printf("  view %2.0f deg: clear %.6e shell %.6e (%+.2e), bound [%+.2e, "
                           "%+.2e], z beyond it %+.2f\n",
                           view_zenith[v], clear[v][k], with[v][k], d / clear[v][k],
                           lo / clear[v][k], hi / clear[v][k], z);
            } else {
                double eps = 3.0 * eps_rel * clear[v][k];
                CHECK(excess <= eps);
                if (k == 1)
                    printf("  view %2.0f deg: clear %.6e shell %.6e (%+.2e), bound [%+.2e, "
                           "%+.2e] +- quadrature %.1e\n",
                           view_zenith[v], clear[v][k], with[v][k], d / clear[v][k],
                           lo / clear[v][k], hi / clear[v][k], eps / clear[v][k]);
            }
        }
    }
    atmo_plan_free(&shell);
}

/* The shell below a camera looking up: nothing changes. */
static void missed(atmo_cl *cl, const char *method)
{
    int reference = strcmp(method, "reference") == 0;
    float4 rays[ABOVE_VIEWS];
    double clear[ABOVE_VIEWS][3], with[ABOVE_VIEWS][3], se_c[ABOVE_VIEWS][3], se_s[ABOVE_VIEWS][3];
    for (int v = 0; v < ABOVE_VIEWS; v++)
        rays[v] = ray_at(6360e3 + 3000.0, view_zenith[v], view_azimuth[v]);
    probe(cl, method, 0, 32, rays, ABOVE_VIEWS, clear, se_c, NULL);
    probe(cl, method, 1, 32, rays, ABOVE_VIEWS, with, se_s, NULL);
    double worst = 0.0;
    for (int v = 0; v < ABOVE_VIEWS; v++)
        for (int k = 0; k < 3; k++) {
            double d = with[v][k] - clear[v][k];
            if (reference) {
                double z = d / sqrt(se_c[v][k] * se_c[v][k] + se_s[v][k] * se_s[v][k]);
                CHECK(fabs(z) < 4.0);
                worst = fmax(worst, fabs(z));
            } else {
                CHECK(memcmp(&with[v][k], &clear[v][k], sizeof(double)) == 0);
                worst = fmax(worst, fabs(d));
            }
        }
    printf("%s: shell below the camera, views up: worst %s %.2e\n", method,
           reference ? "|z|" : "|difference|", worst);
}

static void refused(const char *method)
{
    atmo_scene s;
    atmo_plan p;
    atmo_err e;
    scene_for(&s, method, 1, 32);
    int rc = atmo_plan_make(&s, &p, &e);
    CHECK(rc == ATMO_ERR_USAGE && strstr(e.msg, "cloud.enabled") != NULL);
    if (rc == ATMO_OK)
        atmo_plan_free(&p);
    printf("%s: refuses the shell (%s)\n", method, rc ? e.msg : "accepted");
}

int main(void)
{
    atmo_cl cl;
    test_cl_open(&cl);
    const char *const methods[] = {"single", "march", "reference"};
    for (int i = 0; i < 3; i++) {
        crossing(&cl, methods[i]);
        missed(&cl, methods[i]);
    }
    refused("fast");
    refused("lut");
    atmo_cl_close(&cl);
    return test_finish();
}
