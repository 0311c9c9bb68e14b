/* cmd_mie.c — `atmo mie`: Lorenz–Mie optics of one droplet or a droplet size distribution.
 *
 *   atmo mie (--radius-um R | --dsd NAME|SPEC) --wavelength-nm L [--wavelength-nm L ...]
 *            [--index N+Ki] [--angles-deg LIST] [--table out.csv] [--chart out.svg] [--json]
 *            [--tolerance T | --radius-step DX] [--no-cache]
 *
 * Prints Q_ext, Q_sca, Q_back, g, albedo, and for a distribution sigma_ext per liquid water
 * content (m^2/g), r_eff and v_eff. Without --index the index of water comes from data/
 * (n: Daimon & Masumura 2007, k: Segelstein 1981; host/mie_water.c). --table writes the
 * 4pi-normalised P on the table grid (finest needed by the shortest wavelength) as CSV:
 * theta_deg, then one P column per wavelength. --json prints {"convention": ..., "results": [...]}
 * with P (and S1, S2 for one radius) at --angles-deg (default: the table grid).
 * Sign convention: the index is n + ik with k >= 0 absorbing; S1, S2 are in MIEV0's convention
 * (m = n - ik), the complex conjugates of Bohren & Huffman's. --chart draws log P against theta
 * per wavelength with the corona, fog bow and glory ranges shaded (gnuplot, host/mie_plot.c;
 * checked for before any work, like the --table and --chart paths: output_paths.h). Tables on the grid come from the on-disk cache when built before
 * with the same parameters (host/mie_cache.c; --no-cache rebuilds and does not store).
 * The radius integral of a distribution is refined until it has converged to --tolerance
 * (host/mie/mie_radius.c); --radius-step fixes the step instead. The flags are one table
 * (cli_flags.h); --table and --chart do not replace an existing file without --force. */
#include <cjson/cJSON.h>
#include <math.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "atmo/fileio.h"
#include "atmo/gnuplot.h"
#include "atmo/mie.h"
#include "cli_flags.h"
#include "commands.h"
#include "output_paths.h"
#include "overwrite.h"

#define MIE_CLI_MAX_WAVELENGTHS 64
#define MIE_CLI_PI 3.14159265358979323846
#define MIE_CLI_CONVENTION                                                                     \
    "index n + ik, k >= 0 absorbing; S1, S2 in Wiscombe MIEV0 convention (m = n - ik), the "    \
    "complex conjugates of Bohren & Huffman's; P 4pi-normalised"

static int mie_parse_index(const char *s, double *n, double *k, atmo_err *e)
{
    char *end;
    *n = strtod(s, &end);
    *k = 0.0;
    if (end == s)
        goto bad;
    if (*end == '+') {
        const char *p = end + 1;
        *k = strtod(p, &end);
        if (end == p || strcmp(end, "i") != 0)
            goto bad;
    } else if (*end != '\0') {
        goto bad;
    }
    if (!(*n > 0.0 && *n < 100.0 && *k >= 0.0 && *k < 100.0))
        goto bad;
    return ATMO_OK;
bad:
    return atmo_fail(e, ATMO_ERR_USAGE,
                     "--index '%s' not understood; write N+Ki with N > 0 and absorption K >= 0, "
                     "e.g. 1.33+1e-8i", s);
}

static int mie_parse_angles(const char *s, double **out, int *count, atmo_err *e)
{
    int cap = 1;
    for (const char *p = s; *p; p++)
        cap += *p == ',';
    double *a = malloc(sizeof *a * (size_t)cap);
    if (!a)
        return atmo_fail(e, ATMO_ERR_RUNTIME, "out of memory");
    int n = 0;
    const char *p = s;
    while (1) {
        char *end;
        double v = strtod(p, &end);
        if (end == p || !(v >= 0.0 && v <= 180.0) || (*end != ',' && *end != '\0')) {
            free(a);
            return atmo_fail(e, ATMO_ERR_USAGE, "--angles-deg '%s': need comma-separated angles "
                             "in [0, 180] degrees", s);
        }
        a[n++] = v;
        if (*end == '\0')
            break;
        p = end + 1;
    }
    *out = a;
    *count = n;
    return ATMO_OK;
}

static cJSON *mie_array(const double *v, int n)
{
    cJSON *a = cJSON_CreateArray();
    for (int i = 0; i < n; i++)
        cJSON_AddItemToArray(a, cJSON_CreateNumber(v[i]));
    return a;
}

static cJSON *mie_complex_array(const double complex *v, int n)
{
    cJSON *a = cJSON_CreateArray();
    for (int i = 0; i < n; i++) {
        double pair[2] = {creal(v[i]), cimag(v[i])};
        cJSON_AddItemToArray(a, mie_array(pair, 2));
    }
    return a;
}

/* The flags' destinations (mie_flags), holding the defaults before parsing. */
typedef struct mie_args {
    int json, no_cache, force, nl, have_index, have_dsd, n_ang;
    double lambda[MIE_CLI_MAX_WAVELENGTHS], idx_n, idx_k, tolerance, radius_step;
    double *angles;
    const char *table_path, *chart_path, *dsd_text;
    mie_dsd dsd;
} mie_args;

static int take_radius(void *args, const cli_flag *f, const char *v, atmo_err *e)
{
    mie_args *a = args;
    char *end;
    (void)f;
    a->dsd = (mie_dsd){.kind = MIE_DSD_MONO, .radius_um = strtod(v, &end)};
    a->dsd_text = v;
    a->have_dsd++;
    /* its range depends on the wavelengths: checked once they are all known */
    if (*end || end == v)
        return atmo_fail(e, ATMO_ERR_USAGE, "--radius-um '%s' is not a number", v);
    return ATMO_OK;
}

static int take_dsd(void *args, const cli_flag *f, const char *v, atmo_err *e)
{
    mie_args *a = args;
    (void)f;
    a->dsd_text = v;
    a->have_dsd++;
    return mie_dsd_parse(v, &a->dsd, e);
}

static int take_wavelength(void *args, const cli_flag *f, const char *v, atmo_err *e)
{
    mie_args *a = args;
    (void)f;
    if (a->nl == MIE_CLI_MAX_WAVELENGTHS)
        return atmo_fail(e, ATMO_ERR_USAGE, "more than %d --wavelength-nm options",
                         MIE_CLI_MAX_WAVELENGTHS);
    a->lambda[a->nl++] = strtod(v, NULL);
    return ATMO_OK;
}

static int take_index(void *args, const cli_flag *f, const char *v, atmo_err *e)
{
    mie_args *a = args;
    (void)f;
    a->have_index = 1;
    return mie_parse_index(v, &a->idx_n, &a->idx_k, e);
}

static int take_angles(void *args, const cli_flag *f, const char *v, atmo_err *e)
{
    mie_args *a = args;
    (void)f;
    free(a->angles);
    a->angles = NULL;
    return mie_parse_angles(v, &a->angles, &a->n_ang, e);
}

#define MIE_FLAG(member) offsetof(mie_args, member)

static const cli_flag mie_flags[] = {
    {.type = CLI_STRING, .name = "--radius-um", .metavar = "R", .take = take_radius,
     .help = "one droplet's radius: 2 pi R / lambda in [1e-6, 2e4] and R <= 5000 um\n"
             "(at 550 nm: 8.75e-8 to 1750 um)"},
    {.type = CLI_STRING, .name = "--dsd", .metavar = "NAME|SPEC", .take = take_dsd,
     .help = "preset (cumulus stratus fog corona thesis-disperse thesis-uniform) or\n"
             "mono:R | gamma:REFF,VEFF | lognormal:RG,SIGMA_G | modgamma:ALPHA,B,GAMMA\n"
             "(radii in um; optional ,max=RMAX cut)"},
    {.type = CLI_FLOAT, .name = "--wavelength-nm", .metavar = "L", .min = 100.0, .max = 1e5,
     .take = take_wavelength, .help = "a wavelength in nm (repeatable, at least one)"},
    {.type = CLI_STRING, .name = "--index", .metavar = "N+Ki", .take = take_index,
     .def = "water (n Daimon & Masumura 2007, k Segelstein 1981)",
     .help = "relative refractive index, e.g. 1.33+1e-8i (k >= 0 absorbs)"},
    {.type = CLI_STRING, .name = "--angles-deg", .metavar = "LIST", .take = take_angles,
     .def = "the table grid", .help = "comma-separated scattering angles for P (and S1, S2)"},
    {.type = CLI_PATH, .name = "--table", .offset = MIE_FLAG(table_path), .def = "none",
     .help = "write theta_deg and P per wavelength as CSV"},
    {.type = CLI_PATH, .name = "--chart", .offset = MIE_FLAG(chart_path), .def = "none",
     .help = "draw log P against theta per wavelength as SVG (needs gnuplot)"},
    {.type = CLI_BOOL, .name = "--force", .offset = MIE_FLAG(force),
     .help = "overwrite --table and --chart if they exist"},
    {.type = CLI_FLOAT, .name = "--tolerance", .metavar = "T", .min = 1e-6, .max = 1.0,
     .offset = MIE_FLAG(tolerance), .def = "1e-3",
     .help = "accuracy of the radius integral of a distribution: the\n"
             "size-parameter step halves from 0.125 until P changes by <= T RMS over\n"
             "angle and 5 T at every angle; the default tables are within 1e-3 RMS and\n"
             "5e-3 at every angle (fog bow and glory included) of the converged integral"},
    {.type = CLI_FLOAT, .name = "--radius-step", .metavar = "DX", .min = 1e-6, .max = 1.0,
     .offset = MIE_FLAG(radius_step), .def = "off: converged to --tolerance",
     .help = "fixed size-parameter step instead (e.g. 0.5: fast, ~1 % RMS error)"},
    {.type = CLI_BOOL, .name = "--no-cache", .offset = MIE_FLAG(no_cache),
     .help = "build the phase tables even if cached (and do not store them)"},
    {.type = CLI_BOOL, .name = "--json", .offset = MIE_FLAG(json),
     .help = "one JSON object; " MIE_CLI_CONVENTION},
    {.type = CLI_END},
};

static const cli_command mie_cli = {
    .name = "mie",
    .synopsis = "(--radius-um R | --dsd NAME|SPEC) --wavelength-nm L [--wavelength-nm L ...]\n"
                "                [--index N+Ki] [--angles-deg LIST] [--table out.csv] [--chart out.svg]\n"
                "                [--tolerance T | --radius-step DX] [--json] [--no-cache]",
    .about = "Lorenz-Mie optics of one water droplet or a droplet size distribution.\n",
    .flags = mie_flags,
};

/* What the wavelengths share: the angle grid, the output angles and the buffers. */
typedef struct mie_job {
    mie_table_options opt;
    double *grid, *mu, *P, *tableP;
    double complex *s1, *s2;
    const double *out_ang;
    int n_grid, n_out, need_grid;
    output_paths files;
    cJSON *root, *results;
} mie_job;

static void mie_job_free(mie_job *j)
{
    output_paths_free(&j->files);
    cJSON_Delete(j->root);
    free(j->grid);
    free(j->mu);
    free(j->P);
    free(j->s1);
    free(j->s2);
    free(j->tableP);
}

/* The arguments together, and every output writable, before any work. */
static int mie_check_args(const mie_args *a, mie_job *j, atmo_err *e)
{
    int rc;
    if (a->have_dsd != 1 || a->nl == 0)
        return atmo_fail(e, ATMO_ERR_USAGE, "give exactly one of --radius-um or --dsd, and at "
                         "least one --wavelength-nm; see atmo mie --help");
    if ((a->table_path && (rc = output_paths_add(&j->files, "--table", a->table_path, e))) ||
        (a->chart_path && (rc = output_paths_add(&j->files, "--chart", a->chart_path, e))) ||
        (a->table_path && (rc = overwrite_check("--table", a->table_path, a->force, e))) ||
        (a->chart_path && (rc = overwrite_check("--chart", a->chart_path, a->force, e))))
        return rc;
    if (a->chart_path && !atmo_gnuplot_available())
        return atmo_fail(e, ATMO_ERR_RUNTIME, "--chart needs gnuplot, which is not on PATH; "
                         "install gnuplot-nox (setup.sh does) or leave out --chart");
    if (a->tolerance > 0.0 && a->radius_step > 0.0)
        return atmo_fail(e, ATMO_ERR_USAGE, "give --tolerance or --radius-step, not both");
    return ATMO_OK;
}

/* one grid for all wavelengths, fine enough for the shortest; the drops' radii within the
 * solver's range at every wavelength (the largest at the shortest, the smallest at the
 * longest); the buffers for the output angles */
static int mie_prepare(const mie_args *a, mie_job *j, atmo_err *e)
{
    int rc;
    double r0, r1, lmin = a->lambda[0], lmax = a->lambda[0];
    for (int i = 1; i < a->nl; i++)
        lmin = fmin(lmin, a->lambda[i]), lmax = fmax(lmax, a->lambda[i]);
    if (a->dsd.kind == MIE_DSD_MONO && ((rc = mie_check_radius(a->dsd.radius_um, lmin, e)) ||
                                        (rc = mie_check_radius(a->dsd.radius_um, lmax, e))))
        return rc;
    if ((rc = mie_dsd_range(&a->dsd, &r0, &r1, e)) || (rc = mie_check_radius(r1, lmin, e)) ||
        (rc = mie_check_radius(r0, lmax, e)))
        return rc;
    double xmax = 2.0 * MIE_CLI_PI * r1 / (lmin * 1e-3);
    j->opt = (mie_table_options){.fine_step_deg = fmin(0.1, 10.0 / fmax(xmax, 1.0)),
                                 .tolerance = a->tolerance, .max_dx = a->radius_step};
    if ((rc = mie_angle_grid(xmax, &j->opt, &j->grid, &j->n_grid, e)))
        return rc;
    j->out_ang = a->angles ? a->angles : j->grid;
    j->n_out = a->angles ? a->n_ang : j->n_grid;
    j->mu = malloc(sizeof *j->mu * (size_t)j->n_out);
    j->P = malloc(sizeof *j->P * (size_t)j->n_out);
    j->s1 = malloc(sizeof *j->s1 * (size_t)j->n_out);
    j->s2 = malloc(sizeof *j->s2 * (size_t)j->n_out);
    j->need_grid = a->table_path || a->chart_path;
    j->tableP = j->need_grid ? malloc(sizeof *j->tableP * (size_t)j->n_grid * (size_t)a->nl)
                             : NULL;
    if (!j->mu || !j->P || !j->s1 || !j->s2 || (j->need_grid && !j->tableP))
        return atmo_fail(e, ATMO_ERR_RUNTIME, "out of memory for %d angles", j->n_out);
    for (int k = 0; k < j->n_out; k++)
        j->mu[k] = cos(j->out_ang[k] * MIE_CLI_PI / 180.0);
    j->root = cJSON_CreateObject();
    cJSON_AddStringToObject(j->root, "convention", MIE_CLI_CONVENTION);
    j->results = cJSON_AddArrayToObject(j->root, "results");
    return ATMO_OK;
}

/* Wavelength w: the bulk optics b and P at the output angles (S1, S2 for one drop), the table's
 * P kept for --table and --chart. */
static int mie_compute(const mie_args *a, mie_job *j, int w, double n, double k, mie_bulk *b,
                       atmo_err *e)
{
    int rc;
    double lambda = a->lambda[w];
    if (j->need_grid || !a->angles) { /* the table (cached) gives P on the grid and the bulk */
        mie_table t;
        if ((rc = mie_table_get(&a->dsd, lambda, n, k, &j->opt, !a->no_cache, &t, NULL, e)))
            return rc;
        if (t.n != j->n_grid) {
            mie_table_free(&t);
            return atmo_fail(e, ATMO_ERR_RUNTIME, "internal: table grid of %d angles, expected "
                             "%d", t.n, j->n_grid);
        }
        *b = t.bulk;
        if (j->need_grid)
            memcpy(j->tableP + (size_t)w * j->n_grid, t.P, sizeof *t.P * (size_t)j->n_grid);
        if (!a->angles)
            memcpy(j->P, t.P, sizeof *t.P * (size_t)j->n_grid);
        mie_table_free(&t);
    }
    if (a->angles && (rc = mie_dsd_integrate(&a->dsd, lambda, n, k, j->opt.max_dx,
                                             j->opt.tolerance, j->n_out, j->mu, j->P, b, e)))
        return rc;
    mie_efficiencies q = {0};
    if (a->dsd.kind == MIE_DSD_MONO)
        return mie_sphere(2.0 * MIE_CLI_PI * a->dsd.radius_um / (lambda * 1e-3), n, k,
                          MIE_DN_LENTZ, j->n_out, j->mu, j->s1, j->s2, &q, e);
    return ATMO_OK;
}

/* Wavelength w's result into the JSON; with text output, its line. */
static void mie_report(const mie_args *a, const mie_job *j, int w, double n, double k,
                       const mie_bulk *b)
{
    double lambda = a->lambda[w];
    int mono = a->dsd.kind == MIE_DSD_MONO;
    cJSON *r = cJSON_CreateObject();
    cJSON_AddItemToArray(j->results, r);
    cJSON_AddNumberToObject(r, "wavelength_nm", lambda);
    double nk[2] = {n, k};
    cJSON_AddItemToObject(r, "index", mie_array(nk, 2));
    cJSON_AddNumberToObject(r, "Qext", b->qext);
    cJSON_AddNumberToObject(r, "Qsca", b->qsca);
    cJSON_AddNumberToObject(r, "Qback", b->qback);
    cJSON_AddNumberToObject(r, "g", b->g);
    cJSON_AddNumberToObject(r, "albedo", b->albedo);
    if (mono) {
        cJSON_AddNumberToObject(r, "x", 2.0 * MIE_CLI_PI * a->dsd.radius_um / (lambda * 1e-3));
    } else {
        cJSON_AddNumberToObject(r, "sigma_ext_per_lwc", b->sigma_ext_per_lwc);
        cJSON_AddNumberToObject(r, "r_eff_um", b->r_eff_um);
        cJSON_AddNumberToObject(r, "v_eff", b->v_eff);
        cJSON_AddNumberToObject(r, "n_radii", b->n_radii);
        cJSON_AddNumberToObject(r, "radius_step_dx", b->dx);
        if (b->err_rms >= 0.0) {
            cJSON_AddNumberToObject(r, "error_estimate_rms", b->err_rms);
            cJSON_AddNumberToObject(r, "error_estimate_max", b->err_max);
        }
    }
    cJSON_AddItemToObject(r, "angles_deg", mie_array(j->out_ang, j->n_out));
    cJSON_AddItemToObject(r, "P", mie_array(j->P, j->n_out));
    if (mono) {
        cJSON_AddItemToObject(r, "S1", mie_complex_array(j->s1, j->n_out));
        cJSON_AddItemToObject(r, "S2", mie_complex_array(j->s2, j->n_out));
    }
    if (a->json)
        return;
    printf("lambda %g nm  m = %.6f + %.3gi  Qext %.7g  Qsca %.7g  Qback %.7g  g %.7g  "
           "albedo %.10g", lambda, n, k, b->qext, b->qsca, b->qback, b->g, b->albedo);
    if (!mono) {
        printf("  sigma_ext/LWC %.5g m^2/g  r_eff %.4g um  v_eff %.4g  radii %d (dx %.4g",
               b->sigma_ext_per_lwc, b->r_eff_um, b->v_eff, b->n_radii, b->dx);
        if (b->err_rms >= 0.0)
            printf(", last halving changed P by %.1e RMS, %.1e max)", b->err_rms, b->err_max);
        else
            printf(", fixed)");
    }
    printf("\n");
}

/* --table: theta_deg, then one P column per wavelength, written atomically */
static int mie_write_table(const mie_args *a, const mie_job *j, atmo_err *e)
{
    char tmp[ATMO_TMP_PATH_MAX];
    FILE *tf = atmo_atomic_open(a->table_path, tmp, e);
    if (!tf)
        return ATMO_ERR_RUNTIME;
    fprintf(tf, "theta_deg");
    for (int w = 0; w < a->nl; w++)
        fprintf(tf, ",P_%gnm", a->lambda[w]);
    fprintf(tf, "\n");
    for (int k = 0; k < j->n_grid; k++) {
        fprintf(tf, "%.6f", j->grid[k]);
        for (int w = 0; w < a->nl; w++)
            fprintf(tf, ",%.9g", j->tableP[(size_t)w * j->n_grid + k]);
        fprintf(tf, "\n");
    }
    return atmo_atomic_commit(tf, tmp, a->table_path, e);
}

/* Every wavelength, then the JSON, the table and the chart. */
static int mie_run(const mie_args *a, mie_job *j, atmo_err *e)
{
    int rc;
    for (int w = 0; w < a->nl; w++) {
        double n = a->idx_n, k = a->idx_k;
        mie_bulk b;
        if ((!a->have_index && (rc = mie_water_index(a->lambda[w], &n, &k, e))) ||
            (rc = mie_compute(a, j, w, n, k, &b, e)))
            return rc;
        mie_report(a, j, w, n, k, &b);
    }
    if (a->json) {
        char *text = cJSON_PrintUnformatted(j->root);
        if (!text)
            return atmo_fail(e, ATMO_ERR_RUNTIME, "out of memory printing JSON");
        puts(text);
        free(text);
    }
    if (a->table_path && (rc = mie_write_table(a, j, e)))
        return rc;
    if (a->chart_path) {
        char title[512];
        snprintf(title, sizeof title, "Mie phase function, %s %s",
                 a->dsd.kind == MIE_DSD_MONO ? "radius (um)" : "drops", a->dsd_text);
        return mie_chart_svg(a->chart_path, title, j->grid, j->n_grid, j->tableP, a->lambda,
                             a->nl, e);
    }
    return ATMO_OK;
}

int cmd_mie(int argc, char **argv)
{
    atmo_err e = {{0}};
    mie_args a = {0};
    mie_job j = {0};
    int rc;
    if (!cli_parse(&mie_cli, &a, argc, argv, NULL, NULL, &rc)) {
        free(a.angles);
        return rc;
    }
    if (!(rc = mie_check_args(&a, &j, &e)) && !(rc = mie_prepare(&a, &j, &e)))
        rc = mie_run(&a, &j, &e);
    if (rc)
        cli_fail(&mie_cli, rc, &e);
    mie_job_free(&j);
    free(a.angles);
    return rc;
}
