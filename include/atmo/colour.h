/* colour.h — from spectral radiance at the render wavelengths to luminance and linear sRGB.
 *
 * Bruneton's radiance-to-luminance constants (Bruneton 2016, "A Qualitative and Quantitative
 * Evaluation of 8 Clear Sky Models", §14.3; Bruneton 2017, model.cc): a spectrum that is the
 * solar spectrum S times (lambda / lambda_c)^p, known only at lambda_c, has the linear sRGB
 * luminance k_c · L(lambda_c) in channel c, with
 *     k_c = 683 lm/W · sum_{lambda = 360..829 nm, 1 nm} rgb_c(lambda) S(lambda)/S(lambda_c)
 *                                                       (lambda/lambda_c)^p · 1 nm
 * p = -3 for the sky (Rayleigh-like), p = 0 for the sun. rgb_c = CIE 1931 2° CMF (linear
 * between 5 nm nodes, 0 at and outside 360 and 830 nm) times the XYZ -> linear sRGB matrix;
 * S = ASTM G-173 (linear between 10 nm nodes, clamped). Units: k_c in lm nm W^-1, so
 * cd/m^2 = k_c × W m^-2 sr^-1 nm^-1. Spectral tables: data/ (data/README.md). */
#ifndef ATMO_COLOUR_H
#define ATMO_COLOUR_H

#define ATMO_MAX_LUMINOUS_EFFICACY 683.0 /* lm/W, at 555 nm */

/* k_c for the three channel wavelengths (nm) and exponent p. */
void atmo_luminance_factors(const double wavelengths_nm[3], double p, double out_k[3]);

/* Linear sRGB (cd/m^2 per channel for a radiance spectrum in W m^-2 sr^-1 nm^-1) of a spectrum
 * given at n increasing wavelengths, interpolated linearly and clamped outside them:
 * 683 · sum_{360..829 nm} M · (xbar, ybar, zbar)(lambda) · spectrum(lambda) · 1 nm. */
void atmo_spectrum_to_srgb(int n, const double *wavelengths_nm, const double *values,
                           double out_rgb[3]);

/* The sun's colour: the solar spectrum in linear sRGB, normalised to a mean of 1 over the three
 * channels (divide by it to white-balance so sunlight is white). */
void atmo_solar_white_point(double out_rgb[3]);

/* Relative luminance of linear sRGB (ITU-R BT.709): Y = 0.2126 R + 0.7152 G + 0.0722 B. */
double atmo_luminance(const double rgb[3]);

/* Y of k_c · L_c: the luminance (cd/m^2) of a radiance L at the render wavelengths. */
double atmo_luminance_from_radiance(const double k[3], const double radiance[3]);

#endif
