/* atmosphere_ref.c — double-precision reference of transmittance and single scattering.
 *
 * What it computes (atmosphere_ref.h has the conventions):
 *   optical depth    tau = int_ray beta_R e^{-h/H_R} + beta_M,t e^{-h/H_M} + beta_O tent(h) dt
 *   single scattering  L = int_0^d e^{-tau(0,t)} [beta_R e^{-h/H_R} p_R(nu)
 *                                + beta_M,s e^{-h/H_M} p_M(nu)] E e^{-tau_sun(t)} dt
 *                    (Nishita et al. 1993; Bruneton 2017, "Single scattering"), with the sun's
 *                    term zero inside the planet's shadow.
 *   ground           T(0, d) (rho / pi) E T_sun(ground) max(mu_s,ground, 0).
 *
 * How: global adaptive Gauss-Kronrod quadrature (7-point Gauss inside the 15-point Kronrod
 * rule; nodes and weights are the standard ones, e.g. Piessens et al. 1983, QUADPACK). The
 * interval with the largest error estimate |K15 - G7| is bisected until the estimates sum to
 * less than rel_tol × |integral| in every component. The integrands are smooth except at
 *   - the ozone tent's three altitudes (kinks): the rays are split where r_t = R + h_k;
 *   - the shadow boundary (a jump in T_sun): the view ray is split where it crosses the shadow
 *     cylinder, q(t) = |x_t|^2 - (x_t . s)^2 - R^2 = 0, i.e.
 *     (1 - nu^2) t^2 + 2 r (mu - mu_s nu) t + r^2 (1 - mu_s^2) - R^2 = 0,
 *     so no quadrature node straddles the jump and no refinement is spent on it.
 * Single scattering nests the quadratures: each outer node integrates the view ray up to it and
 * the sun ray from it (about 1-5 ms per radiance on one core).
 *
 * Precision at planet scale: altitudes come from h = (r_t^2 - R^2) / (r_t + R) with
 * r_t^2 - R^2 = t^2 + 2 r mu t + (r - R)(r + R), and ray-sphere distances use the root formula
 * without cancellation, so nothing subtracts two radii of 6.4e6 m. */
#include <math.h>
#include <string.h>
#include "atmo/atmosphere_ref.h"

#define REF_MAX_COMPONENTS 6
#define REF_MAX_INTERVALS 1024
#define REF_MAX_POINTS 16
#define REF_TOL_DEPTH 1e-11
#define REF_TOL_RADIANCE 1e-9

/* ---- geometry ---------------------------------------------------------------------------- */

/* (r - R)(r + R) + r^2 mu^2: the discriminant / 4 of |x + t v|^2 = R^2, without cancellation. */
static double ref_discriminant(double r, double mu, double radius)
{
    return (radius - r) * (radius + r) + r * r * mu * mu;
}

double atmo_ref_distance_to_top(double r, double mu, double top)
{
    double disc = fmax(ref_discriminant(r, mu, top), 0.0);
    double c = (top - r) * (top + r); /* product of the roots is -c */
    if (c <= 0.0) /* on or above the sphere: the far root, where the ray leaves it */
        return mu < 0.0 && ref_discriminant(r, mu, top) >= 0.0 ? -r * mu + sqrt(disc) : 0.0;
    /* the positive root, in the form that does not cancel for either sign of mu */
    return mu > 0.0 ? c / (r * mu + sqrt(disc)) : -r * mu + sqrt(disc);
}

double atmo_ref_distance_to_bottom(double r, double mu, double bottom)
{
    double disc = fmax(ref_discriminant(r, mu, bottom), 0.0);
    double c = (r - bottom) * (r + bottom);
    double q = -r * mu + sqrt(disc); /* the far root; the near one is c / q */
    return q > 0.0 ? fmax(c, 0.0) / q : 0.0;
}

int atmo_ref_ray_hits_ground(double r, double mu, double bottom)
{
    return mu < 0.0 && ref_discriminant(r, mu, bottom) >= 0.0;
}

double atmo_ref_radius_at(double r, double mu, double t)
{
    return sqrt(fmax(t * t + 2.0 * r * mu * t + r * r, 0.0));
}

double atmo_ref_mu_s_at(double r, double mu, double mu_s, double nu, double t)
{
    double r_t = atmo_ref_radius_at(r, mu, t);
    return r_t > 0.0 ? fmin(fmax((r * mu_s + t * nu) / r_t, -1.0), 1.0) : mu_s;
}

/* Altitude above `bottom` at distance t, from r_t^2 - R^2 without subtracting large numbers. */
static double ref_altitude_at(double r, double mu, double t, double bottom)
{
    double r_t = atmo_ref_radius_at(r, mu, t);
    return (t * t + 2.0 * r * mu * t + (r - bottom) * (r + bottom)) / (r_t + bottom);
}

/* The part of the ray inside the atmosphere: [*t0, *t1]; returns 0 when it has none. */
static int ref_ray_span(const atmo_atmosphere *a, double r, double mu, double *t0, double *t1)
{
    double top = a->top_radius_m, bottom = a->bottom_radius_m;
    r = fmax(r, bottom);
    *t0 = 0.0;
    if (r > top) {
        double disc = ref_discriminant(r, mu, top);
        if (mu >= 0.0 || disc < 0.0)
            return 0;
        double c = (r - top) * (r + top);
        *t0 = c / (-r * mu + sqrt(disc)); /* near root */
    }
    if (atmo_ref_ray_hits_ground(r, mu, bottom))
        *t1 = atmo_ref_distance_to_bottom(r, mu, bottom);
    else if (r > top)
        *t1 = -r * mu + sqrt(fmax(ref_discriminant(r, mu, top), 0.0));
    else
        *t1 = atmo_ref_distance_to_top(r, mu, top);
    return *t1 > *t0;
}

/* ---- model ------------------------------------------------------------------------------- */

static double ref_ozone_tent(const atmo_atmosphere *a, double h)
{
    if (h <= a->ozone_bottom_m || h >= a->ozone_top_m)
        return 0.0;
    if (h < a->ozone_peak_m)
        return (h - a->ozone_bottom_m) / (a->ozone_peak_m - a->ozone_bottom_m);
    return (a->ozone_top_m - h) / (a->ozone_top_m - a->ozone_peak_m);
}

double atmo_ref_phase_rayleigh(double nu)
{
    return 3.0 / (16.0 * ATMO_REF_PI) * (1.0 + nu * nu);
}

double atmo_ref_phase_mie(const atmo_atmosphere *a, double nu)
{
    double g = a->mie_g;
    double denom = 1.0 + g * g - 2.0 * g * nu;
    if (a->mie_phase == ATMO_PHASE_HENYEY_GREENSTEIN)
        return (1.0 - g * g) / (4.0 * ATMO_REF_PI * denom * sqrt(denom));
    return 3.0 / (8.0 * ATMO_REF_PI) * (1.0 - g * g) / (2.0 + g * g) * (1.0 + nu * nu) /
           (denom * sqrt(denom));
}

/* ---- adaptive Gauss-Kronrod quadrature ----------------------------------------------------- */

typedef void (*ref_integrand)(void *ctx, double t, double *out);

static const double ref_xgk[8] = {
    0.991455371120812639206854697526329, 0.949107912342758524526189684047851,
    0.864864423359769072789712788640926, 0.741531185599394439863864773280788,
    0.586087235467691130294144845693013, 0.405845151377397166906606412076961,
    0.207784955007898467600689403773245, 0.0};
static const double ref_wgk[8] = {
    0.022935322010529224963732008058970, 0.063092092629978553290700663189204,
    0.104790010322250183839876322541518, 0.140653259715525918745189590510238,
    0.169004726639267902826583426598550, 0.190350578064785409913256402421014,
    0.204432940075298892414161999234649, 0.209482141084727828012999174891714};
/* Gauss weights of the odd Kronrod nodes ref_xgk[1], [3], [5], [7] */
static const double ref_wg[4] = {0.129484966168869693270611432679082,
                                 0.279705391489276667901467771423780,
                                 0.381830050505118944950369775488975,
                                 0.417959183673469387755102040816327};

typedef struct {
    double a, b;
    double value[REF_MAX_COMPONENTS], error[REF_MAX_COMPONENTS];
} ref_interval;

static void ref_kronrod(ref_integrand f, void *ctx, int n, ref_interval *iv)
{
    double centre = 0.5 * (iv->a + iv->b), half = 0.5 * (iv->b - iv->a);
    double k[REF_MAX_COMPONENTS] = {0}, g[REF_MAX_COMPONENTS] = {0}, y[REF_MAX_COMPONENTS];
    for (int j = 0; j < 8; j++) {
        int nodes = j == 7 ? 1 : 2;
        for (int side = 0; side < nodes; side++) {
            f(ctx, centre + (side ? -half : half) * ref_xgk[j], y);
            for (int c = 0; c < n; c++) {
                k[c] += ref_wgk[j] * y[c];
                if (j & 1)
                    g[c] += ref_wg[j / 2] * y[c];
            }
        }
    }
    for (int c = 0; c < n; c++) {
        iv->value[c] = k[c] * half;
        iv->error[c] = fabs((k[c] - g[c]) * half);
    }
}

/* Integral of the n-component f over [points[0], points[np-1]], split at the given (sorted)
 * points, to relative accuracy rel_tol in every component. */
static void ref_integrate(ref_integrand f, void *ctx, int n, const double *points, int np,
                            double rel_tol, double *out)
{
    ref_interval iv[REF_MAX_INTERVALS];
    int count = 0;
    for (int i = 0; i + 1 < np; i++) {
        if (!(points[i + 1] > points[i]))
            continue;
        iv[count].a = points[i];
        iv[count].b = points[i + 1];
        ref_kronrod(f, ctx, n, &iv[count++]);
    }
    for (;;) {
        double total[REF_MAX_COMPONENTS] = {0}, error[REF_MAX_COMPONENTS] = {0};
        for (int i = 0; i < count; i++)
            for (int c = 0; c < n; c++) {
                total[c] += iv[i].value[c];
                error[c] += iv[i].error[c];
            }
        int converged = 1;
        for (int c = 0; c < n; c++)
            converged &= error[c] <= rel_tol * fabs(total[c]);
        if (converged || count == 0 || count + 1 > REF_MAX_INTERVALS) {
            memcpy(out, total, sizeof(double) * (size_t)n);
            return;
        }
        /* bisect the interval whose error weighs most against its component's total */
        int worst = 0;
        double worst_ratio = -1.0;
        for (int i = 0; i < count; i++)
            for (int c = 0; c < n; c++) {
                double ratio = iv[i].error[c] / (fabs(total[c]) + 1e-300);
                if (ratio > worst_ratio) {
                    worst_ratio = ratio;
                    worst = i;
                }
            }
        double mid = 0.5 * (iv[worst].a + iv[worst].b);
        if (!(mid > iv[worst].a && mid < iv[worst].b)) { /* cannot split further */
            memcpy(out, total, sizeof(double) * (size_t)n);
            return;
        }
        iv[count].a = mid;
        iv[count].b = iv[worst].b;
        iv[worst].b = mid;
        ref_kronrod(f, ctx, n, &iv[worst]);
        ref_kronrod(f, ctx, n, &iv[count++]);
    }
}

/* Sorted break points of [t0, t1]: its ends plus where the ray crosses the ozone tent's kinks
 * and, when extra is given, the extra points inside (t0, t1). Returns their count. */
static int ref_break_points(const atmo_atmosphere *a, double r, double mu, double t0,
                              double t1, const double *extra, int n_extra, double *points)
{
    int np = 0;
    points[np++] = t0;
    double heights[3] = {a->ozone_bottom_m, a->ozone_peak_m, a->ozone_top_m};
    for (int k = 0; k < 3; k++) {
        double radius = a->bottom_radius_m + heights[k];
        double disc = ref_discriminant(r, mu, radius);
        if (disc <= 0.0)
            continue;
        double root[2] = {-r * mu - sqrt(disc), -r * mu + sqrt(disc)};
        for (int j = 0; j < 2; j++)
            if (root[j] > t0 && root[j] < t1)
                points[np++] = root[j];
    }
    for (int j = 0; j < n_extra; j++)
        if (extra[j] > t0 && extra[j] < t1)
            points[np++] = extra[j];
    points[np++] = t1;
    for (int i = 1; i < np; i++) /* insertion sort: a dozen points at most */
        for (int j = i; j > 0 && points[j] < points[j - 1]; j--) {
            double tmp = points[j];
            points[j] = points[j - 1];
            points[j - 1] = tmp;
        }
    return np;
}

/* ---- transmittance ------------------------------------------------------------------------- */

typedef struct {
    const atmo_atmosphere *a;
    double r, mu;
} ref_ray;

static void ref_column_integrand(void *ctx, double t, double *out)
{
    const ref_ray *ray = ctx;
    const atmo_atmosphere *a = ray->a;
    double h = ref_altitude_at(ray->r, ray->mu, t, a->bottom_radius_m);
    out[0] = exp(-h / a->rayleigh_scale_height_m);
    out[1] = exp(-h / a->mie_scale_height_m);
    out[2] = ref_ozone_tent(a, h);
}

/* Column integrals from t0 to t1 along the ray. */
static void ref_columns_between(const atmo_atmosphere *a, double r, double mu, double t0,
                                  double t1, double out[3])
{
    out[0] = out[1] = out[2] = 0.0;
    if (!(t1 > t0))
        return;
    ref_ray ray = {a, r, mu};
    double points[REF_MAX_POINTS];
    int np = ref_break_points(a, r, mu, t0, t1, NULL, 0, points);
    ref_integrate(ref_column_integrand, &ray, 3, points, np, REF_TOL_DEPTH, out);
}

static void ref_depth_from_columns(const atmo_atmosphere *a, const double col[3],
                                     double tau[3])
{
    for (int c = 0; c < 3; c++)
        tau[c] = a->rayleigh_scattering_per_m[c] * col[0] + a->mie_extinction_per_m[c] * col[1] +
                 a->ozone_absorption_per_m[c] * col[2];
}

void atmo_ref_columns(const atmo_atmosphere *a, double r, double mu, double out[3])
{
    double t0, t1;
    r = fmax(r, a->bottom_radius_m);
    if (!ref_ray_span(a, r, mu, &t0, &t1)) {
        out[0] = out[1] = out[2] = 0.0;
        return;
    }
    ref_columns_between(a, r, mu, t0, t1, out);
}

void atmo_ref_optical_depth(const atmo_atmosphere *a, double r, double mu, double out_tau[3])
{
    double col[3];
    atmo_ref_columns(a, r, mu, col);
    ref_depth_from_columns(a, col, out_tau);
}

void atmo_ref_optical_depth_to(const atmo_atmosphere *a, double r, double mu, double d,
                               double out_tau[3])
{
    double t0, t1, col[3] = {0.0, 0.0, 0.0};
    r = fmax(r, a->bottom_radius_m);
    if (ref_ray_span(a, r, mu, &t0, &t1))
        ref_columns_between(a, r, mu, t0, fmin(fmax(d, t0), t1), col);
    ref_depth_from_columns(a, col, out_tau);
}

void atmo_ref_transmittance(const atmo_atmosphere *a, double r, double mu, double out_T[3])
{
    double tau[3];
    atmo_ref_optical_depth(a, r, mu, tau);
    for (int c = 0; c < 3; c++)
        out_T[c] = exp(-tau[c]);
}

void atmo_ref_sun_transmittance(const atmo_atmosphere *a, double r, double mu_s, double out_T[3])
{
    r = fmax(r, a->bottom_radius_m);
    if (atmo_ref_ray_hits_ground(r, mu_s, a->bottom_radius_m)) {
        out_T[0] = out_T[1] = out_T[2] = 0.0;
        return;
    }
    atmo_ref_transmittance(a, r, mu_s, out_T);
}

void atmo_ref_direct_irradiance(const atmo_atmosphere *a, double r, double mu_s, double out_E[3])
{
    double T[3];
    atmo_ref_sun_transmittance(a, r, mu_s, T);
    for (int c = 0; c < 3; c++)
        out_E[c] = a->solar_irradiance[c] * T[c] * fmax(mu_s, 0.0);
}

/* ---- single scattering --------------------------------------------------------------------- */

typedef struct {
    const atmo_atmosphere *a;
    double r, mu, mu_s, nu; /* at the start of the ray inside the atmosphere (t = 0) */
} ref_view;

/* Rayleigh (out[0..2]) and Mie (out[3..5]) in-scattering at t, without the phase functions. */
static void ref_single_integrand(void *ctx, double t, double *out)
{
    const ref_view *v = ctx;
    const atmo_atmosphere *a = v->a;
    double bottom = a->bottom_radius_m;
    double r_t = fmax(atmo_ref_radius_at(v->r, v->mu, t), bottom);
    double mu_s_t = atmo_ref_mu_s_at(v->r, v->mu, v->mu_s, v->nu, t);
    for (int c = 0; c < 6; c++)
        out[c] = 0.0;
    if (atmo_ref_ray_hits_ground(r_t, mu_s_t, bottom))
        return; /* in the planet's shadow */
    double col_view[3], col_sun[3], tau_view[3], tau_sun[3];
    ref_columns_between(a, v->r, v->mu, 0.0, t, col_view);
    atmo_ref_columns(a, r_t, mu_s_t, col_sun);
    ref_depth_from_columns(a, col_view, tau_view);
    ref_depth_from_columns(a, col_sun, tau_sun);
    double h = ref_altitude_at(v->r, v->mu, t, bottom);
    double rho_r = exp(-h / a->rayleigh_scale_height_m), rho_m = exp(-h / a->mie_scale_height_m);
    for (int c = 0; c < 3; c++) {
        double lit = a->solar_irradiance[c] * exp(-tau_view[c] - tau_sun[c]);
        out[c] = lit * a->rayleigh_scattering_per_m[c] * rho_r;
        out[3 + c] = lit * a->mie_scattering_per_m[c] * rho_m;
    }
}

/* Moves a camera above the atmosphere to where its ray enters it (r, mu, mu_s change, nu does
 * not); returns the ray's length inside, 0 when it misses the atmosphere. */
static double ref_enter(const atmo_atmosphere *a, double *r, double *mu, double *mu_s,
                          double nu)
{
    double t0, t1;
    *r = fmax(*r, a->bottom_radius_m);
    if (!ref_ray_span(a, *r, *mu, &t0, &t1))
        return 0.0;
    if (t0 > 0.0) {
        double r0 = a->top_radius_m;
        *mu_s = fmin(fmax((*r * *mu_s + t0 * nu) / r0, -1.0), 1.0);
        *mu = fmin(fmax((*r * *mu + t0) / r0, -1.0), 1.0);
        *r = r0;
    }
    return t1 - t0;
}

/* Single scattering along the ray up to distance t_max from the camera (INFINITY: all of it). */
static void ref_single_parts(const atmo_atmosphere *a, double r, double mu, double mu_s,
                               double nu, double t_max, double out_rayleigh[3], double out_mie[3])
{
    double L[6] = {0, 0, 0, 0, 0, 0}, t0, t1;
    if (!ref_ray_span(a, fmax(r, a->bottom_radius_m), mu, &t0, &t1))
        t0 = 0.0;
    double d = fmin(ref_enter(a, &r, &mu, &mu_s, nu), t_max - t0);
    if (d > 0.0) {
        /* shadow-cylinder crossings: roots of q(t) = A t^2 + 2 B t + C */
        double A = 1.0 - nu * nu, B = r * (mu - mu_s * nu);
        double C = (r - a->bottom_radius_m) * (r + a->bottom_radius_m) - r * r * mu_s * mu_s;
        double roots[2];
        int n_roots = 0;
        double disc = B * B - A * C;
        if (A > 0.0 && disc > 0.0) {
            double q = -(B + copysign(sqrt(disc), B)); /* stable pair of roots */
            roots[n_roots++] = q / A;
            if (q != 0.0)
                roots[n_roots++] = C / q;
        } else if (A == 0.0 && B != 0.0) {
            roots[n_roots++] = -C / (2.0 * B);
        }
        ref_view view = {a, r, mu, mu_s, nu};
        double points[REF_MAX_POINTS];
        int np = ref_break_points(a, r, mu, 0.0, d, roots, n_roots, points);
        ref_integrate(ref_single_integrand, &view, 6, points, np, REF_TOL_RADIANCE, L);
    }
    double p_r = atmo_ref_phase_rayleigh(nu), p_m = atmo_ref_phase_mie(a, nu);
    for (int c = 0; c < 3; c++) {
        if (out_rayleigh)
            out_rayleigh[c] = L[c] * p_r;
        if (out_mie)
            out_mie[c] = L[3 + c] * p_m;
    }
}

void atmo_ref_single_scattering_parts(const atmo_atmosphere *a, double r, double mu, double mu_s,
                                      double nu, double out_rayleigh[3], double out_mie[3])
{
    ref_single_parts(a, r, mu, mu_s, nu, INFINITY, out_rayleigh, out_mie);
}

void atmo_ref_single_scattering_to(const atmo_atmosphere *a, double r, double mu, double mu_s,
                                   double nu, double d, double out_L[3])
{
    double rayleigh[3], mie[3];
    ref_single_parts(a, r, mu, mu_s, nu, d, rayleigh, mie);
    for (int c = 0; c < 3; c++)
        out_L[c] = rayleigh[c] + mie[c];
}

void atmo_ref_single_scattering(const atmo_atmosphere *a, double r, double mu, double mu_s,
                                double nu, double out_L[3])
{
    double rayleigh[3], mie[3];
    atmo_ref_single_scattering_parts(a, r, mu, mu_s, nu, rayleigh, mie);
    for (int c = 0; c < 3; c++)
        out_L[c] = rayleigh[c] + mie[c];
}

void atmo_ref_ground_radiance(const atmo_atmosphere *a, double r, double mu, double mu_s,
                              double nu, double out_L[3])
{
    out_L[0] = out_L[1] = out_L[2] = 0.0;
    double d = ref_enter(a, &r, &mu, &mu_s, nu);
    if (!(d > 0.0) || !atmo_ref_ray_hits_ground(r, mu, a->bottom_radius_m))
        return;
    double bottom = a->bottom_radius_m;
    double mu_s_ground = fmin(fmax((r * mu_s + d * nu) / bottom, -1.0), 1.0);
    if (mu_s_ground <= 0.0)
        return;
    double col[3], tau[3], T_sun[3];
    ref_columns_between(a, r, mu, 0.0, d, col);
    ref_depth_from_columns(a, col, tau);
    atmo_ref_sun_transmittance(a, bottom, mu_s_ground, T_sun);
    for (int c = 0; c < 3; c++)
        out_L[c] = exp(-tau[c]) * a->ground_albedo[c] / ATMO_REF_PI * a->solar_irradiance[c] *
                   T_sun[c] * mu_s_ground;
}
