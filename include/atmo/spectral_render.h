/* spectral_render.h — the spectral mode: many wavelengths, combined through the CIE 1931 CMFs.
 *
 * Bands. N equal bands cover 360–830 nm (width h = 470/N nm); band i is rendered at its centre
 * lambda_i = 360 + (i + 1/2) h. N >= 15 (ATMO_SPECTRAL_MIN_BANDS; scene key
 * render.spectral_bands, 0 = the 3-wavelength mode).
 *
 * Quadrature. XYZ = 683 lm/W · ∫ cmf(lambda) L(lambda) dlambda, written as a weighted sum of the
 * band radiances, XYZ = sum_i W_i L(lambda_i), with
 *     W_i = 683 · sum_{lambda = 360..829 nm, 1 nm} cmf(lambda) · S(lambda)/S(lambda_i) · phi_i(lambda)
 * where S is the solar spectrum (ASTM G-173) and phi_i the cardinal functions of piecewise cubic
 * interpolation between band centres (on each interval the Lagrange cubic through the two
 * centres around it and one more on each side, shifted inward at the ends; constant beyond the
 * first and last centre, where the CMFs are below 1e-3 of their peak): the quadrature
 * interpolates the smooth ratio L/S and integrates the rest (the jagged solar spectrum and the
 * CMFs) at 1 nm with Bruneton's recipe (the 1 nm sum of colour.c). Why not the plain midpoint
 * rule sum_i cmf(lambda_i) L(lambda_i) h: the sky's spectrum is the sun's (a 10 nm table with
 * Fraunhofer structure) times a smooth atmospheric response, and at h = 31 nm the midpoint rule
 * samples the jagged factor and the CMF lobes (xbar's blue lobe is ~40 nm wide) too coarsely:
 * the sun's own spectrum then misses colour.c's white point by 1.5e-2 (4.5e-3 at 30 bands).
 * Here the sun's spectrum maps to the white point to rounding (the cardinal functions sum to
 * 1), and a smooth L/S is integrated with the fourth-order error of cubic interpolation,
 * about 0.023 h^4 max|d^4(L/S)/dlambda^4|: measured against the 1 nm sum, at most 2e-3 of Y at
 * 15 bands for the test spectra, 16x less per halving of h (tests/test_spectral_mode.c). The
 * weights are Bruneton's radiance-to-luminance constants (colour.h) generalised from 3 to N
 * wavelengths, with p = 0 and a cubic instead of a power-law interpolation of L/S.
 *
 * Output. Linear sRGB (XYZ -> sRGB matrix of IEC 61966-2-1, as colour.c) in cd/m^2: the image
 * the 3-wavelength mode gives with render.quantity=luminance, computed from N wavelengths
 * instead of 3. The sun disc is included like any radiance. */
#ifndef ATMO_SPECTRAL_RENDER_H
#define ATMO_SPECTRAL_RENDER_H
#include "atmo/render.h"
#include "atmo/scene.h"
#include "atmo/status.h"

#define ATMO_SPECTRAL_LAMBDA_MIN_NM 360.0
#define ATMO_SPECTRAL_LAMBDA_MAX_NM 830.0

/* Band centres (nm) of n bands, n in [1, ATMO_SPECTRAL_MAX_BANDS]. */
void atmo_spectral_bands(int n, double *centres_nm);

/* Weights W_i (see above), n x 3: XYZ (cd/m^2 per W m^-2 sr^-1 nm^-1) for the radiance at
 * centre i. centres_nm increasing, n >= 2. */
void atmo_spectral_xyz_weights(int n, const double *centres_nm, double (*w)[3]);

/* XYZ <-> linear sRGB (IEC 61966-2-1). */
void atmo_xyz_to_linear_srgb(const double xyz[3], double rgb[3]);
void atmo_linear_srgb_to_xyz(const double rgb[3], double xyz[3]);


/* Render s in spectral mode with s->render.spectral_bands bands: the wavelengths are set to
 * successive triplets of band centres (the last triplet padded by repeating its last centre),
 * each triplet planned and rendered as radiance with the scene's seed (so the noise of the
 * bands is correlated and the colour noise small), and the band images are combined into
 * linear sRGB (cd/m^2). All triplets share one render session and so one kernel build: a
 * triplet changes only the scene struct, the host tables and the LUTs (atmo_session_set_scene).
 * cache_luts as atmo_plan.cache_luts. With rs->progress a line per triplet goes to stderr.
 * result->rgb is the combined image; timings are sums over triplets. A cancel (rs->cancel)
 * fails the render (a partial set of bands has no meaningful colour). */
int atmo_spectral_render(const atmo_scene *s, int cache_luts, const atmo_render_settings *rs,
                         atmo_render_result *result, atmo_err *e);

#endif
