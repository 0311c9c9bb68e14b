/* test_space_views — a ray seen from space gives the radiance of the same ray started where it
 * enters the atmosphere, for every method: views from space and from inside the atmosphere
 * agree where they overlap.
 * labels: kernel slow
 * composes: atmosphere ms_lut visibility medium ms_lut_passes fast
 *
 * Rays. Cameras at the altitude of the `space` preset (2000 km) and at 1e8 m (100 000 km). Each
 * ray is designed at its entry point (r = top): its closest distance b to the planet centre
 * (perigee altitudes from the nadir through the ground limb, +-100 m around it, to 1 km below
 * the top of the atmosphere), the sun zenith at the entry (30, 80, 95 and 120 deg: day, low sun,
 * twilight across the planet's shadow, night) and the sun's azimuth from the ray's vertical
 * plane (0, 90, 180 deg); then walked back to the camera and rounded to float, as a kernel gets
 * it. The "inside" ray is the entry of that float ray computed in double: r = top exactly,
 * where every method takes its inside branch (atmosphere_enter moves only r > top); a radius
 * below the top would leave out a slice of air that, for rays grazing the top, holds a few
 * tenths of a percent of their light.
 *
 * Oracles and tolerances, per ray and channel:
 *  - single, march, lut (deterministic given the random numbers: common random numbers, so
 *    both rays get the same march offsets; lut at small table sizes). The only difference is
 *    the kernel's float computation of the entry, so |L_space - L_inside| must stay within the
 *    effect of that rounding: the entry's closest distance b = r sqrt((1 - mu)(1 + mu)) carries
 *    about three float roundings (dB = 4 u b, u = 2^-24: ~1.5 m), and the distance t0 to the
 *    entry the error that dB makes in sqrt(top^2 - b^2) plus a few roundings of r mu (it sets the
 *    sun cosine at the entry, dmu_s = dt0 |nu| / top + 4 u (r + t0) / top). Their effect on L is
 *    measured on the inside ray itself (b +- dB, mu_s +- dmu_s, sun azimuth kept), and the bound
 *    is the larger change in each plus 1e-5 L for the float rounding of the march and the
 *    lookups (32 segments of a few roundings each).
 *  - reference (Monte Carlo, 1024 samples): independent random numbers for the two rays; z =
 *    dL / sqrt(se1^2 + se2^2) from 64 batches each, |z| <= 5.5 per value (~700 values of the
 *    sunlit rays: with the batch estimates' ~126 degrees of freedom a false alarm about once in
 *    3000 runs), and sum z^2 below the chi-square critical value at p = 1e-4 (a bias common to
 *    many rays). The rounding effects above (<= 1e-3 of L) are far below its standard errors
 *    (median 3 % of a difference), so this check sees only errors of ~10 % or more.
 *  - fast: its sky-view LUT exists for a camera inside the atmosphere, so the inside rays come
 *    from a camera at the top (one plan per entry sun zenith, as the LUT holds one sun) and
 *    read the LUT, while a ray from space falls back to the march (test_fast checks that the
 *    fallback equals march). Their difference has two parts, separated here by interpolating,
 *    with fast's own lookup run on the host, a LUT of march values at the texels' rays (the
 *    march with the LUT's 64 segments, 64 common offsets; the whole radiance goes into the
 *    LUT's third plane, whose weight is 1, and its phase-free single-scattering planes are 0):
 *      texels: LUT lookup - interpolated march values. The texels hold a 64-segment midpoint
 *        march, the march values the mean over 64 random offsets of the same segments; both
 *        are quadratures of one integral and differ by the midpoint rule's error, second
 *        order in the segment length; the LUT interpolates single scattering without its
 *        phase functions and applies them at the ray's own nu, the emulation interpolates
 *        whole radiances, so the phase's change across a texel adds to this part; asserted
 *        within 1 % (test_fast's bound for ground rays)
 *        + 3 standard errors of the interpolated march, relative to max(L, 1 % of the largest
 *        L of the sun's rays).
 *      interpolation: interpolated march values - the march from space. This is the LUT's
 *        resolution, a property of the method, reported and not asserted: from the top of the
 *        atmosphere the rays that graze the ground limb or pass through the air above it (view
 *        zenith ~90-99 deg) change brightness by a factor e over ~1 deg, while the sky rows
 *        there are up to ~0.9 deg apart and the ground rows start at the horizon.
 *    Measured (PoCL): texels within 1.5 % (the emulation interpolates whole radiances, the LUT its
 *    phase-free parts: docs/notes/fast_method.md); interpolation up to 4.4 % (sun zenith 30 deg),
 *    4.4 % (80 deg), 5.9 % (95 deg; a ray reaching the ground 100 m inside the limb). So fast
 *    disagrees by up to ~6 % on the limb between a camera just inside the top of the atmosphere
 *    (its LUT) and one above it (the march).
 *
 * Measured: single, march and lut agree within 0.4 of their rounding bounds (worst 7.6e-5,
 * 3.2e-4 and 1.8e-4 of L); reference: worst |z| 3.4, median standard error of a difference 3 %.
 * These bounds hold because the entry's discriminant is formed from b
 * (atmosphere_top_discriminant, kernels/atmosphere/atmosphere.h; the other form, measured:
 * docs/notes/space_views.md); an error of the entry shows in the deterministic methods, far below
 * the reference's 3 % resolution.
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "testlib.h"
#include "testprobe.h"
#include "kernels_composed.h"

#define DEG (M_PI / 180.0)
#define U_FLOAT 5.9604644775390625e-8 /* 2^-24 */
#define N_PERIGEE 13
#define N_SUN 4
#define N_AZ 3
#define RAYS_PER_CAMERA (N_PERIGEE * N_SUN * N_AZ)
#define MAX_RAYS (2 * RAYS_PER_CAMERA)

static const double perigee_m[N_PERIGEE] = {-6.36e6, -3e6, -1e6, -1e5, -1e4, -1e3, -100,
                                            100,     1e3,  5e3,  2e4,  5e4,  59e3};
static const double sun_zenith_deg[N_SUN] = {30, 80, 95, 120};
static const double azimuth_deg[N_AZ] = {0, 90, 180};

/* A ray in double: radius, view cosine, sun cosine, view-sun cosine. */
typedef struct ray_d {
    double r, mu, mu_s, nu;
} ray_d;

static float4 to_float(ray_d q)
{
    float4 f = {(float)q.r, (float)q.mu, (float)q.mu_s, (float)q.nu};
    return f;
}

/* nu from mu, mu_s and the sun's azimuth from the ray's vertical plane */
static double view_sun_cosine(double mu, double mu_s, double cos_phi)
{
    return sqrt(fmax(1.0 - mu * mu, 0.0)) * sqrt(fmax(1.0 - mu_s * mu_s, 0.0)) * cos_phi +
           mu * mu_s;
}

/* cos of the sun's azimuth from the ray's plane, from a (possibly float-rounded) triple */
static double azimuth_cosine(double mu, double mu_s, double nu)
{
    double d = sqrt(fmax((1.0 - mu * mu) * (1.0 - mu_s * mu_s), 0.0));
    return d > 0.0 ? fmax(-1.0, fmin(1.0, (nu - mu * mu_s) / d)) : 1.0;
}

/* The camera at radius rc on the ray through the entry point (top, mu_e) with sun cosine mu_s_e
 * and nu there: C = E - t0 v with |C| = rc. */
static ray_d orbit_ray(double top, double rc, double mu_e, double mu_s_e, double nu)
{
    double t0 = top * mu_e + sqrt(rc * rc - top * top * (1.0 - mu_e * mu_e));
    ray_d c = {rc, (top * mu_e - t0) / rc, (top * mu_s_e - t0 * nu) / rc, nu};
    return c;
}

/* The entry into the atmosphere of the float ray q from r > top, in double; also the float
 * rounding bounds of the kernel's entry (see the header): dB on b, dmu_s on the sun cosine. */
static ray_d entry_of(double top, float4 q, double *dB, double *dmu_s)
{
    double r = q.x, mu = q.y, mu_s = q.z, nu = q.w;
    double b = r * sqrt((1.0 - mu) * (1.0 + mu));
    double disc = (top - b) * (top + b), root = sqrt(disc);
    double t0 = -r * mu - root;
    ray_d e = {top, -root / top, (r * mu_s + t0 * nu) / top, nu};
    *dB = 4.0 * U_FLOAT * b;
    double dt0 = 2.0 * top * *dB / (2.0 * fmax(root, 1.0)) + 4.0 * U_FLOAT * (r + t0);
    *dmu_s = dt0 * fabs(nu) / top + 4.0 * U_FLOAT * (r + t0) / top;
    return e;
}

/* The inside ray with b moved by db and the sun cosine by ds (sun azimuth kept). */
static float4 perturbed(double top, ray_d e, double db, double ds)
{
    double cos_phi = azimuth_cosine(e.mu, e.mu_s, e.nu);
    double b = top * sqrt(fmax(1.0 - e.mu * e.mu, 0.0)) + db;
    ray_d p = e;
    p.mu = -sqrt(fmax((top - b) * (top + b), 0.0)) / top;
    p.mu_s = fmax(-1.0, fmin(1.0, e.mu_s + ds));
    p.nu = view_sun_cosine(p.mu, p.mu_s, cos_phi);
    return to_float(p);
}

/* Space rays of both cameras for entry sun cosines mu_s_e[is]; *n rays. */
static void space_rays(const atmo_atmosphere *a, const double cam_r[2], const double *mu_s_e,
                       float4 *rays, int *n)
{
    double top = a->top_radius_m;
    *n = 0;
    for (int ic = 0; ic < 2; ic++)
        for (int ip = 0; ip < N_PERIGEE; ip++)
            for (int is = 0; is < N_SUN; is++)
                for (int ia = 0; ia < N_AZ; ia++) {
                    double b = fmax(a->bottom_radius_m + perigee_m[ip], 0.0);
                    double mu_e = -sqrt((top - b) * (top + b)) / top;
                    double nu = view_sun_cosine(mu_e, mu_s_e[is], cos(azimuth_deg[ia] * DEG));
                    rays[(*n)++] = to_float(orbit_ray(top, cam_r[ic], mu_e, mu_s_e[is], nu));
                }
}

static void describe(int i)
{
    int ia = i % N_AZ, is = (i / N_AZ) % N_SUN, ip = (i / (N_AZ * N_SUN)) % N_PERIGEE;
    fprintf(stderr, "  camera %d, perigee %g m, entry sun zenith %g deg, azimuth %g deg\n",
            i / RAYS_PER_CAMERA, perigee_m[ip], sun_zenith_deg[is], azimuth_deg[ia]);
}

/* single, march, lut: the inside ray and its four perturbations, common random numbers. */
static void check_deterministic(atmo_cl *cl, const char *method, const double cam_r[2])
{
    static float4 space[MAX_RAYS], inside[5 * MAX_RAYS];
    static double Ls[MAX_RAYS][3], Li[5 * MAX_RAYS][3];
    atmo_plan p;
    test_sky_plan(method, 0.0, 0.0, &p);
    const atmo_atmosphere *a = &p.atmosphere;
    double top = a->top_radius_m, mu_s_e[N_SUN];
    for (int is = 0; is < N_SUN; is++)
        mu_s_e[is] = cos(sun_zenith_deg[is] * DEG);
    int n;
    space_rays(a, cam_r, mu_s_e, space, &n);
    for (int i = 0; i < n; i++) {
        double dB, ds;
        ray_d e = entry_of(top, space[i], &dB, &ds);
        inside[i] = to_float(e);
        inside[n + i] = perturbed(top, e, dB, 0.0);
        inside[2 * n + i] = perturbed(top, e, -dB, 0.0);
        inside[3 * n + i] = perturbed(top, e, 0.0, ds);
        inside[4 * n + i] = perturbed(top, e, 0.0, -ds);
    }
    test_probe t;
    test_probe_open(&t, cl, &p);
    int batches = strcmp(method, "lut") ? 16 : 1; /* 16 march offsets shared by both rays */
    test_probe_rays(&t, space, n, batches, 1, TEST_PROBE_COMMON, Ls, NULL, NULL, NULL);
    test_probe_rays(&t, inside, 5 * n, batches, 1, TEST_PROBE_COMMON, Li, NULL, NULL, NULL);
    test_probe_close(&t);
    double worst = 0.0, worst_ratio = 0.0;
    for (int i = 0; i < n; i++)
        for (int c = 0; c < 3; c++) {
            double L = Li[i][c], d = fabs(Ls[i][c] - L);
            double sb = fmax(fabs(Li[n + i][c] - L), fabs(Li[2 * n + i][c] - L));
            double ss = fmax(fabs(Li[3 * n + i][c] - L), fabs(Li[4 * n + i][c] - L));
            double tol = sb + ss + 1e-5 * L;
            if (!(d <= tol)) {
                fprintf(stderr, "%s: space %.7g vs inside %.7g (channel %d), bound %.3g\n",
                        method, Ls[i][c], L, c, tol);
                describe(i);
            }
            CHECK(d <= tol);
            if (L > 0.0)
                worst = fmax(worst, d / L);
            if (tol > 0.0)
                worst_ratio = fmax(worst_ratio, d / tol);
        }
    printf("%-9s %d rays: worst |space - inside| %.2e of L, %.2f of its rounding bound\n", method,
           n, worst, worst_ratio);
}

static int compare_double(const void *x, const void *y)
{
    double a = *(const double *)x, b = *(const double *)y;
    return (a > b) - (a < b);
}

/* reference: independent random numbers, z-tests; the suns that light the rays (30, 80 and
 * 95 deg: at 120 deg the rays hold ~1e-10 of the day's light, all noise). */
static void check_reference(atmo_cl *cl, const double cam_r[2])
{
    enum { SAMPLES = 64 * 16 };
    static float4 all[MAX_RAYS], rays[2 * MAX_RAYS];
    static double L[2 * MAX_RAYS][3], se[2 * MAX_RAYS][3], rel_se[3 * MAX_RAYS];
    static int index[MAX_RAYS];
    atmo_plan p;
    test_sky_plan("reference", 0.0, 0.0, &p);
    double top = p.atmosphere.top_radius_m, mu_s_e[N_SUN];
    for (int is = 0; is < N_SUN; is++)
        mu_s_e[is] = cos(sun_zenith_deg[is] * DEG);
    int n_all, n = 0;
    space_rays(&p.atmosphere, cam_r, mu_s_e, all, &n_all);
    for (int i = 0; i < n_all; i++)
        if (sun_zenith_deg[(i / N_AZ) % N_SUN] < 100.0)
            index[n] = i, rays[n++] = all[i];
    for (int i = 0; i < n; i++) {
        double dB, ds;
        rays[n + i] = to_float(entry_of(top, rays[i], &dB, &ds));
    }
    test_probe t;
    test_probe_open(&t, cl, &p);
    test_probe_rays(&t, rays, 2 * n, 64, SAMPLES / 64, TEST_PROBE_INDEPENDENT, L, se, NULL,
                    NULL);
    test_probe_close(&t);
    double chi2 = 0.0, worst_z = 0.0;
    int dof = 0;
    for (int i = 0; i < n; i++)
        for (int c = 0; c < 3; c++) {
            double s = sqrt(se[i][c] * se[i][c] + se[n + i][c] * se[n + i][c]);
            double d = L[i][c] - L[n + i][c];
            if (s == 0.0) { /* both dark: no light reaches either */
                CHECK(d == 0.0);
                continue;
            }
            double z = d / s;
            if (!(fabs(z) <= 5.5)) {
                fprintf(stderr, "reference: space %.6g +- %.2g vs inside %.6g +- %.2g (channel "
                        "%d): z = %.2f\n", L[i][c], se[i][c], L[n + i][c], se[n + i][c], c, z);
                describe(index[i]);
            }
            CHECK(fabs(z) <= 5.5);
            rel_se[dof] = s / fabs(L[n + i][c]);
            chi2 += z * z, dof++;
            worst_z = fmax(worst_z, fabs(z));
        }
    double crit = test_chi2_critical_1e4(dof);
    CHECK(chi2 <= crit);
    qsort(rel_se, (size_t)dof, sizeof *rel_se, compare_double);
    double median = dof ? rel_se[dof / 2] : 0.0;
    printf("reference %d rays x %d samples: worst |z| %.2f, sum z^2 %.0f for %d values "
           "(critical %.0f); median relative standard error of a difference %.1f %%\n", n,
           SAMPLES, worst_z, chi2, dof, crit, 100.0 * median);
}

/* fast: the sky-view LUT of a camera at the top against the march fallback of the rays from
 * space, split into the LUT's texel error (asserted) and its interpolation error (reported). */
static void check_fast(atmo_cl *cl, const double cam_r[2], double top_altitude_m)
{
    enum { N_COLUMNS = 6, FAST_SUNS = 3 }; /* the night sun (120 deg) leaves ~1e-10 */
    static float4 space[MAX_RAYS], inside[MAX_RAYS], texels[N_COLUMNS * 4096], all[MAX_RAYS];
    static double Ls[MAX_RAYS][3], Li[MAX_RAYS][3], Li_se[MAX_RAYS][3];
    static double Lt[N_COLUMNS * 4096][3], Lt_se[N_COLUMNS * 4096][3];
    static float4 host_lut[4096 * 4096 / 64], host_se[4096 * 4096 / 64];
    double worst_texel = 0.0, worst_interp = 0.0, worst_total = 0.0, sun_interp[N_SUN] = {0};
    int worst_ray = 0, worst_sun = 0;
    for (int is = 0; is < FAST_SUNS; is++) {
        atmo_plan pf, pm;
        test_sky_plan("fast", top_altitude_m, sun_zenith_deg[is], &pf);
        test_sky_plan("march", top_altitude_m, sun_zenith_deg[is], &pm);
        pm.gpu.view_steps = pf.gpu.sky_view.steps; /* the LUT's segments per ray */
        const atmo_atmosphere *a = &pf.atmosphere;
        double top = a->top_radius_m;
        float r_c = pf.gpu.camera.local_up.w, mu_s_c = pf.gpu.sun_direction.y;
        int W = pf.gpu.sky_view.width, H = pf.gpu.sky_view.height;
        CHECK(r_c == (float)top && W > 0 && 3 * W * H <= 4096 * 4096 / 64 && H <= 4096);

        double mu_s_e[N_SUN] = {mu_s_c, mu_s_c, mu_s_c, mu_s_c};
        int n_all, n = 0;
        space_rays(a, cam_r, mu_s_e, all, &n_all);
        for (int i = 0; i < n_all; i++) { /* this sun's rays only */
            if ((i / N_AZ) % N_SUN != is)
                continue;
            double dB, ds;
            ray_d e = entry_of(top, all[i], &dB, &ds);
            space[n] = all[i];
            inside[n] = to_float(e);
            inside[n].x = r_c, inside[n].z = mu_s_c; /* the LUT's (r, mu_s) exactly */
            n++;
        }
        /* the texels that rays at sun azimuth 0, 90 and 180 deg interpolate between, computed
         * by the march with the LUT's segment count, the others NaN (a lookup that touched one
         * would say so) */
        int cols[N_COLUMNS] = {0, 1, W / 2 - 1, W / 2, W - 2, W - 1}, nt = 0;
        for (int k = 0; k < 3 * W * H; k++) { /* planes: Rayleigh, Mie (phase-free), rest */
            float4 q = {k < 2 * W * H ? 0.0f : NAN, k < 2 * W * H ? 0.0f : NAN,
                        k < 2 * W * H ? 0.0f : NAN, 0.0f};
            host_lut[k] = host_se[k] = q;
        }
        for (int j = 0; j < H; j++)
            for (int k = 0; k < N_COLUMNS; k++) {
                float mu, cos_phi;
                fast_sky_view_ray(&pf.gpu, cols[k], j, W, H, &mu, &cos_phi);
                float nu = atmo_clamp_cos(mu * mu_s_c + atmo_safe_sqrt((1.0f - mu * mu) *
                                          (1.0f - mu_s_c * mu_s_c)) * cos_phi);
                float4 q = {r_c, mu, mu_s_c, nu};
                texels[nt++] = q;
            }

        test_probe tf, tm;
        test_probe_open(&tf, cl, &pf);
        test_probe_rays(&tf, inside, n, 1, 1, TEST_PROBE_COMMON, Li, Li_se, NULL, NULL);
        test_probe_rays(&tf, space, n, 64, 1, TEST_PROBE_COMMON, Ls, NULL, NULL, NULL);
        test_probe_close(&tf);
        test_probe_open(&tm, cl, &pm);
        test_probe_rays(&tm, texels, nt, 64, 1, TEST_PROBE_COMMON, Lt, Lt_se, NULL, NULL);
        test_probe_close(&tm);
        for (int j = 0, t = 0; j < H; j++)
            for (int k = 0; k < N_COLUMNS; k++, t++) {
                float4 q = {(float)Lt[t][0], (float)Lt[t][1], (float)Lt[t][2], 0.0f};
                float4 e = {(float)Lt_se[t][0], (float)Lt_se[t][1], (float)Lt_se[t][2], 0.0f};
                host_lut[2 * W * H + j * W + cols[k]] = q; /* the whole march as "rest" */
                host_se[2 * W * H + j * W + cols[k]] = e;
            }

        double floor_c[3] = {0, 0, 0};
        for (int i = 0; i < n; i++)
            for (int c = 0; c < 3; c++)
                floor_c[c] = fmax(floor_c[c], 1e-2 * Ls[i][c]);
        for (int i = 0; i < n; i++) {
            int ground = geometry_ray_hits_ground(inside[i].x, inside[i].y, a->bottom_radius_m);
            vec3 v = fast_sky_view_lookup(&pf.gpu, host_lut, inside[i].y, inside[i].z,
                                          inside[i].w, ground);
            vec3 w = fast_sky_view_lookup(&pf.gpu, host_se, inside[i].y, inside[i].z,
                                          inside[i].w, ground);
            double interp[3] = {v.x, v.y, v.z}, interp_se[3] = {w.x, w.y, w.z};
            for (int c = 0; c < 3; c++) {
                CHECK(isfinite(interp[c])); /* only the probed texels were read */
                double ref = fmax(Ls[i][c], floor_c[c]);
                double texel = (Li[i][c] - interp[c]) / ref;
                double tol = 0.01 + 3.0 * interp_se[c] / ref;
                if (!(fabs(texel) <= tol))
                    fprintf(stderr, "fast: LUT %.6g vs the march at its texels, interpolated, "
                            "%.6g (channel %d): %+.2f %%\n", Li[i][c], interp[c], c,
                            100 * texel);
                CHECK(fabs(texel) <= tol);
                CHECK(Li_se[i][c] == 0.0); /* the LUT path: no randomness */
                worst_texel = fmax(worst_texel, fabs(texel));
                worst_interp = fmax(worst_interp, fabs(interp[c] - Ls[i][c]) / ref);
                sun_interp[is] = fmax(sun_interp[is], fabs(interp[c] - Ls[i][c]) / ref);
                if (fabs(Li[i][c] - Ls[i][c]) / ref > worst_total) {
                    worst_total = fabs(Li[i][c] - Ls[i][c]) / ref;
                    worst_ray = i, worst_sun = is;
                }
            }
        }
    }
    printf("fast      LUT at the top vs march from space: worst %.2f %% (camera %d, perigee %g m, "
           "sun zenith %g deg, azimuth %g deg); LUT texels within %.2f %%, its bilinear "
           "interpolation %.2f %%\n", 100 * worst_total, worst_ray / (N_PERIGEE * N_AZ),
           perigee_m[(worst_ray / N_AZ) % N_PERIGEE], sun_zenith_deg[worst_sun],
           azimuth_deg[worst_ray % N_AZ], 100 * worst_texel, 100 * worst_interp);
    for (int is = 0; is < FAST_SUNS; is++)
        printf("          interpolation error, sun zenith %g deg: %.2f %%\n", sun_zenith_deg[is],
               100 * sun_interp[is]);
}

int main(void)
{
    atmo_cl cl;
    test_cl_open(&cl);
    atmo_scene s;
    atmo_plan p;
    test_scene_preset(&s, "space");
    test_plan(&s, &p);
    const double *x = s.camera.position_m, R = p.atmosphere.bottom_radius_m;
    double cam_r[2] = {sqrt(x[0] * x[0] + (x[1] + R) * (x[1] + R) + x[2] * x[2]), R + 1e8};
    printf("cameras at %.0f km (preset space) and %.0f km\n",
           (cam_r[0] - p.atmosphere.bottom_radius_m) / 1e3,
           (cam_r[1] - p.atmosphere.bottom_radius_m) / 1e3);
    check_deterministic(&cl, "single", cam_r);
    check_deterministic(&cl, "march", cam_r);
    check_deterministic(&cl, "lut", cam_r);
    check_fast(&cl, cam_r, p.atmosphere.top_radius_m - R);
    check_reference(&cl, cam_r);
    atmo_cl_close(&cl);
    return test_finish();
}
