/* cmd_radiance.c — `atmo radiance`: the sky radiance of the scene's atmosphere for given view
 * directions, from any method, for users and tests.
 *
 * Scene: the defaults (clear air, no terrain or clouds), then --scene
 * FILE, then --set KEY=VALUE, --method M and --seed N in command-line order (the flags are one
 * table, cli_flags.h); --altitude-m, --sun-zenith-deg and --sun-azimuth-deg place
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
#include <stddef.h>
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
#include "cli_flags.h"
#include "commands.h"

#define RADIANCE_MAX_VIEWS 1024
#define RADIANCE_QUAD 16
#define DEG (M_PI / 180.0)

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

#define RADIANCE_MAX_SETS 256

/* The flags' destinations (radiance_flags), holding the defaults before parsing. */
typedef struct radiance_args {
    double altitude, sun_zenith, sun_azimuth, distance;
    int samples, json, irradiance, n_views, n_sets;
    const char *scene_file, *device;
    const char *sets[RADIANCE_MAX_SETS]; /* KEY=VALUE from --set, --method, --seed, in order */
    char set_text[RADIANCE_MAX_SETS][64]; /* --method's and --seed's assignments */
    radiance_view views[RADIANCE_MAX_VIEWS];
} radiance_args;

static int take_view(void *args, const cli_flag *f, const char *v, atmo_err *e)
{
    radiance_args *a = args;
    (void)f;
    if (a->n_views == RADIANCE_MAX_VIEWS)
        return atmo_fail(e, ATMO_ERR_USAGE, "at most %d --view options", RADIANCE_MAX_VIEWS);
    return parse_view(v, &a->views[a->n_views++], e);
}

/* --set KEY=VALUE, and --method, --seed as the assignments of their keys, in order */
static int take_set(void *args, const cli_flag *f, const char *v, atmo_err *e)
{
    radiance_args *a = args;
    if (a->n_sets == RADIANCE_MAX_SETS)
        return atmo_fail(e, ATMO_ERR_USAGE, "more than %d --set, --method and --seed options",
                         RADIANCE_MAX_SETS);
    if (f->key)
        snprintf(a->set_text[a->n_sets], sizeof a->set_text[0], "%s=%s", f->key, v);
    a->sets[a->n_sets] = f->key ? a->set_text[a->n_sets] : v;
    a->n_sets++;
    return ATMO_OK;
}

#define RADIANCE_FLAG(member) offsetof(radiance_args, member)

static const cli_flag radiance_flags[] = {
    {.type = CLI_FLOAT, .name = "--altitude-m", .metavar = "H", .min = 0.0, .max = 1e9,
     .offset = RADIANCE_FLAG(altitude), .def = "none: required",
     .help = "camera altitude above the ground in metres"},
    {.type = CLI_FLOAT, .name = "--sun-zenith-deg", .metavar = "S", .min = 0.0, .max = 180.0,
     .offset = RADIANCE_FLAG(sun_zenith), .def = "none: required", .help = "the sun's zenith angle"},
    {.type = CLI_FLOAT, .name = "--sun-azimuth-deg", .metavar = "A", .min = -360.0, .max = 360.0,
     .offset = RADIANCE_FLAG(sun_azimuth), .help = "the sun's azimuth"},
    {.type = CLI_STRING, .name = "--view", .metavar = "Z,A", .take = take_view,
     .def = "none: at least one, unless --irradiance",
     .help = "a view: zenith and azimuth in degrees (repeatable)"},
    {.type = CLI_ENUM, .name = "--method", .key = "atmosphere.method", .take = take_set,
     .help = "atmosphere method (auto: march with clouds or the observer, else fast)"},
    {.type = CLI_PATH, .name = "--scene", .offset = RADIANCE_FLAG(scene_file),
     .def = "none: the scene defaults (clear air, no terrain or clouds)",
     .help = "JSON scene file, read first wherever it stands"},
    {.type = CLI_STRING, .name = "--set", .metavar = "K=V", .take = take_set, .def = "none",
     .help = "override one parameter (repeatable, in order with --method and --seed)"},
    {.type = CLI_FLOAT, .name = "--distance-m", .metavar = "D", .min = 0.0, .max = 1e12,
     .open_min = 1, .offset = RADIANCE_FLAG(distance), .def = "off: the whole view",
     .help = "aerial perspective: each view ends at a black surface D metres away;\n"
             "prints the radiance in-scattered over [0, D] and the transmittance\n"
             "to the surface. A view that meets the ground or leaves the\n"
             "atmosphere before D gives its whole sky radiance (lit ground\n"
             "included) and the transmittance to the ground or to space"},
    {.type = CLI_BOOL, .name = "--irradiance", .offset = RADIANCE_FLAG(irradiance),
     .help = "add direct and sky irradiance on a horizontal surface (W m^-2 nm^-1)"},
    {.type = CLI_BOOL, .name = "--json", .offset = RADIANCE_FLAG(json),
     .help = "one JSON object instead of text"},
    {.type = CLI_INT, .name = "--samples", .min = 1, .max = 1 << 26, .offset = RADIANCE_FLAG(samples),
     .def = "65536 for reference, 64 otherwise", .help = "samples per view"},
    {.type = CLI_INT, .name = "--seed", .key = "image.seed", .take = take_set, .help = "random seed"},
    {.type = CLI_STRING, .name = "--device", .metavar = "D", .offset = RADIANCE_FLAG(device),
     .def = "$ATMO_DEVICE, else the first GPU, else the first device",
     .help = "OpenCL device by index or name part (atmo devices)"},
    {.type = CLI_END},
};

static const cli_command radiance_cli = {
    .name = "radiance",
    .synopsis = "--altitude-m H --sun-zenith-deg S [--sun-azimuth-deg A]\n"
                "                     --view Z,A [--view Z,A ...] [--method M] [--scene F] [--set K=V ...]\n"
                "                     [--distance-m D] [--irradiance] [--json] [--samples N] [--seed N]\n"
                "                     [--device D]",
    .about = "Prints, for each view (zenith Z and azimuth A in degrees, azimuth measured like the sun's),\n"
             "the spectral radiance of the sky at each render wavelength (W m^-2 sr^-1 nm^-1, sun disc\n"
             "excluded) and its luminance (cd/m^2).\n",
    .flags = radiance_flags,
};

/* What the probe computes: the rays (views, then the irradiance quadrature) and their means. */
typedef struct radiance_run {
    int n_views, n_quad, samples;
    float4 *rays;
    float *distances;
    double (*mean)[3], (*se)[3], (*t_mean)[3], (*t_se)[3];
    double gx[RADIANCE_QUAD], gw[RADIANCE_QUAD];
    double r, sun[3], mu_s;
    double sun_vis[1][3]; /* V, the sun's visibility at the camera (with --irradiance) */
} radiance_run;

static void radiance_run_free(radiance_run *run)
{
    free(run->t_se);
    free(run->t_mean);
    free(run->distances);
    free(run->se);
    free(run->mean);
    free(run->rays);
}

/* The scene: the defaults (clear air, no terrain or clouds) or the file, the assignments in
 * order, the sun. */
static int radiance_scene(const radiance_args *a, atmo_scene *scene, atmo_err *e)
{
    char number[64];
    int rc;
    atmo_scene_defaults(scene);
    rc = a->scene_file ? atmo_scene_load_json(scene, a->scene_file, e) : ATMO_OK;
    for (int i = 0; i < a->n_sets && !rc; i++)
        rc = atmo_scene_assign(scene, a->sets[i], "--set", e);
    if (rc)
        return rc;
    if (a->altitude < 0.0 || a->sun_zenith < 0.0)
        return atmo_fail(e, ATMO_ERR_USAGE,
                         "--altitude-m and --sun-zenith-deg are required (atmo radiance --help)");
    if (a->n_views == 0 && !a->irradiance)
        return atmo_fail(e, ATMO_ERR_USAGE,
                         "give at least one --view ZENITH,AZIMUTH (or --irradiance)");
    snprintf(number, sizeof number, "%.17g", a->sun_zenith);
    if ((rc = atmo_scene_set(scene, "sun.zenith_deg", number, "--sun-zenith-deg", e)))
        return rc;
    snprintf(number, sizeof number, "%.17g", a->sun_azimuth);
    return atmo_scene_set(scene, "sun.azimuth_deg", number, "--sun-azimuth-deg", e);
}

/* rays: the views, then the sky-irradiance quadrature directions */
static int radiance_rays(const radiance_args *a, const atmo_atmosphere *atm, radiance_run *run,
                         atmo_err *e)
{
    int n_views = a->n_views, n_rays = n_views + run->n_quad;
    run->n_views = n_views;
    run->r = atm->bottom_radius_m + a->altitude;
    view_direction(a->sun_zenith, a->sun_azimuth, run->sun);
    run->mu_s = run->sun[1];
    size_t nr = n_rays > 0 ? (size_t)n_rays : 1, nv = n_views > 0 ? (size_t)n_views : 1;
    run->rays = malloc(sizeof(float4) * nr);
    run->distances = malloc(sizeof(float) * nv);
    run->mean = malloc(sizeof *run->mean * nr);
    run->se = malloc(sizeof *run->se * nv);
    run->t_mean = malloc(sizeof *run->t_mean * nv);
    run->t_se = malloc(sizeof *run->t_se * nv);
    if (!run->rays || !run->mean || !run->se || !run->distances || !run->t_mean || !run->t_se)
        return atmo_fail(e, ATMO_ERR_RUNTIME, "out of memory");
    double r = run->r, mu_s = run->mu_s, *sun = run->sun;
    for (int i = 0; i < n_views; i++) {
        double d[3];
        view_direction(a->views[i].zenith_deg, a->views[i].azimuth_deg, d);
        float4 q = {(float)r, (float)d[1], (float)mu_s,
                    (float)(d[0] * sun[0] + d[1] * sun[1] + d[2] * sun[2])};
        run->rays[i] = q;
        run->distances[i] = (float)a->distance;
    }
    gauss_legendre01(RADIANCE_QUAD, run->gx, run->gw);
    for (int i = 0; i < RADIANCE_QUAD && run->n_quad; i++)
        for (int j = 0; j < RADIANCE_QUAD; j++) {
            double mu = run->gx[i], phi = M_PI * (j + 0.5) / RADIANCE_QUAD, s = sqrt(1.0 - mu * mu);
            /* azimuth measured from the sun's */
            double nu = s * sqrt(fmax(1.0 - mu_s * mu_s, 0.0)) * cos(phi) + mu * mu_s;
            float4 q = {(float)r, (float)mu, (float)mu_s, (float)nu};
            run->rays[n_views + i * RADIANCE_QUAD + j] = q;
        }
    return ATMO_OK;
}

/* The views' means (or segments with --distance-m) and the quadrature's, on the device. */
static int radiance_probe(const radiance_args *a, atmo_probe *probe, radiance_run *run,
                          atmo_err *e)
{
    int rc = ATMO_OK, n_views = run->n_views, samples = run->samples;
    if (n_views && a->distance <= 0.0 &&
        (rc = atmo_probe_rays(probe, run->rays, n_views, samples, run->mean, run->se, e)))
        return rc;
    if (n_views && a->distance > 0.0 &&
        (rc = atmo_probe_segments(probe, run->rays, run->distances, n_views, samples, run->mean,
                                  run->se, run->t_mean, run->t_se, e)))
        return rc;
    float4 camera_up = {(float)run->r, 1.0f, (float)run->mu_s, (float)run->mu_s};
    if (run->n_quad && (rc = atmo_probe_sun(probe, &camera_up, 1, run->sun_vis, e)))
        return rc;
    int quad_samples = samples / 64 > 0 ? samples / 64 : 1;
    if (run->n_quad && (rc = atmo_probe_rays(probe, run->rays + n_views, run->n_quad,
                                             quad_samples, run->mean + n_views, NULL, e)))
        return rc;
    return ATMO_OK;
}

/* direct = E T_sun V max(mu_s, 0); sky = the quadrature of L cos(theta) over the hemisphere */
static void radiance_irradiance(const atmo_atmosphere *atm, const radiance_run *run,
                                double direct[3], double sky[3])
{
    int n_views = run->n_views;
    atmo_ref_direct_irradiance(atm, run->r, run->mu_s, direct);
    for (int c = 0; c < 3; c++)
        direct[c] *= run->sun_vis[0][c];
    for (int i = 0; i < RADIANCE_QUAD; i++)
        for (int j = 0; j < RADIANCE_QUAD; j++)
            for (int c = 0; c < 3; c++) /* 2 (symmetry) * pi / n (midpoint) * w mu L */
                sky[c] += 2.0 * M_PI / RADIANCE_QUAD * run->gw[i] * run->gx[i] *
                          run->mean[n_views + i * RADIANCE_QUAD + j][c];
}

typedef struct radiance_result {
    const char *method, *device;
    int samples, is_reference;
    double k[3], direct[3], sky[3];
    const double *wl;
    int seed;
} radiance_result;

static int radiance_print_json(const radiance_args *a, const radiance_result *res, atmo_err *e)
{
    cJSON *root = cJSON_CreateObject();
    json_vec(root, "wavelengths_nm", res->wl);
    cJSON_AddStringToObject(root, "method", res->method);
    cJSON_AddNumberToObject(root, "altitude_m", a->altitude);
    cJSON_AddNumberToObject(root, "sun_zenith_deg", a->sun_zenith);
    cJSON_AddNumberToObject(root, "sun_azimuth_deg", a->sun_azimuth);
    if (a->distance > 0.0)
        cJSON_AddNumberToObject(root, "distance_m", a->distance);
    cJSON_AddNumberToObject(root, "samples", res->samples);
    cJSON_AddNumberToObject(root, "seed", res->seed);
    cJSON_AddStringToObject(root, "device", res->device);
    cJSON *arr = cJSON_AddArrayToObject(root, "views");
    for (int i = 0; i < a->n_views; i++) {
        const radiance_view *v = &a->views[i];
        cJSON *o = cJSON_CreateObject();
        cJSON_AddNumberToObject(o, "zenith_deg", v->zenith_deg);
        cJSON_AddNumberToObject(o, "azimuth_deg", v->azimuth_deg);
        json_vec(o, "radiance", v->L);
        json_vec(o, "radiance_standard_error", v->se);
        cJSON_AddNumberToObject(o, "luminance_cd_m2", atmo_luminance_from_radiance(res->k, v->L));
        if (a->distance > 0.0) {
            json_vec(o, "transmittance", v->T);
            json_vec(o, "transmittance_standard_error", v->T_se);
        }
        cJSON_AddItemToArray(arr, o);
    }
    if (a->irradiance) {
        cJSON *irr = cJSON_AddObjectToObject(root, "irradiance");
        json_vec(irr, "direct", res->direct);
        json_vec(irr, "sky", res->sky);
    }
    char *text = cJSON_Print(root);
    cJSON_Delete(root);
    if (!text)
        return atmo_fail(e, ATMO_ERR_RUNTIME, "out of memory printing JSON");
    printf("%s\n", text);
    free(text);
    return ATMO_OK;
}

static void radiance_print_text(const radiance_args *a, const radiance_result *res)
{
    const double *wl = res->wl;
    int have_distance = a->distance > 0.0;
    printf("method %s, altitude %g m, sun zenith %g deg azimuth %g deg, %d sample%s per view\n",
           res->method, a->altitude, a->sun_zenith, a->sun_azimuth, res->samples,
           res->samples == 1 ? "" : "s");
    if (have_distance)
        printf("aerial perspective: radiance in-scattered over the first %g m of each view, "
               "transmittance to there\n", a->distance);
    printf("%10s %11s  radiance at %g, %g, %g nm (W m^-2 sr^-1 nm^-1)    luminance (cd/m^2)",
           "zenith_deg", "azimuth_deg", wl[0], wl[1], wl[2]);
    printf("%s\n", have_distance ? "  transmittance" : "");
    for (int i = 0; i < a->n_views; i++) {
        const radiance_view *v = &a->views[i];
        printf("%10.3f %11.3f  %.6e %.6e %.6e  %.6e", v->zenith_deg, v->azimuth_deg, v->L[0],
               v->L[1], v->L[2], atmo_luminance_from_radiance(res->k, v->L));
        if (have_distance)
            printf("  %.6f %.6f %.6f", v->T[0], v->T[1], v->T[2]);
        printf("\n");
        if (res->is_reference)
            printf("%23s  +- %.1e %.1e %.1e (standard error)\n", "", v->se[0], v->se[1], v->se[2]);
        if (res->is_reference && have_distance)
            printf("%23s  transmittance +- %.1e %.1e %.1e (standard error)\n", "", v->T_se[0],
                   v->T_se[1], v->T_se[2]);
    }
    if (a->irradiance)
        printf("irradiance on a horizontal surface (W m^-2 nm^-1): direct %.6e %.6e %.6e, "
               "sky %.6e %.6e %.6e\n",
               res->direct[0], res->direct[1], res->direct[2], res->sky[0], res->sky[1],
               res->sky[2]);
}

/* The probe's means into the views, and the irradiance. */
static void radiance_collect(radiance_args *a, const atmo_scene *scene, const atmo_plan *plan,
                             const radiance_run *run, radiance_result *res)
{
    atmo_luminance_factors(scene->render.wavelengths_nm, -3.0, res->k);
    if (a->irradiance)
        radiance_irradiance(&plan->atmosphere, run, res->direct, res->sky);
    for (int i = 0; i < a->n_views; i++)
        for (int c = 0; c < 3; c++) {
            radiance_view *v = &a->views[i];
            v->L[c] = run->mean[i][c], v->se[c] = run->se[i][c];
            v->T[c] = a->distance > 0.0 ? run->t_mean[i][c] : 0.0;
            v->T_se[c] = a->distance > 0.0 ? run->t_se[i][c] : 0.0;
        }
}

int cmd_radiance(int argc, char **argv)
{
    atmo_err e = {{0}};
    atmo_scene scene;
    atmo_plan plan = {0};
    atmo_probe probe = {0};
    radiance_run run = {0};
    radiance_result res = {0};
    static radiance_args a;
    int rc;
    memset(&a, 0, sizeof a);
    a.altitude = a.sun_zenith = -1.0; /* required: out of range until given */
    if (!cli_parse(&radiance_cli, &a, argc, argv, NULL, NULL, &rc))
        return rc;
    if ((rc = radiance_scene(&a, &scene, &e)) || (rc = atmo_plan_make(&scene, &plan, &e)))
        goto cleanup;
    res.is_reference = scene.atmosphere.method == ATMO_METHOD_REFERENCE;
    run.samples = a.samples ? a.samples : res.is_reference ? 65536 : 64;
    run.samples = (run.samples + ATMO_PROBE_BATCHES - 1) / ATMO_PROBE_BATCHES * ATMO_PROBE_BATCHES;
    run.n_quad = a.irradiance ? RADIANCE_QUAD * RADIANCE_QUAD : 0;
    if ((rc = radiance_rays(&a, &plan.atmosphere, &run, &e)) ||
        (rc = atmo_probe_open(&probe, &plan, a.device, &e)) ||
        (rc = radiance_probe(&a, &probe, &run, &e)))
        goto cleanup;
    radiance_collect(&a, &scene, &plan, &run, &res);
    res.method = plan.method;
    res.device = atmo_session_get_info(probe.session)->device_name;
    res.samples = run.samples;
    res.wl = scene.render.wavelengths_nm;
    res.seed = scene.image.seed;
    if (a.json)
        rc = radiance_print_json(&a, &res, &e);
    else
        radiance_print_text(&a, &res);
cleanup:
    atmo_probe_close(&probe);
    atmo_plan_free(&plan);
    radiance_run_free(&run);
    return rc ? cli_fail(&radiance_cli, rc, &e) : ATMO_OK;
}
