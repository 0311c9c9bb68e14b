/* testslab.h — radiative transfer in a plane-parallel homogeneous slab over a black surface,
 * solved on the host in double precision by adding-doubling (tests/support_slab.c): the
 * independent oracle of tests/test_cloud_slab.c.
 *
 * The slab has optical thickness tau, single-scattering albedo omega and a phase function
 * p(cos theta) per steradian (int p dOmega = 1) of the scattering angle; a collimated beam of
 * irradiance 1 (normal to the beam) falls on its top at cosine mu0 to the downward normal. The
 * solver gives the radiance reflected at the top and the diffuse radiance transmitted at the
 * bottom (the direct beam excluded) at a photon direction of cosine mu (> 0) to the upward
 * (reflected) or downward (transmitted) normal and azimuth phi from the beam's (phi = 0: the
 * horizontal direction the beam travels in). Method: delta-M truncation of p to M <= 2N
 * Legendre moments (Wiscombe 1977), the truncated problem per azimuthal Fourier mode on N
 * Gauss-Legendre cosines per hemisphere (plus the beam's and the views' cosines at zero weight)
 * by doubling from a layer of tau 2^-n thin enough for single scattering, and the exact phase
 * function's single scattering put back in place of the truncated one (the TMS correction of
 * Nakajima & Tanaka 1988). */
#ifndef ATMO_TESTSLAB_H
#define ATMO_TESTSLAB_H

typedef double (*slab_phase_fn)(double cos_theta, const void *ctx);

typedef struct slab_problem {
    double tau, omega, mu0;
    slab_phase_fn phase; /* p(cos theta) per steradian */
    const void *ctx;
    int streams;         /* N, Gauss cosines per hemisphere */
    int moments;         /* M <= 2N, Legendre moments kept by delta-M (0: 2N) */
} slab_problem;

typedef struct slab_fluxes {
    double reflected, diffuse, direct; /* fluxes over the incident mu0: albedo, diffuse and
                                          direct transmission of the truncated problem (they add
                                          up to 1 where omega = 1) */
    double truncated;                  /* f, the delta-M forward fraction */
} slab_fluxes;

/* Legendre moments chi_l = 2 pi int p(mu) P_l(mu) dmu, l = 0..count-1 (chi_0 = 1 for a
 * normalised p), by Gauss quadrature on a grid in theta refined toward 0 (forward peaks). */
void slab_moments(slab_phase_fn phase, const void *ctx, int count, double *chi);

/* Radiance (per unit irradiance) reflected (refl[i]) and diffusely transmitted (trans[i]) at
 * the n views (mu[i], phi[i] in radians); fluxes into *f when f is not NULL. Returns 0, or -1
 * on a singular system or bad input. */
int slab_solve(const slab_problem *p, int n, const double *mu, const double *phi, double *refl,
               double *trans, slab_fluxes *f);

#endif
