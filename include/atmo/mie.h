/* mie.h — Lorenz–Mie scattering by homogeneous spheres (host, double precision), droplet size
 * distributions with their bulk optical properties, and phase tables for the kernels.
 *
 * Conventions
 *   - Size parameter x = 2 pi r / lambda; the refractive index is relative to the medium.
 *   - Refractive index IN: (n, k) with k >= 0 meaning absorption, i.e. m = n + i k as in
 *     Bohren & Huffman and the data tables (water_refractive_index.csv).
 *   - Amplitudes and coefficients OUT: Wiscombe's MIEV0 convention (m = n - i k, time factor
 *     e^{+i w t}). They are the complex conjugates of Bohren & Huffman's; all intensities,
 *     efficiencies and phase functions are the same in both. S(0) has Re S(0) = x^2 Q_ext / 4
 *     (optical theorem) and (1/2) integral (|S1|^2 + |S2|^2) dOmega = pi x^2 Q_sca.
 *   - mu is the cosine of the scattering angle (1 = forward). Phase functions P are
 *     4pi-normalised: (1/4pi) integral P dOmega = 1 (isotropic P = 1).
 *   - Radii in micrometres, wavelengths in nanometres at this API (as at the CLI); sigma per
 *     liquid water content in m^2 per gram (sigma_ext [1/m] = value * LWC [g/m^3]).
 *
 * Methods (details at the top of host/mie/mie.c, mie_dsd.c, mie_radius.c, mie_gram.c,
 * mie_table.c): Wiscombe's term count, D_n(mx) by downward recurrence started from Lentz's
 * continued fraction, Wiscombe's small-sphere series for |m| x <= 0.1; valid for
 * 1e-6 <= x <= 2e4. Size integrals refined until converged, summed as quadratic forms. */
#ifndef ATMO_MIE_H
#define ATMO_MIE_H
#include <complex.h>
#include "atmo/status.h"

/* ---- single sphere (host/mie.c) ------------------------------------------------------------ */

/* The sizes the solver resolves: size parameter x = 2 pi r / lambda in [MIE_X_MIN, MIE_X_MAX]
 * (below 1e-6 the small-sphere series' x^3 and x^6 terms leave double's range or precision:
 * Q_sca underflows at x ~ 1e-77, x^2 at 1e-154; above 2e4 the term count and the recurrences
 * are untested), and drops no larger than MIE_RADIUS_MAX_UM (raindrops break up beyond ~5 mm). */
#define MIE_X_MIN 1.0e-6
#define MIE_X_MAX 2.0e4
#define MIE_RADIUS_MAX_UM 5000.0

/* The radii (um) the solver takes at a wavelength (nm): [MIE_X_MIN, MIE_X_MAX] lambda / 2 pi,
 * the upper end at most MIE_RADIUS_MAX_UM. */
void mie_radius_limits_um(double wavelength_nm, double *r_min_um, double *r_max_um);

/* ATMO_OK when radius_um is within mie_radius_limits_um at wavelength_nm; otherwise a usage
 * error that states the range at that wavelength in radius and size parameter. */
int mie_check_radius(double radius_um, double wavelength_nm, atmo_err *e);

/* How the downward recurrence of D_n(mx) is started. Only MIE_DN_LENTZ is meant for use; the
 * others exist so tests can show which starts are safe (ZERO_FAR) and which are not (BHMIE). */
typedef enum mie_dn_start {
    MIE_DN_LENTZ,     /* D_N from Lentz's continued fraction at N = number of terms */
    MIE_DN_ZERO_FAR,  /* D = 0 at N >= max(nstop, |mx| + 10 |mx|^(1/3)) + 1 */
    MIE_DN_ZERO_BHMIE /* D = 0 at max(nstop, |mx|) + 15: the textbook start, wrong at large x */
} mie_dn_start;

typedef struct mie_efficiencies {
    double qext, qsca, qback; /* efficiencies (cross-section / pi r^2) */
    double g;                 /* asymmetry parameter <cos theta> */
    int nterms;               /* number of terms of the series that were summed */
} mie_efficiencies;

/* Wiscombe's (1979) number of terms for size parameter x. */
int mie_nterms(double x);

/* The first `count` Mie coefficients a_n, b_n (n = 1..count, stored at [n-1]), MIEV0 sign
 * convention. count may exceed mie_nterms(x). Uses the small-sphere series (only a1, b1, a2
 * non-zero) when |m| x <= 0.1. */
int mie_coefficients(double x, double n, double k, mie_dn_start start, int count,
                     double complex *a, double complex *b, atmo_err *e);

/* The number of terms N that mie_sphere sums at x: Wiscombe's count plus x^(1/3). */
int mie_sphere_nterms(double x, double n, double k);

/* The N = mie_sphere_nterms(x, n, k) coefficients a_n, b_n into a[0..N-1], b[0..N-1] (a and b
 * hold N + 1 entries; a[N] = b[N] = 0) and the efficiencies from them. */
int mie_sphere_coefficients(double x, double n, double k, mie_dn_start start, double complex *a,
                            double complex *b, mie_efficiencies *q, atmo_err *e);

/* Efficiencies, and amplitudes S1(mu_i), S2(mu_i) for n_mu cosines (s1, s2 may be NULL when
 * n_mu == 0). */
int mie_sphere(double x, double n, double k, mie_dn_start start, int n_mu, const double *mu,
               double complex *s1, double complex *s2, mie_efficiencies *q, atmo_err *e);

/* ---- refractive index of water (host/mie_water.c) -------------------------------------------- */

/* n from Daimon & Masumura 2007 (20 C) inside 200-1125 nm, Segelstein 1981 outside; k from
 * Segelstein 1981, interpolated linearly in log k. Valid for 200-2500 nm. */
int mie_water_index(double wavelength_nm, double *n, double *k, atmo_err *e);

/* ---- droplet size distributions (host/mie_dsd.c) --------------------------------------------- */

typedef enum mie_dsd_kind {
    MIE_DSD_MONO,      /* one radius: radius_um */
    MIE_DSD_GAMMA,     /* Hansen: n ~ r^((1-3b)/b) exp(-r/(a b)), a = r_eff_um, b = v_eff */
    MIE_DSD_LOGNORMAL, /* n ~ exp(-(ln r - ln r_g)^2 / (2 s^2)) / r, s = ln sigma_g */
    MIE_DSD_MODGAMMA   /* Deirmendjian: n ~ r^alpha exp(-b r^gamma), r in um */
} mie_dsd_kind;

typedef struct mie_dsd {
    mie_dsd_kind kind;
    double radius_um;         /* MONO */
    double r_eff_um, v_eff;   /* GAMMA */
    double r_g_um, sigma_g;   /* LOGNORMAL (sigma_g > 1, geometric standard deviation) */
    double alpha, b, gamma;   /* MODGAMMA (b in um^-gamma) */
    double r_max_um;          /* optional hard upper cut (0 = none), e.g. the thesis table */
} mie_dsd;

/* Named presets: cumulus, stratus, fog, corona, thesis-disperse, thesis-uniform. Returns 0 and
 * fills d, or -1 when the name is unknown. */
int mie_dsd_preset(const char *name, mie_dsd *d);
/* The preset names, NULL-terminated. */
extern const char *const mie_dsd_preset_names[];
/* Parse NAME or SPEC: mono:R | gamma:REFF,VEFF | lognormal:RG,SIGMA_G | modgamma:ALPHA,B,GAMMA
 * (radii in um), each optionally followed by ",max=RMAX". */
int mie_dsd_parse(const char *text, mie_dsd *d, atmo_err *e);
/* Check parameter ranges. */
int mie_dsd_validate(const mie_dsd *d, atmo_err *e);
/* Unnormalised number density n(r) (r in um). */
double mie_dsd_density(const mie_dsd *d, double r_um);

/* Radius interval the integrals use: the tails outside it carry at most MIE_DSD_TAIL of the
 * distribution's <r^2> (below) and <r^3> (above); 1e-7 each. */
#define MIE_DSD_TAIL 1.0e-7
int mie_dsd_range(const mie_dsd *d, double *r_min_um, double *r_max_um, atmo_err *e);

/* Bulk optical properties at one wavelength. Q-averages are cross-section weighted:
 * qext = <C_ext> / <pi r^2>. */
typedef struct mie_bulk {
    double wavelength_nm, n, k;
    double qext, qsca, qback, albedo, g;
    double sigma_ext_per_lwc, sigma_sca_per_lwc; /* m^2/g */
    double r_eff_um, v_eff;                      /* of the integrated (cut) distribution */
    double x_max;                                /* largest size parameter integrated */
    int n_radii;                                 /* quadrature nodes in radius */
    double dx;                                   /* final size-parameter step */
    double err_rms, err_max; /* converged rule: change of P in the last halving (RMS over the
                                checked angles, largest); -1 for a fixed step */
} mie_bulk;

/* Integrate over radius (host/mie_radius.c). max_dx > 0: the trapezoid rule with size-parameter
 * steps <= max_dx (and >= 200 nodes), one pass. max_dx == 0: the converged rule, which halves the
 * step from MIE_DSD_START_DX, to at least MIE_DSD_COARSEST_DX, until P changes by at most
 * `tolerance` RMS over angle and 5 x tolerance at every angle, Q_ext and g by `tolerance` and the
 * co-albedo by MIE_DSD_COALBEDO_TOLERANCE (tolerance 0 = MIE_DSD_TOLERANCE), or the step reaches
 * MIE_DSD_MIN_DX. Against a converged integral (step 0.005) the default table is within 1e-3 RMS
 * and 5e-3 at every angle. When n_mu > 0, also the 4pi-normalised effective phase function at the
 * cosines mu (sizes weighted by scattering cross-section) into P. */
#define MIE_DSD_START_DX 0.125
#define MIE_DSD_MIN_DX 0.002
#define MIE_DSD_COARSEST_DX (1.0 / 64.0) /* the converged rule's final step is at most this */
#define MIE_DSD_MAX_INTERVALS 4000000
#define MIE_DSD_TOLERANCE 1.0e-3
#define MIE_DSD_COALBEDO_TOLERANCE 0.10 /* relative change of 1 - omega_0 per halving */
int mie_dsd_integrate(const mie_dsd *d, double wavelength_nm, double n, double k, double max_dx,
                      double tolerance, int n_mu, const double *mu, double *P, mie_bulk *out,
                      atmo_err *e);

/* ---- phase tables (host/mie_table.c) --------------------------------------------------------- */

typedef struct mie_table_options {
    double fine_step_deg;   /* step within fine_zone_deg of 0 and 180; 0 = min(0.1, 10/x_max) */
    double fine_zone_deg;   /* 0 = 5 degrees */
    double coarse_step_deg; /* step elsewhere; 0 = 0.1 */
    int uniform;            /* 1: coarse_step_deg everywhere (for tests showing it fails) */
    double sun_radius_deg;  /* > 0: convolve with a uniform solar disc of this angular radius */
    double max_dx;          /* fixed size-parameter step of the radius integral; 0 = converged */
    double tolerance;       /* converged rule's RMS target; 0 = MIE_DSD_TOLERANCE */
} mie_table_options;

typedef struct mie_table {
    int n;             /* angles, 0 and 180 included */
    double *theta_deg; /* ascending */
    double *mu;        /* cos theta, descending */
    double *P;         /* 4pi-normalised phase function */
    double *cdf;       /* integral of P sin(theta) d theta from 0 to theta_i (trapezoid), / total */
    double norm;       /* (1/2) integral P sin(theta) d theta on the grid (ideally 1) */
    mie_bulk bulk;
} mie_table;

/* Angle grid for a largest size parameter x_max (opt may be NULL for defaults). */
int mie_angle_grid(double x_max, const mie_table_options *opt, double **theta_deg, int *count,
                   atmo_err *e);
/* Build the table of a distribution at one wavelength. */
int mie_table_build(const mie_dsd *d, double wavelength_nm, double n, double k,
                    const mie_table_options *opt, mie_table *t, atmo_err *e);
void mie_table_free(mie_table *t);
/* <cos theta> of the tabulated P (trapezoid on the table grid). */
double mie_table_asymmetry(const mie_table *t);
/* Legendre coefficient beta_l = (2l+1)/2 integral P(mu) P_l(mu) dmu on the table grid. */
double mie_table_legendre(const mie_table *t, int l);
/* Linear interpolation of P at theta (degrees). */
double mie_table_eval(const mie_table *t, double theta_deg);

/* ---- table cache (host/mie_cache.c) ---------------------------------------------------------- */

/* mie_table_build through the on-disk cache (atmo_cache_dir()): loads a table built earlier with
 * exactly these parameters, else builds and stores it. use_cache 0 only builds. *hit (may be
 * NULL) is 1 when the table came from the cache. */
int mie_table_get(const mie_dsd *d, double wavelength_nm, double n, double k,
                  const mie_table_options *opt, int use_cache, mie_table *t, int *hit, atmo_err *e);
/* The cache file for these parameters; -1 when there is no cache directory. */
int mie_table_cache_path(const mie_dsd *d, double wavelength_nm, double n, double k,
                         const mie_table_options *opt, char *path, size_t size);

/* ---- charts (host/mie_plot.c) ---------------------------------------------------------------- */

/* log P against theta, one line per wavelength (P: n_wavelengths rows of n values), with the
 * corona, fog bow and glory ranges shaded. */
int mie_chart_svg(const char *svg, const char *title, const double *theta_deg, int n,
                  const double *P, const double *wavelength_nm, int n_wavelengths, atmo_err *e);

#endif
