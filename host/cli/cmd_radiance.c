/* cmd_radiance.c — `atmo radiance`: the sky radiance of the scene's atmosphere for given view
 * directions, from any method, for users and tests.
 *
 * Scene: the defaults, then --scene FILE (or the default preset), then --set KEY=VALUE and
 * --method M in command-line order; --altitude-m, --sun-zenith-deg and --sun-azimuth-deg place
 * the camera and the sun (zenith and azimuth in degrees; the azimuth of a view is measured like
 * the sun's, direction = (sin z sin a, cos z, sin z cos a)). Each view becomes a ray
 * (r = bottom radius + altitude, mu = cos z, mu_s, nu) for the plan's `sky_probe` kernel, which
 * averages `--samples` samples of the method's sky_radiance (the sun disc is not included).
 * Default samples: 65536 for `reference` (about 0.5 % standard error in blue at the zenith), 64
 * for the other methods (their only randomness is the offset of the march samples).
 * Samples are rounded up to a multiple of 64: each view runs as K = 64 independent batches
 * (distinct RNG pixel indices), and the spread of the batch means gives the standard error.
 *
 * --distance-m D (aerial perspective): each view ray ends at a black surface D metres from the
 * camera, and the method's sky_segment (kernels/atmosphere/sky_method.h) gives the radiance that the air
 * over [0, D] scatters toward the camera (all orders the method models) and the transmittance
 * T(0, D) (kernel sky_probe_segment). A view that reaches the ground before D sees the lit
 * ground (the surface lies behind it), one that leaves the atmosphere before D the whole sky:
 * both are then the view's sky radiance. --irradiance is unaffected (the sky above the camera).
 *
 * Luminance: Y = BT.709 luminance of k_c L_c with k from atmo_luminance_factors(lambda, -3)
 * (Bruneton's radiance-to-luminance constants for the sky), in cd/m^2.
 * --irradiance adds, on a horizontal surface at the camera (W m^-2 nm^-1):
 *   direct = E T_sun V max(mu_s, 0): E T_sun max(mu_s, 0) of the atmosphere alone from the
 *            double-precision model (atmo_ref_direct_irradiance), times V, the sun's visibility
 *            at the camera from the device (atmo_probe_sun: visibility.h's visibility_sun, the
 *            query every kernel's sunlight goes through: the planet, terrain and objects, and
 *            the clouds' transmittance toward the sun, shell or layer), so whatever shades the
 *            scene's sunlight shades the direct beam, while the atmosphere's part keeps the
 *            double model's accuracy;
 *   sky    = int_{upper hemisphere} L cos(theta) dw of the method's radiance, by a product rule:
 *            16-point Gauss-Legendre in cos(theta) on [0, 1] times a 16-point midpoint rule in
 *            azimuth over [0, pi] (the sky is symmetric about the sun's vertical plane, so the
 *            half is doubled; the midpoint rule is spectrally accurate for a smooth periodic
 *            integrand). Each direction gets samples / 64 samples (at least 1): the 256
 *            directions average their noise. */
#include <cjson/cJSON.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "atmo/atmosphere_ref.h"
#include "atmo/cl_runtime.h"
#include "atmo/colour.h"
#include "atmo/plan.h"
#include "atmo/probe.h"
#include "atmo/quadrature.h"
#include "atmo/render.h"
#include "atmo/scene.h"
#include "commands.h"

#define RADIANCE_MAX_VIEWS 1024
#define RADIANCE_QUAD 16
#define DEG (M_PI / 180.0)

static const char radiance_usage[] =
    "usage: atmo radiance --altitude-m H --sun-zenith-deg S [--sun-azimuth-deg A]\n"
    "                     --view Z,A [--view Z,A ...] [--method M] [--scene F] [--set K=V ...]\n"
    "                     [--distance-m D] [--irradiance] [--json] [--samples N] [--seed N]\n"
    "                     [--device D]\n"
    "\n"
    "Prints, for each view (zenith Z and azimuth A in degrees, azimuth measured like the sun's),\n"
    "the spectral radiance of the sky at each render wavelength (W m^-2 sr^-1 nm^-1, sun disc\n"
    "excluded) and its luminance (cd/m^2).\n"
    "  --altitude-m H     camera altitude above the ground in metres (>= 0)\n"
    "  --sun-zenith-deg S, --sun-azimuth-deg A   the sun (degrees; azimuth default 0)\n"
    "  --method M         atmosphere method (single, march, fast, lut, reference, auto;\n"
    "                     default auto: march with clouds or the observer, else fast)\n"
    "  --scene F          JSON scene file (default: the default preset); --set K=V overrides\n"
    "  --distance-m D     aerial perspective: each view ends at a black surface D metres away\n"
    "                     (D > 0); prints the radiance in-scattered over [0, D] and the\n"
    "                     transmittance to the surface. A view that meets the ground or leaves\n"
    "                     the atmosphere before D gives its whole sky radiance (lit ground\n"
    "                     included) and the transmittance to the ground or to space\n"
    "  --irradiance       add direct and sky irradiance on a horizontal surface (W m^-2 nm^-1)\n"
    "  --json             one JSON object instead of text\n"
    "  --samples N        samples per view (default 65536 for reference, 64 otherwise)\n"
    "  --seed N           random seed (image.seed)\n"
    "  --device D         OpenCL device by index or name part (atmo devices)\n";

typedef struct radiance_view {
    double zenith_deg, azimuth_deg;
    double L[3], se[3];
    double T[3], T_se[3]; /* with --distance-m */
} radiance_view;

/* Parses a finite number that fills the whole string. */
static int parse_option_number(const char *opt, const char *v, double lo, double hi, double *out, atmo_err *e)
{
    char *end;
    double x = v ? strtod(v, &end) : 0.0;
    if (!v || *v == 0 || *end != 0 || !isfinite(x) || x < lo || x > hi)
        return atmo_fail(e, ATMO_ERR_USAGE, "%s needs a number in [%g, %g], got '%s'", opt, lo, hi,
                         v ? v : "");
    *out = x;
    return ATMO_OK;
}

static int parse_view(const char *v, radiance_view *view, atmo_err *e)
{
    char z[64], a[64];
    const char *comma = strchr(v, ',');
    size_t n = comma ? (size_t)(comma - v) : 0;
    if (!comma || n == 0 || n >= sizeof z || strlen(comma + 1) >= sizeof a)
        return atmo_fail(e, ATMO_ERR_USAGE,
                         "--view needs ZENITH,AZIMUTH in degrees (e.g. --view 45,180), got '%s'", v);
    memcpy(z, v, n);
    z[n] = 0;
    snprintf(a, sizeof a, "%s", comma + 1);
    int rc = parse_option_number("--view zenith", z, 0.0, 180.0, &view->zenith_deg, e);
    return rc ? rc : parse_option_number("--view azimuth", a, -360.0, 360.0, &view->azimuth_deg, e);
}

static void view_direction(double zenith_deg, double azimuth_deg, double out[3])
{
    atmo_sun_direction(zenith_deg, azimuth_deg, out); /* the same convention for views */
}

/* Gauss-Legendre nodes and weights on [0, 1]: x = (1 - z) / 2, w / 2 of those on (-1, 1). */
static void gauss_legendre01(int n, double *x, double *w)
{
    atmo_gauss_legendre(n, x, w);
    for (int i = 0; i < n; i++)
        x[i] = 0.5 * (1.0 - x[i]), w[i] *= 0.5;
}

static void json_vec(cJSON *o, const char *key, const double v[3])
{
    cJSON_AddItemToObject(o, key, cJSON_CreateDoubleArray(v, 3));
}

int cmd_radiance(int argc, char **argv)
{
    atmo_err e = {{0}};
    atmo_scene scene;
    atmo_plan plan = {0};
    atmo_probe probe = {0};
    int rc = ATMO_OK, json = 0, irradiance = 0, samples = 0, n_views = 0;
    int have_altitude = 0, have_sun = 0, have_distance = 0;
    double altitude = 0.0, sun_zenith = 0.0, sun_azimuth = 0.0, distance = 0.0;
    const char *scene_file = NULL, *device = NULL;
    static radiance_view views[RADIANCE_MAX_VIEWS];
    float4 *rays = NULL;
    double(*mean)[3] = NULL;

    /* the scene file comes first whatever its position, so --set and --method apply over it */
    for (int i = 1; i + 1 < argc; i++)
        if (strcmp(argv[i], "--scene") == 0)
            scene_file = argv[i + 1];
    atmo_scene_defaults(&scene);
    rc = scene_file ? atmo_scene_load_json(&scene, scene_file, &e)
                    : atmo_scene_apply_preset(&scene, atmo_default_preset, &e);
    for (int i = 1; i < argc && rc == ATMO_OK; i++) {
        const char *a = argv[i], *v = i + 1 < argc ? argv[i + 1] : NULL;
        if (strcmp(a, "--help") == 0 || strcmp(a, "-h") == 0) {
            fputs(radiance_usage, stdout);
            return ATMO_OK;
        }
        if (strcmp(a, "--json") == 0) {
            json = 1;
            continue;
        }
        if (strcmp(a, "--irradiance") == 0) {
            irradiance = 1;
            continue;
        }
        static const char *const with_value[] = {
            "--altitude-m", "--sun-zenith-deg", "--sun-azimuth-deg", "--view", "--method",
            "--scene", "--set", "--samples", "--seed", "--device", "--distance-m", NULL};
        int known = 0;
        for (int k = 0; with_value[k]; k++)
            known |= strcmp(a, with_value[k]) == 0;
        if (!known) {
            rc = atmo_fail(&e, ATMO_ERR_USAGE, "%s '%s' (atmo radiance --help)",
                           a[0] == '-' ? "unknown option" : "unexpected argument", a);
            break;
        }
        if (!v) {
            rc = atmo_fail(&e, ATMO_ERR_USAGE, "%s needs a value (atmo radiance --help)", a);
            break;
        }
        i++;
        double x = 0.0;
        if (strcmp(a, "--altitude-m") == 0) {
            rc = parse_option_number(a, v, 0.0, 1e9, &altitude, &e);
            have_altitude = 1;
        } else if (strcmp(a, "--sun-zenith-deg") == 0) {
            rc = parse_option_number(a, v, 0.0, 180.0, &sun_zenith, &e);
            have_sun = 1;
        } else if (strcmp(a, "--distance-m") == 0) {
            if ((rc = parse_option_number(a, v, 0.0, 1e12, &distance, &e)) == ATMO_OK && distance <= 0.0)
                rc = atmo_fail(&e, ATMO_ERR_USAGE, "--distance-m needs a distance > 0 m, got '%s'",
                               v);
            have_distance = 1;
        } else if (strcmp(a, "--sun-azimuth-deg") == 0) {
            rc = parse_option_number(a, v, -360.0, 360.0, &sun_azimuth, &e);
        } else if (strcmp(a, "--view") == 0) {
            if (n_views == RADIANCE_MAX_VIEWS)
                rc = atmo_fail(&e, ATMO_ERR_USAGE, "at most %d --view options", RADIANCE_MAX_VIEWS);
            else
                rc = parse_view(v, &views[n_views++], &e);
        } else if (strcmp(a, "--method") == 0) {
            rc = atmo_scene_set(&scene, "atmosphere.method", v, "--method", &e);
        } else if (strcmp(a, "--set") == 0) {
            rc = atmo_scene_assign(&scene, v, "--set", &e);
        } else if (strcmp(a, "--samples") == 0) {
            if ((rc = parse_option_number(a, v, 1, 1 << 26, &x, &e)) == ATMO_OK && x != floor(x))
                rc = atmo_fail(&e, ATMO_ERR_USAGE, "--samples needs a whole number, got '%s'", v);
            samples = (int)x;
        } else if (strcmp(a, "--seed") == 0) {
            rc = atmo_scene_set(&scene, "image.seed", v, "--seed", &e);
        } else if (strcmp(a, "--device") == 0) {
            device = v;
        }
    }
    if (rc == ATMO_OK && (!have_altitude || !have_sun))
        rc = atmo_fail(&e, ATMO_ERR_USAGE,
                       "--altitude-m and --sun-zenith-deg are required (atmo radiance --help)");
    if (rc == ATMO_OK && n_views == 0 && !irradiance)
        rc = atmo_fail(&e, ATMO_ERR_USAGE, "give at least one --view ZENITH,AZIMUTH (or --irradiance)");
    char number[64];
    if (rc == ATMO_OK) {
        snprintf(number, sizeof number, "%.17g", sun_zenith);
        rc = atmo_scene_set(&scene, "sun.zenith_deg", number, "--sun-zenith-deg", &e);
    }
    if (rc == ATMO_OK) {
        snprintf(number, sizeof number, "%.17g", sun_azimuth);
        rc = atmo_scene_set(&scene, "sun.azimuth_deg", number, "--sun-azimuth-deg", &e);
    }
    if (rc == ATMO_OK)
        rc = atmo_plan_make(&scene, &plan, &e);
    if (rc)
        goto cleanup;
    int is_reference = scene.atmosphere.method == ATMO_METHOD_REFERENCE;
    if (samples == 0)
        samples = is_reference ? 65536 : 64;
    samples = (samples + ATMO_PROBE_BATCHES - 1) / ATMO_PROBE_BATCHES * ATMO_PROBE_BATCHES;

    /* rays: the views, then the sky-irradiance quadrature directions */
    const atmo_atmosphere *atm = &plan.atmosphere;
    double r = atm->bottom_radius_m + altitude, sun[3], mu_s;
    view_direction(sun_zenith, sun_azimuth, sun);
    mu_s = sun[1];
    int n_quad = irradiance ? RADIANCE_QUAD * RADIANCE_QUAD : 0;
    int n_rays = n_views + n_quad;
    rays = malloc(sizeof(float4) * (size_t)(n_rays ? n_rays : 1));
    float *distances = malloc(sizeof(float) * (size_t)(n_views ? n_views : 1));
    mean = malloc(sizeof *mean * (size_t)(n_rays ? n_rays : 1));
    double(*se)[3] = malloc(sizeof *se * (size_t)(n_views ? n_views : 1));
    double(*t_mean)[3] = malloc(sizeof *t_mean * (size_t)(n_views ? n_views : 1));
    double(*t_se)[3] = malloc(sizeof *t_se * (size_t)(n_views ? n_views : 1));
    double gx[RADIANCE_QUAD], gw[RADIANCE_QUAD];
    if (!rays || !mean || !se || !distances || !t_mean || !t_se) {
        free(t_se);
        free(t_mean);
        free(distances);
        free(se);
        rc = atmo_fail(&e, ATMO_ERR_RUNTIME, "out of memory");
        goto cleanup;
    }
    for (int i = 0; i < n_views; i++) {
        double d[3];
        view_direction(views[i].zenith_deg, views[i].azimuth_deg, d);
        float4 q = {(float)r, (float)d[1], (float)mu_s,
                    (float)(d[0] * sun[0] + d[1] * sun[1] + d[2] * sun[2])};
        rays[i] = q;
        distances[i] = (float)distance;
    }
    gauss_legendre01(RADIANCE_QUAD, gx, gw);
    for (int i = 0; i < RADIANCE_QUAD && irradiance; i++)
        for (int j = 0; j < RADIANCE_QUAD; j++) {
            double mu = gx[i], phi = M_PI * (j + 0.5) / RADIANCE_QUAD, s = sqrt(1.0 - mu * mu);
            /* azimuth measured from the sun's */
            double nu = s * sqrt(fmax(1.0 - mu_s * mu_s, 0.0)) * cos(phi) + mu * mu_s;
            float4 q = {(float)r, (float)mu, (float)mu_s, (float)nu};
            rays[n_views + i * RADIANCE_QUAD + j] = q;
        }

    if ((rc = atmo_probe_open(&probe, &plan, device, &e)))
        goto cleanup_se;
    if (n_views && !have_distance &&
        (rc = atmo_probe_rays(&probe, rays, n_views, samples, mean, se, &e)))
        goto cleanup_se;
    if (n_views && have_distance &&
        (rc = atmo_probe_segments(&probe, rays, distances, n_views, samples, mean, se, t_mean,
                                  t_se, &e)))
        goto cleanup_se;
    int quad_samples = samples / 64 > 0 ? samples / 64 : 1;
    if (n_quad && (rc = atmo_probe_rays(&probe, rays + n_views, n_quad, quad_samples,
                                        mean + n_views, NULL, &e)))
        goto cleanup_se;

    double k[3], direct[3] = {0, 0, 0}, sky[3] = {0, 0, 0}, sun_vis[1][3];
    float4 camera_up = {(float)r, 1.0f, (float)mu_s, (float)mu_s};
    if (irradiance && (rc = atmo_probe_sun(&probe, &camera_up, 1, sun_vis, &e)))
        goto cleanup_se;
    atmo_luminance_factors(scene.render.wavelengths_nm, -3.0, k);
    if (irradiance) {
        atmo_ref_direct_irradiance(atm, r, mu_s, direct);
        for (int c = 0; c < 3; c++)
            direct[c] *= sun_vis[0][c];
        for (int i = 0; i < RADIANCE_QUAD; i++)
            for (int j = 0; j < RADIANCE_QUAD; j++)
                for (int c = 0; c < 3; c++) /* 2 (symmetry) * pi / n (midpoint) * w mu L */
                    sky[c] += 2.0 * M_PI / RADIANCE_QUAD * gw[i] * gx[i] *
                              mean[n_views + i * RADIANCE_QUAD + j][c];
    }
    for (int i = 0; i < n_views; i++)
        for (int c = 0; c < 3; c++)
            views[i].L[c] = mean[i][c], views[i].se[c] = se[i][c],
            views[i].T[c] = have_distance ? t_mean[i][c] : 0.0,
            views[i].T_se[c] = have_distance ? t_se[i][c] : 0.0;

    const double *wl = scene.render.wavelengths_nm;
    if (json) {
        cJSON *root = cJSON_CreateObject();
        json_vec(root, "wavelengths_nm", wl);
        cJSON_AddStringToObject(root, "method", plan.method);
        cJSON_AddNumberToObject(root, "altitude_m", altitude);
        cJSON_AddNumberToObject(root, "sun_zenith_deg", sun_zenith);
        cJSON_AddNumberToObject(root, "sun_azimuth_deg", sun_azimuth);
        if (have_distance)
            cJSON_AddNumberToObject(root, "distance_m", distance);
        cJSON_AddNumberToObject(root, "samples", samples);
        cJSON_AddNumberToObject(root, "seed", scene.image.seed);
        cJSON_AddStringToObject(root, "device", atmo_session_get_info(probe.session)->device_name);
        cJSON *arr = cJSON_AddArrayToObject(root, "views");
        for (int i = 0; i < n_views; i++) {
            cJSON *o = cJSON_CreateObject();
            cJSON_AddNumberToObject(o, "zenith_deg", views[i].zenith_deg);
            cJSON_AddNumberToObject(o, "azimuth_deg", views[i].azimuth_deg);
            json_vec(o, "radiance", views[i].L);
            json_vec(o, "radiance_standard_error", views[i].se);
            cJSON_AddNumberToObject(o, "luminance_cd_m2", atmo_luminance_from_radiance(k, views[i].L));
            if (have_distance) {
                json_vec(o, "transmittance", views[i].T);
                json_vec(o, "transmittance_standard_error", views[i].T_se);
            }
            cJSON_AddItemToArray(arr, o);
        }
        if (irradiance) {
            cJSON *irr = cJSON_AddObjectToObject(root, "irradiance");
            json_vec(irr, "direct", direct);
            json_vec(irr, "sky", sky);
        }
        char *text = cJSON_Print(root);
        cJSON_Delete(root);
        if (!text) {
            rc = atmo_fail(&e, ATMO_ERR_RUNTIME, "out of memory printing JSON");
            goto cleanup_se;
        }
        printf("%s\n", text);
        free(text);
    } else {
        printf("method %s, altitude %g m, sun zenith %g deg azimuth %g deg, %d samples per view\n",
               plan.method, altitude, sun_zenith, sun_azimuth, samples);
        if (have_distance)
            printf("aerial perspective: radiance in-scattered over the first %g m of each view, "
                   "transmittance to there\n", distance);
        printf("%10s %11s  radiance at %g, %g, %g nm (W m^-2 sr^-1 nm^-1)    luminance (cd/m^2)",
               "zenith_deg", "azimuth_deg", wl[0], wl[1], wl[2]);
        printf("%s\n", have_distance ? "  transmittance" : "");
        for (int i = 0; i < n_views; i++) {
            printf("%10.3f %11.3f  %.6e %.6e %.6e  %.6e", views[i].zenith_deg,
                   views[i].azimuth_deg, views[i].L[0], views[i].L[1], views[i].L[2],
                   atmo_luminance_from_radiance(k, views[i].L));
            if (have_distance)
                printf("  %.6f %.6f %.6f", views[i].T[0], views[i].T[1], views[i].T[2]);
            printf("\n");
            if (is_reference)
                printf("%23s  +- %.1e %.1e %.1e (standard error)\n", "", views[i].se[0],
                       views[i].se[1], views[i].se[2]);
            if (is_reference && have_distance)
                printf("%23s  transmittance +- %.1e %.1e %.1e (standard error)\n", "",
                       views[i].T_se[0], views[i].T_se[1], views[i].T_se[2]);
        }
        if (irradiance)
            printf("irradiance on a horizontal surface (W m^-2 nm^-1): direct %.6e %.6e %.6e, "
                   "sky %.6e %.6e %.6e\n",
                   direct[0], direct[1], direct[2], sky[0], sky[1], sky[2]);
    }
cleanup_se:
    free(t_se);
    free(t_mean);
    free(distances);
    free(se);
cleanup:
    atmo_probe_close(&probe);
    atmo_plan_free(&plan);
    free(mean);
    free(rays);
    if (rc)
        fprintf(stderr, "atmo radiance: %s\n", e.msg);
    return rc;
}
