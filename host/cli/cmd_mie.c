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
 * (host/mie/mie_radius.c); --radius-step fixes the step instead. */
#include <cjson/cJSON.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "atmo/fileio.h"
#include "atmo/gnuplot.h"
#include "atmo/mie.h"
#include "commands.h"
#include "output_paths.h"

#define MIE_CLI_MAX_WAVELENGTHS 64
#define MIE_CLI_PI 3.14159265358979323846
#define MIE_CLI_CONVENTION                                                                     \
    "index n + ik, k >= 0 absorbing; S1, S2 in Wiscombe MIEV0 convention (m = n - ik), the "    \
    "complex conjugates of Bohren & Huffman's; P 4pi-normalised"

static void mie_usage(FILE *f)
{
    fprintf(f,
            "usage: atmo mie (--radius-um R | --dsd NAME|SPEC) --wavelength-nm L [--wavelength-nm L ...]\n"
            "                [--index N+Ki] [--angles-deg LIST] [--table out.csv] [--chart out.svg]\n"
            "                [--tolerance T | --radius-step DX] [--json] [--no-cache]\n\n"
            "Lorenz-Mie optics of one water droplet or a droplet size distribution.\n"
            "  --radius-um  one droplet's radius: 2 pi R / lambda in [1e-6, 2e4] and R <= 5000 um\n"
            "               (at 550 nm: 8.75e-8 to 1750 um)\n"
            "  --dsd        preset (cumulus stratus fog corona thesis-disperse thesis-uniform) or\n"
            "               mono:R | gamma:REFF,VEFF | lognormal:RG,SIGMA_G | modgamma:ALPHA,B,GAMMA\n"
            "               (radii in um; optional ,max=RMAX cut)\n"
            "  --index      relative refractive index, e.g. 1.33+1e-8i (k >= 0 absorbs); default:\n"
            "               water (n Daimon & Masumura 2007, k Segelstein 1981)\n"
            "  --angles-deg comma-separated scattering angles for P (and S1, S2); default: table grid\n"
            "  --table      write theta_deg and P per wavelength as CSV\n"
            "  --chart      draw log P against theta per wavelength as SVG (needs gnuplot)\n"
            "  --tolerance  accuracy of the radius integral of a distribution (default 1e-3): the\n"
            "               size-parameter step halves from 0.125 until P changes by <= T RMS over\n"
            "               angle and 5 T at every angle; the default tables are within 1e-3 RMS and\n"
            "               5e-3 at every angle (fog bow and glory included) of the converged integral\n"
            "  --radius-step fixed size-parameter step instead (e.g. 0.5: fast, ~1 %% RMS error)\n"
            "  --no-cache   build the phase tables even if cached (and do not store them)\n"
            "  --json       one JSON object; " MIE_CLI_CONVENTION "\n");
}

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

int cmd_mie(int argc, char **argv)
{
    atmo_err e = {{0}};
    int rc = ATMO_OK, json = 0, nl = 0, have_index = 0, have_dsd = 0, n_ang = 0, use_cache = 1;
    double lambda[MIE_CLI_MAX_WAVELENGTHS], idx_n = 0.0, idx_k = 0.0, tolerance = 0.0;
    double radius_step = 0.0;
    double *angles = NULL, *grid = NULL, *mu = NULL, *P = NULL, *tableP = NULL;
    double complex *s1 = NULL, *s2 = NULL;
    const char *table_path = NULL, *chart_path = NULL, *dsd_text = NULL;
    output_paths files = {0};
    mie_dsd dsd = {0};
    cJSON *root = NULL;
    FILE *tf = NULL;
    char tmp[ATMO_TMP_PATH_MAX];

    for (int i = 1; i < argc; i++) {
        const char *a = argv[i], *v = i + 1 < argc ? argv[i + 1] : NULL;
        if (strcmp(a, "--help") == 0 || strcmp(a, "-h") == 0) {
            mie_usage(stdout);
            return ATMO_OK;
        } else if (strcmp(a, "--json") == 0) {
            json = 1;
            continue;
        } else if (strcmp(a, "--no-cache") == 0) {
            use_cache = 0;
            continue;
        } else if (!v) {
            rc = atmo_fail(&e, ATMO_ERR_USAGE, "'%s' needs a value or is unknown; see atmo mie --help", a);
        } else if (strcmp(a, "--radius-um") == 0) {
            char *end;
            dsd = (mie_dsd){.kind = MIE_DSD_MONO, .radius_um = strtod(v, &end)};
            dsd_text = v;
            /* its range depends on the wavelengths: checked once they are all known */
            if (*end || end == v)
                rc = atmo_fail(&e, ATMO_ERR_USAGE, "--radius-um '%s' is not a number", v);
            have_dsd++;
        } else if (strcmp(a, "--dsd") == 0) {
            rc = mie_dsd_parse(v, &dsd, &e);
            dsd_text = v;
            have_dsd++;
        } else if (strcmp(a, "--wavelength-nm") == 0) {
            char *end;
            double l = strtod(v, &end);
            if (*end || !(l >= 100.0 && l <= 1e5) || nl == MIE_CLI_MAX_WAVELENGTHS)
                rc = atmo_fail(&e, ATMO_ERR_USAGE, "--wavelength-nm '%s': need 100-100000 nm, at "
                               "most %d of them", v, MIE_CLI_MAX_WAVELENGTHS);
            else
                lambda[nl++] = l;
        } else if (strcmp(a, "--index") == 0) {
            rc = mie_parse_index(v, &idx_n, &idx_k, &e);
            have_index = 1;
        } else if (strcmp(a, "--angles-deg") == 0) {
            free(angles);
            rc = mie_parse_angles(v, &angles, &n_ang, &e);
        } else if (strcmp(a, "--tolerance") == 0 || strcmp(a, "--radius-step") == 0) {
            char *end;
            double t = strtod(v, &end);
            if (*end || !(t >= 1e-6 && t <= 1.0))
                rc = atmo_fail(&e, ATMO_ERR_USAGE, "%s '%s': need a number in [1e-6, 1]", a, v);
            else if (a[2] == 't')
                tolerance = t;
            else
                radius_step = t;
        } else if (strcmp(a, "--table") == 0) {
            table_path = v;
        } else if (strcmp(a, "--chart") == 0) {
            chart_path = v;
        } else {
            rc = atmo_fail(&e, ATMO_ERR_USAGE, "unknown option '%s'; see atmo mie --help", a);
        }
        if (rc)
            goto done;
        i++;
    }
    if (have_dsd != 1 || nl == 0) {
        rc = atmo_fail(&e, ATMO_ERR_USAGE, "give exactly one of --radius-um or --dsd, and at least "
                       "one --wavelength-nm; see atmo mie --help");
        goto done;
    }
    if ((table_path && (rc = output_paths_add(&files, "--table", table_path, &e))) ||
        (chart_path && (rc = output_paths_add(&files, "--chart", chart_path, &e))))
        goto done;
    if (chart_path && !atmo_gnuplot_available()) {
        rc = atmo_fail(&e, ATMO_ERR_RUNTIME, "--chart needs gnuplot, which is not on PATH; install "
                       "gnuplot-nox (setup.sh does) or leave out --chart");
        goto done;
    }

    /* one grid for all wavelengths, fine enough for the shortest; the drops' radii within the
     * solver's range at every wavelength (the largest at the shortest, the smallest at the
     * longest) */
    double r0, r1, lmin = lambda[0], lmax = lambda[0];
    for (int i = 1; i < nl; i++)
        lmin = fmin(lmin, lambda[i]), lmax = fmax(lmax, lambda[i]);
    if (dsd.kind == MIE_DSD_MONO && ((rc = mie_check_radius(dsd.radius_um, lmin, &e)) ||
                                     (rc = mie_check_radius(dsd.radius_um, lmax, &e))))
        goto done;
    if ((rc = mie_dsd_range(&dsd, &r0, &r1, &e)) || (rc = mie_check_radius(r1, lmin, &e)) ||
        (rc = mie_check_radius(r0, lmax, &e)))
        goto done;
    double xmax = 2.0 * MIE_CLI_PI * r1 / (lmin * 1e-3);
    if (tolerance > 0.0 && radius_step > 0.0) {
        rc = atmo_fail(&e, ATMO_ERR_USAGE, "give --tolerance or --radius-step, not both");
        goto done;
    }
    mie_table_options opt = {.fine_step_deg = fmin(0.1, 10.0 / fmax(xmax, 1.0)),
                             .tolerance = tolerance, .max_dx = radius_step};
    int n_grid = 0;
    if ((rc = mie_angle_grid(xmax, &opt, &grid, &n_grid, &e)))
        goto done;
    const double *out_ang = angles ? angles : grid;
    int n_out = angles ? n_ang : n_grid;
    mu = malloc(sizeof *mu * (size_t)n_out);
    P = malloc(sizeof *P * (size_t)n_out);
    s1 = malloc(sizeof *s1 * (size_t)n_out);
    s2 = malloc(sizeof *s2 * (size_t)n_out);
    int need_grid = table_path || chart_path;
    tableP = need_grid ? malloc(sizeof *tableP * (size_t)n_grid * (size_t)nl) : NULL;
    if (!mu || !P || !s1 || !s2 || (need_grid && !tableP)) {
        rc = atmo_fail(&e, ATMO_ERR_RUNTIME, "out of memory for %d angles", n_out);
        goto done;
    }
    for (int j = 0; j < n_out; j++)
        mu[j] = cos(out_ang[j] * MIE_CLI_PI / 180.0);
    root = cJSON_CreateObject();
    cJSON_AddStringToObject(root, "convention", MIE_CLI_CONVENTION);
    cJSON *results = cJSON_AddArrayToObject(root, "results");
    for (int w = 0; w < nl; w++) {
        double n = idx_n, k = idx_k;
        if (!have_index && (rc = mie_water_index(lambda[w], &n, &k, &e)))
            goto done;
        mie_bulk b;
        if (need_grid || !angles) { /* the table (cached) gives P on the grid and the bulk */
            mie_table t;
            if ((rc = mie_table_get(&dsd, lambda[w], n, k, &opt, use_cache, &t, NULL, &e)))
                goto done;
            if (t.n != n_grid) {
                mie_table_free(&t);
                rc = atmo_fail(&e, ATMO_ERR_RUNTIME, "internal: table grid of %d angles, expected "
                               "%d", t.n, n_grid);
                goto done;
            }
            b = t.bulk;
            if (need_grid)
                memcpy(tableP + (size_t)w * n_grid, t.P, sizeof *t.P * (size_t)n_grid);
            if (!angles)
                memcpy(P, t.P, sizeof *t.P * (size_t)n_grid);
            mie_table_free(&t);
        }
        if (angles && (rc = mie_dsd_integrate(&dsd, lambda[w], n, k, opt.max_dx, opt.tolerance, n_out, mu, P,
                                         &b, &e)))
            goto done;
        mie_efficiencies q = {0};
        if (dsd.kind == MIE_DSD_MONO &&
            (rc = mie_sphere(2.0 * MIE_CLI_PI * dsd.radius_um / (lambda[w] * 1e-3), n, k,
                             MIE_DN_LENTZ, n_out, mu, s1, s2, &q, &e)))
            goto done;
        cJSON *r = cJSON_CreateObject();
        cJSON_AddItemToArray(results, r);
        cJSON_AddNumberToObject(r, "wavelength_nm", lambda[w]);
        double nk[2] = {n, k};
        cJSON_AddItemToObject(r, "index", mie_array(nk, 2));
        cJSON_AddNumberToObject(r, "Qext", b.qext);
        cJSON_AddNumberToObject(r, "Qsca", b.qsca);
        cJSON_AddNumberToObject(r, "Qback", b.qback);
        cJSON_AddNumberToObject(r, "g", b.g);
        cJSON_AddNumberToObject(r, "albedo", b.albedo);
        if (dsd.kind == MIE_DSD_MONO) {
            cJSON_AddNumberToObject(r, "x", 2.0 * MIE_CLI_PI * dsd.radius_um / (lambda[w] * 1e-3));
        } else {
            cJSON_AddNumberToObject(r, "sigma_ext_per_lwc", b.sigma_ext_per_lwc);
            cJSON_AddNumberToObject(r, "r_eff_um", b.r_eff_um);
            cJSON_AddNumberToObject(r, "v_eff", b.v_eff);
            cJSON_AddNumberToObject(r, "n_radii", b.n_radii);
            cJSON_AddNumberToObject(r, "radius_step_dx", b.dx);
            if (b.err_rms >= 0.0) {
                cJSON_AddNumberToObject(r, "error_estimate_rms", b.err_rms);
                cJSON_AddNumberToObject(r, "error_estimate_max", b.err_max);
            }
        }
        cJSON_AddItemToObject(r, "angles_deg", mie_array(out_ang, n_out));
        cJSON_AddItemToObject(r, "P", mie_array(P, n_out));
        if (dsd.kind == MIE_DSD_MONO) {
            cJSON_AddItemToObject(r, "S1", mie_complex_array(s1, n_out));
            cJSON_AddItemToObject(r, "S2", mie_complex_array(s2, n_out));
        }
        if (!json) {
            printf("lambda %g nm  m = %.6f + %.3gi  Qext %.7g  Qsca %.7g  Qback %.7g  g %.7g  "
                   "albedo %.10g", lambda[w], n, k, b.qext, b.qsca, b.qback, b.g, b.albedo);
            if (dsd.kind != MIE_DSD_MONO) {
                printf("  sigma_ext/LWC %.5g m^2/g  r_eff %.4g um  v_eff %.4g  radii %d (dx %.4g",
                       b.sigma_ext_per_lwc, b.r_eff_um, b.v_eff, b.n_radii, b.dx);
                if (b.err_rms >= 0.0)
                    printf(", last halving changed P by %.1e RMS, %.1e max)", b.err_rms, b.err_max);
                else
                    printf(", fixed)");
            }
            printf("\n");
        }
    }
    if (json) {
        char *text = cJSON_PrintUnformatted(root);
        if (!text) {
            rc = atmo_fail(&e, ATMO_ERR_RUNTIME, "out of memory printing JSON");
            goto done;
        }
        puts(text);
        free(text);
    }
    if (table_path) {
        if (!(tf = atmo_atomic_open(table_path, tmp, &e))) {
            rc = ATMO_ERR_RUNTIME;
            goto done;
        }
        fprintf(tf, "theta_deg");
        for (int w = 0; w < nl; w++)
            fprintf(tf, ",P_%gnm", lambda[w]);
        fprintf(tf, "\n");
        for (int j = 0; j < n_grid; j++) {
            fprintf(tf, "%.6f", grid[j]);
            for (int w = 0; w < nl; w++)
                fprintf(tf, ",%.9g", tableP[(size_t)w * n_grid + j]);
            fprintf(tf, "\n");
        }
        rc = atmo_atomic_commit(tf, tmp, table_path, &e);
        tf = NULL;
        if (rc)
            goto done;
    }
    if (chart_path) {
        char title[512];
        snprintf(title, sizeof title, "Mie phase function, %s %s", dsd.kind == MIE_DSD_MONO ?
                 "radius (um)" : "drops", dsd_text);
        rc = mie_chart_svg(chart_path, title, grid, n_grid, tableP, lambda, nl, &e);
    }
done:
    if (tf)
        atmo_atomic_abort(tf, tmp);
    if (rc)
        fprintf(stderr, "atmo mie: %s\n", e.msg);
    output_paths_free(&files);
    cJSON_Delete(root);
    free(angles);
    free(grid);
    free(mu);
    free(P);
    free(s1);
    free(s2);
    free(tableP);
    return rc;
}
