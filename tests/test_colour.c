/* test_colour.c — radiance-to-luminance constants, white point and luminance.
 * labels: unit
 *
 * Oracle: published values (shared/reference/atmosphere.md, reproduced independently in
 * shared/data/README.md): Bruneton's k_sky and k_sun at 680/550/440 nm, printed to 6 decimals (the
 * README's independent computation agrees to < 5e-7 absolute, i.e. < 1e-11 relative), so they are
 * checked to 1e-9 relative, well inside the 1e-6 required of them. The white point is printed to 5
 * decimals: checked to half a unit of the last digit (5e-6). The sun's luminance at the top,
 * 1.930e9 cd/m^2 (4 digits), to half a unit (5e5). The luminance weights are BT.709's. */
#include "atmo/colour.h"
#include "atmo/spectral.h"
#include "testlib.h"

int main(void)
{
    const double wl[3] = {680.0, 550.0, 440.0};
    const double k_sky_want[3] = {114974.916437, 71305.954816, 65310.548555};
    const double k_sun_want[3] = {98242.786222, 69954.398112, 66475.012354};
    double k_sky[3], k_sun[3], white[3];
    atmo_luminance_factors(wl, -3.0, k_sky);
    atmo_luminance_factors(wl, 0.0, k_sun);
    for (int c = 0; c < 3; c++) {
        printf("k_sky[%d] = %.6f  k_sun[%d] = %.6f\n", c, k_sky[c], c, k_sun[c]);
        CHECK_REL(k_sky[c], k_sky_want[c], 1e-9);
        CHECK_REL(k_sun[c], k_sun_want[c], 1e-9);
    }

    atmo_solar_white_point(white);
    const double white_want[3] = {1.08241, 0.96756, 0.95003};
    printf("white point = %.7f %.7f %.7f\n", white[0], white[1], white[2]);
    for (int c = 0; c < 3; c++)
        CHECK_ABS(white[c], white_want[c], 5e-6);
    CHECK_ABS((white[0] + white[1] + white[2]) / 3.0, 1.0, 1e-15);

    /* the sun's luminance at the top: k_sun · E / (pi r^2) with r = 0.004675 rad */
    const double E[3] = {1.474, 1.8504, 1.91198};
    const double solid_angle = 3.14159265358979323846 * 0.004675 * 0.004675;
    double L_sun[3];
    for (int c = 0; c < 3; c++)
        L_sun[c] = E[c] / solid_angle;
    double y_sun = atmo_luminance_from_radiance(k_sun, L_sun);
    printf("sun luminance = %.4e cd/m^2\n", y_sun);
    CHECK_ABS(y_sun, 1.930e9, 0.5e6);

    /* luminance of the sRGB primaries and of white */
    CHECK_ABS(atmo_luminance((double[3]){1, 0, 0}), 0.2126, 1e-15);
    CHECK_ABS(atmo_luminance((double[3]){0, 1, 0}), 0.7152, 1e-15);
    CHECK_ABS(atmo_luminance((double[3]){0, 0, 1}), 0.0722, 1e-15);
    CHECK_ABS(atmo_luminance((double[3]){1, 1, 1}), 1.0, 1e-15);

    /* The two paths of colour.c must agree: k_sun,c = 683 sum rgb_c S / S(lambda_c) is the
     * linear sRGB of the solar spectrum divided by S(lambda_c) (identical sums: rounding only). */
    const double solar_wl[4] = {430.0, 440.0, 550.0, 680.0};
    double solar[4], rgb_sun[3];
    for (int i = 0; i < 4; i++)
        solar[i] = spectral_solar_irradiance(solar_wl[i]);
    CHECK_ABS(solar[1], 1.91198, 0.0);
    CHECK_ABS(solar[2], 1.8504, 0.0);
    CHECK_ABS(solar[3], 1.474, 0.0);
    atmo_solar_white_point(white); /* and it is normalised from the same conversion */
    const spectral_table *t = spectral_table_get("data/astm_g173_extraterrestrial.csv");
    double table_wl[64], table_v[64];
    CHECK(t && t->rows <= 64);
    for (int i = 0; i < t->rows && i < 64; i++) {
        table_wl[i] = t->values[i * t->columns];
        table_v[i] = t->values[i * t->columns + 1];
    }
    atmo_spectrum_to_srgb(t->rows, table_wl, table_v, rgb_sun);
    for (int c = 0; c < 3; c++) {
        CHECK_REL(rgb_sun[c] / solar[3 - c], k_sun[c], 1e-12);
        CHECK_REL(rgb_sun[c] / ((rgb_sun[0] + rgb_sun[1] + rgb_sun[2]) / 3.0), white[c], 1e-12);
    }

    /* An equal-energy spectrum of 1 W m^-2 sr^-1 nm^-1 has Y = 683 × sum_{361..829} ybar: the
     * CMF table's 5 nm sum is 106.857 (data/README.md) and the 1 nm sum of its linear
     * interpolation differs by the end terms only (< 1e-4 relative); the sRGB matrix's 4-digit
     * rounding makes Y from R, G, B differ from ybar by up to ~2e-4 relative. */
    const double flat_wl[2] = {360.0, 830.0}, flat[2] = {1.0, 1.0};
    double rgb_flat[3];
    atmo_spectrum_to_srgb(2, flat_wl, flat, rgb_flat);
    double y_flat = atmo_luminance(rgb_flat);
    printf("equal-energy Y = %.3f cd/m^2\n", y_flat);
    CHECK_REL(y_flat, 683.0 * 106.857, 5e-4);
    return test_finish();
}
