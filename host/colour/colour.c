/* colour.c — Bruneton's radiance-to-luminance constants, spectrum to linear sRGB, white point.
 *
 * The exact recipe (data/README.md, last section) reproduces Bruneton 2017's constants to all
 * printed digits: 1 nm steps from 360 to 829 nm without end weights, CMFs that are zero at and
 * beyond 360 and 830 nm, the solar table clamped, S(lambda_c) read by the same interpolation. */
#include <math.h>
#include "atmo/colour.h"
#include "atmo/spectral.h"

#define COLOUR_LAMBDA_MIN 360
#define COLOUR_LAMBDA_MAX 830

/* XYZ -> linear sRGB (IEC 61966-2-1, as Bruneton 2017 uses it). */
static const double colour_xyz_to_srgb[3][3] = {
    {3.2406, -1.5372, -0.4986},
    {-0.9689, 1.8758, 0.0415},
    {0.0557, -0.2040, 1.0570},
};

/* rgb_c(lambda): the CMFs in linear sRGB; zero at and beyond the ends of the table, as in
 * Bruneton's code (the lambda = 360 term contributes nothing). */
static void colour_cmf_srgb(double lambda_nm, double rgb[3])
{
    const spectral_table *cmf = spectral_table_get("data/cie1931_2deg_cmf.csv");
    double xyz[3] = {0.0, 0.0, 0.0};
    if (lambda_nm > COLOUR_LAMBDA_MIN && lambda_nm < COLOUR_LAMBDA_MAX)
        for (int i = 0; i < 3; i++)
            xyz[i] = spectral_table_lookup(cmf, i + 1, lambda_nm);
    for (int c = 0; c < 3; c++)
        rgb[c] = colour_xyz_to_srgb[c][0] * xyz[0] + colour_xyz_to_srgb[c][1] * xyz[1] +
                 colour_xyz_to_srgb[c][2] * xyz[2];
}

void atmo_luminance_factors(const double wavelengths_nm[3], double p, double out_k[3])
{
    double s_c[3];
    for (int c = 0; c < 3; c++) {
        s_c[c] = spectral_solar_irradiance(wavelengths_nm[c]);
        out_k[c] = 0.0;
    }
    for (int lambda = COLOUR_LAMBDA_MIN; lambda < COLOUR_LAMBDA_MAX; lambda++) {
        double rgb[3];
        colour_cmf_srgb(lambda, rgb);
        double s = spectral_solar_irradiance(lambda);
        for (int c = 0; c < 3; c++)
            out_k[c] += rgb[c] * s / s_c[c] * pow(lambda / wavelengths_nm[c], p);
    }
    for (int c = 0; c < 3; c++)
        out_k[c] *= ATMO_MAX_LUMINOUS_EFFICACY;
}

/* Linear interpolation in (wavelengths, values) read with a stride, clamped to the end values. */
static double colour_interpolate(int n, const double *wl, const double *v, int stride,
                                   double lambda)
{
    if (lambda <= wl[0])
        return v[0];
    for (int i = 1; i < n; i++)
        if (lambda < wl[i * stride]) {
            double w0 = wl[(i - 1) * stride], w1 = wl[i * stride];
            double v0 = v[(i - 1) * stride], v1 = v[i * stride];
            return v0 + (v1 - v0) * (lambda - w0) / (w1 - w0);
        }
    return v[(n - 1) * stride];
}

/* The stride lets the white point read a spectral table's rows in place. */
static void colour_spectrum_to_srgb(int n, const double *wl, const double *v, int stride,
                                      double out_rgb[3])
{
    out_rgb[0] = out_rgb[1] = out_rgb[2] = 0.0;
    for (int lambda = COLOUR_LAMBDA_MIN; lambda < COLOUR_LAMBDA_MAX; lambda++) {
        double rgb[3];
        colour_cmf_srgb(lambda, rgb);
        double value = colour_interpolate(n, wl, v, stride, lambda);
        for (int c = 0; c < 3; c++)
            out_rgb[c] += rgb[c] * value;
    }
    for (int c = 0; c < 3; c++)
        out_rgb[c] *= ATMO_MAX_LUMINOUS_EFFICACY;
}

void atmo_spectrum_to_srgb(int n, const double *wavelengths_nm, const double *values,
                           double out_rgb[3])
{
    colour_spectrum_to_srgb(n, wavelengths_nm, values, 1, out_rgb);
}

void atmo_solar_white_point(double out_rgb[3])
{
    const spectral_table *s = spectral_table_get("data/astm_g173_extraterrestrial.csv");
    colour_spectrum_to_srgb(s->rows, s->values, s->values + 1, s->columns, out_rgb);
    double mean = (out_rgb[0] + out_rgb[1] + out_rgb[2]) / 3.0;
    for (int c = 0; c < 3; c++)
        out_rgb[c] /= mean;
}

double atmo_luminance(const double rgb[3])
{
    return 0.2126 * rgb[0] + 0.7152 * rgb[1] + 0.0722 * rgb[2];
}

double atmo_luminance_from_radiance(const double k[3], const double radiance[3])
{
    double rgb[3] = {k[0] * radiance[0], k[1] * radiance[1], k[2] * radiance[2]};
    return atmo_luminance(rgb);
}
