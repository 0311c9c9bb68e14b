/* mie_dsd.c — droplet size distributions: presets, parsing, densities and the radius range.
 *
 * Distributions (unnormalised number density n(r), r in um):
 *   gamma (Hansen 1971):      n ~ r^((1-3b)/b) exp(-r/(a b)),  a = r_eff, b = v_eff (0 < b < 1/2)
 *   log-normal:               n ~ exp(-(ln r - ln r_g)^2 / (2 s^2)) / r,  s = ln sigma_g;
 *                             r_eff = r_g e^(2.5 s^2), v_eff = e^(s^2) - 1
 *   modified gamma (Deirmendjian 1969): n ~ r^alpha exp(-b r^gamma)
 *   monodisperse:             one radius.
 * Range: the distribution is cut where the tails hold MIE_DSD_TAIL (1e-7) of <r^2> below and of
 * <r^3> above (found on a fine grid in ln r); the integrals over it are in mie_radius.c. The
 * results describe the cut distribution; the dropped 2e-7 is far below every other error. */
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include "atmo/mie.h"

/* grid in ln r for finding the cut-offs: 0.002 resolves sigma_g >= 1.01 with 5 nodes per s */
#define MIE_DSD_LN_STEP 0.002
#define MIE_DSD_R_LO_UM 1e-3
#define MIE_DSD_R_HI_UM 1e4

const char *const mie_dsd_preset_names[] = {"cumulus", "stratus", "fog", "corona",
                                            "thesis-disperse", "thesis-uniform", NULL};

int mie_dsd_preset(const char *name, mie_dsd *d)
{
    mie_dsd z = {0};
    if (strcmp(name, "cumulus") == 0) {
        z.kind = MIE_DSD_GAMMA, z.r_eff_um = 10.0, z.v_eff = 0.1;
    } else if (strcmp(name, "stratus") == 0) {
        z.kind = MIE_DSD_GAMMA, z.r_eff_um = 6.0, z.v_eff = 0.1;
    } else if (strcmp(name, "fog") == 0) { /* Monte di Procida fog */
        z.kind = MIE_DSD_LOGNORMAL, z.r_g_um = 4.69, z.sigma_g = 1.504;
    } else if (strcmp(name, "corona") == 0) { /* 5 % spread: rings survive (10 % weakens them) */
        z.kind = MIE_DSD_LOGNORMAL, z.r_g_um = 10.0, z.sigma_g = 1.05;
    } else if (strcmp(name, "thesis-disperse") == 0) { /* r^2 e^(-r / 5 um), table cut at 33 um */
        z.kind = MIE_DSD_MODGAMMA, z.alpha = 2.0, z.b = 0.2, z.gamma = 1.0, z.r_max_um = 33.0;
    } else if (strcmp(name, "thesis-uniform") == 0) { /* 1 % spread; r as its shipped table */
        z.kind = MIE_DSD_LOGNORMAL, z.r_g_um = 7.6, z.sigma_g = 1.01;
    } else {
        return -1;
    }
    *d = z;
    return 0;
}

int mie_dsd_validate(const mie_dsd *d, atmo_err *e)
{
    switch (d->kind) {
    case MIE_DSD_MONO:
        if (!(d->radius_um > 0.0 && d->radius_um <= MIE_RADIUS_MAX_UM))
            return atmo_fail(e, ATMO_ERR_USAGE, "droplet radius %g um is outside (0, %g] um",
                             d->radius_um, MIE_RADIUS_MAX_UM);
        break;
    case MIE_DSD_GAMMA:
        if (!(d->r_eff_um > 0.0 && d->r_eff_um <= 1000.0) || !(d->v_eff >= 0.001 && d->v_eff < 0.5))
            return atmo_fail(e, ATMO_ERR_USAGE,
                             "gamma distribution r_eff %g um, v_eff %g: need 0 < r_eff <= 1000 and "
                             "0.001 <= v_eff < 0.5", d->r_eff_um, d->v_eff);
        break;
    case MIE_DSD_LOGNORMAL:
        if (!(d->r_g_um > 0.0 && d->r_g_um <= 1000.0) || !(d->sigma_g >= 1.01 && d->sigma_g <= 4.0))
            return atmo_fail(e, ATMO_ERR_USAGE,
                             "log-normal r_g %g um, sigma_g %g: need 0 < r_g <= 1000 and "
                             "1.01 <= sigma_g <= 4 (use mono:R for one size)", d->r_g_um,
                             d->sigma_g);
        break;
    case MIE_DSD_MODGAMMA:
        if (!(d->alpha > -1.0 && d->alpha <= 100.0) || !(d->b > 0.0) || !(d->gamma > 0.0 && d->gamma <= 10.0))
            return atmo_fail(e, ATMO_ERR_USAGE,
                             "modified gamma alpha %g, b %g, gamma %g: need -1 < alpha <= 100, "
                             "b > 0, 0 < gamma <= 10", d->alpha, d->b, d->gamma);
        break;
    default:
        return atmo_fail(e, ATMO_ERR_USAGE, "unknown size distribution kind %d", (int)d->kind);
    }
    if (!(d->r_max_um >= 0.0) || (d->kind == MIE_DSD_MONO && d->r_max_um > 0.0))
        return atmo_fail(e, ATMO_ERR_USAGE, "max=%g: the radius cut must be >= 0 and applies only "
                         "to distributions", d->r_max_um);
    return ATMO_OK;
}

int mie_dsd_parse(const char *text, mie_dsd *d, atmo_err *e)
{
    if (mie_dsd_preset(text, d) == 0)
        return ATMO_OK;
    static const struct { const char *prefix; mie_dsd_kind kind; int count; } kinds[] = {
        {"mono:", MIE_DSD_MONO, 1}, {"gamma:", MIE_DSD_GAMMA, 2},
        {"lognormal:", MIE_DSD_LOGNORMAL, 2}, {"modgamma:", MIE_DSD_MODGAMMA, 3}};
    mie_dsd z = {0};
    for (size_t i = 0; i < sizeof kinds / sizeof kinds[0]; i++) {
        size_t len = strlen(kinds[i].prefix);
        if (strncmp(text, kinds[i].prefix, len) != 0)
            continue;
        double v[3] = {0};
        const char *p = text + len;
        for (int j = 0; j < kinds[i].count; j++) {
            char *end;
            v[j] = strtod(p, &end);
            if (end == p || (*end != ',' && *end != '\0') || (j + 1 < kinds[i].count && *end != ','))
                goto bad;
            p = *end == ',' ? end + 1 : end;
        }
        if (*p != '\0') {
            char *end;
            if (strncmp(p, "max=", 4) != 0)
                goto bad;
            z.r_max_um = strtod(p + 4, &end);
            if (end == p + 4 || *end != '\0')
                goto bad;
        } else if (p > text && p[-1] == ',') {
            goto bad;
        }
        z.kind = kinds[i].kind;
        if (z.kind == MIE_DSD_MONO)
            z.radius_um = v[0];
        else if (z.kind == MIE_DSD_GAMMA)
            z.r_eff_um = v[0], z.v_eff = v[1];
        else if (z.kind == MIE_DSD_LOGNORMAL)
            z.r_g_um = v[0], z.sigma_g = v[1];
        else
            z.alpha = v[0], z.b = v[1], z.gamma = v[2];
        int rc = mie_dsd_validate(&z, e);
        if (rc == ATMO_OK)
            *d = z;
        return rc;
    }
bad:
    return atmo_fail(e, ATMO_ERR_USAGE,
                     "size distribution '%s' not understood; use a preset (cumulus, stratus, fog, "
                     "corona, thesis-disperse, thesis-uniform) or mono:R, gamma:REFF,VEFF, "
                     "lognormal:RG,SIGMA_G, modgamma:ALPHA,B,GAMMA (radii in um, optional ,max=R)",
                     text);
}

/* ln n(r) up to a constant; -inf outside the support. */
static double mie_dsd_log_density(const mie_dsd *d, double r)
{
    if (r <= 0.0 || (d->r_max_um > 0.0 && r > d->r_max_um))
        return -INFINITY;
    switch (d->kind) {
    case MIE_DSD_GAMMA: {
        double b = d->v_eff, scale = d->r_eff_um * b;
        return (1.0 - 3.0 * b) / b * log(r / d->r_eff_um) - (r - d->r_eff_um) / scale;
    }
    case MIE_DSD_LOGNORMAL: {
        double s = log(d->sigma_g), t = log(r / d->r_g_um) / s;
        return -0.5 * t * t - log(r / d->r_g_um);
    }
    case MIE_DSD_MODGAMMA: { /* relative to the mode, so large alpha cannot overflow */
        double rm = d->alpha > 0.0 ? pow(d->alpha / (d->b * d->gamma), 1.0 / d->gamma) : 1.0;
        return d->alpha * log(r / rm) - d->b * (pow(r, d->gamma) - pow(rm, d->gamma));
    }
    default:
        return -INFINITY;
    }
}

double mie_dsd_density(const mie_dsd *d, double r_um)
{
    if (d->kind == MIE_DSD_MONO)
        return r_um == d->radius_um ? 1.0 : 0.0;
    return exp(mie_dsd_log_density(d, r_um));
}

int mie_dsd_range(const mie_dsd *d, double *r_min_um, double *r_max_um, atmo_err *e)
{
    int rc = mie_dsd_validate(d, e);
    if (rc)
        return rc;
    if (d->kind == MIE_DSD_MONO) {
        *r_min_um = *r_max_um = d->radius_um;
        return ATMO_OK;
    }
    double l0 = log(MIE_DSD_R_LO_UM), l1 = log(MIE_DSD_R_HI_UM);
    int n = (int)ceil((l1 - l0) / MIE_DSD_LN_STEP) + 1;
    double *c2 = malloc(sizeof *c2 * (size_t)n), *c3 = malloc(sizeof *c3 * (size_t)n);
    if (!c2 || !c3) {
        rc = atmo_fail(e, ATMO_ERR_RUNTIME, "out of memory for the size grid");
        goto cleanup;
    }
    /* r^k n(r) dr = r^(k+1) n(r) d ln r; shift logs by the peak of the r^3 weight to stay finite */
    double peak = -INFINITY;
    for (int i = 0; i < n; i++) {
        double lr = l0 + i * MIE_DSD_LN_STEP;
        peak = fmax(peak, mie_dsd_log_density(d, exp(lr)) + 4.0 * lr);
    }
    double s2 = 0.0, s3 = 0.0, prev2 = 0.0, prev3 = 0.0;
    for (int i = 0; i < n; i++) {
        double lr = l0 + i * MIE_DSD_LN_STEP, ld = mie_dsd_log_density(d, exp(lr));
        double f2 = exp(ld + 3.0 * lr - peak), f3 = exp(ld + 4.0 * lr - peak);
        if (i > 0) {
            s2 += 0.5 * (f2 + prev2) * MIE_DSD_LN_STEP;
            s3 += 0.5 * (f3 + prev3) * MIE_DSD_LN_STEP;
        }
        c2[i] = s2, c3[i] = s3, prev2 = f2, prev3 = f3;
    }
    if (!(s3 > 0.0) || c2[1] > MIE_DSD_TAIL * s2 || c3[n - 2] < (1.0 - MIE_DSD_TAIL) * s3) {
        rc = atmo_fail(e, ATMO_ERR_USAGE, "size distribution does not fit in %g-%g um; choose "
                       "parameters with drops in that range", MIE_DSD_R_LO_UM, MIE_DSD_R_HI_UM);
        goto cleanup;
    }
    int lo = 0, hi = n - 1;
    while (lo + 1 < n && c2[lo + 1] <= MIE_DSD_TAIL * s2)
        lo++;
    while (hi > 0 && c3[hi - 1] >= (1.0 - MIE_DSD_TAIL) * s3)
        hi--;
    *r_min_um = exp(l0 + lo * MIE_DSD_LN_STEP);
    *r_max_um = exp(l0 + hi * MIE_DSD_LN_STEP);
    if (d->r_max_um > 0.0 && *r_max_um > d->r_max_um)
        *r_max_um = d->r_max_um;
cleanup:
    free(c2);
    free(c3);
    return rc;
}
