/* atmosphere_model.c — the scene's atmosphere at the three render wavelengths.
 *
 * From the user's parameters (scene.h) to the per-wavelength model of atmosphere.h:
 *   Rayleigh scattering  beta_R(lambda) = c · (lambda / 1 um)^-4            [1/m], c in m^-1 um^4
 *   Mie                  beta_M,t = extinction (Angstrom alpha = 0: the same at every lambda),
 *                        beta_M,s = extinction × single-scattering albedo   [1/m]
 *   ozone                beta_O(lambda) = sigma_O3(lambda) · n_peak         [1/m], where n_peak
 *                        spreads the column (DU, 1 DU = 2.687e20 m^-2) over the tent of width
 *                        ozone_top - ozone_bottom (its integral is width / 2)
 *   solar irradiance     E(lambda) = ASTM G-173(lambda) × irradiance_scale  [W m^-2 nm^-1]
 *   sun angular radius   degrees -> radians.
 * With Bruneton 2017's Earth (the scene defaults) and 680/550/440 nm this gives the constants of
 * shared/reference/atmosphere.md (tests/test_atmosphere_ref.c checks it). */
#include <math.h>
#include "atmo/atmosphere.h"
#include "atmo/atmosphere_ref.h"
#include "atmo/scene.h"
#include "atmo/spectral.h"
#include "atmo/status.h"

int atmo_atmosphere_from_scene(const atmo_scene *s, atmo_atmosphere *a, atmo_err *e)
{
    if (!spectral_table_get("data/astm_g173_extraterrestrial.csv") ||
        !spectral_table_get("data/ozone_cross_section.csv"))
        return atmo_fail(e, ATMO_ERR_RUNTIME,
                         "spectral tables missing from the binary (data/*.csv); rebuild atmo");
    double tent_width = s->atmosphere.ozone_top_m - s->atmosphere.ozone_bottom_m;
    if (s->atmosphere.ozone_column_du > 0.0 && !(tent_width > 0.0))
        return atmo_fail(e, ATMO_ERR_USAGE,
                         "ozone layer has no thickness (atmosphere.ozone_top_m %.9g m <= "
                         "atmosphere.ozone_bottom_m %.9g m); raise the top or set "
                         "atmosphere.ozone_column_du=0",
                         s->atmosphere.ozone_top_m, s->atmosphere.ozone_bottom_m);
    double ozone_density = s->atmosphere.ozone_column_du > 0.0
                               ? spectral_ozone_peak_density_per_m3(s->atmosphere.ozone_column_du,
                                                                    tent_width)
                               : 0.0;

    a->bottom_radius_m = s->atmosphere.bottom_radius_m;
    a->top_radius_m = s->atmosphere.top_radius_m;
    a->rayleigh_scale_height_m = s->atmosphere.rayleigh_scale_height_m;
    a->mie_scale_height_m = s->atmosphere.mie_scale_height_m;
    a->mie_g = s->atmosphere.mie_g;
    a->mie_phase = s->atmosphere.mie_phase;
    a->ozone_bottom_m = s->atmosphere.ozone_bottom_m;
    a->ozone_peak_m = s->atmosphere.ozone_peak_m;
    a->ozone_top_m = s->atmosphere.ozone_top_m;
    a->sun_angular_radius_rad = s->sun.angular_radius_deg * (ATMO_REF_PI / 180.0);
    for (int c = 0; c < 3; c++) {
        double lambda = s->render.wavelengths_nm[c];
        double lambda_um = lambda * 1e-3;
        a->wavelengths_nm[c] = lambda;
        a->rayleigh_scattering_per_m[c] =
            s->atmosphere.rayleigh_coefficient / (lambda_um * lambda_um * lambda_um * lambda_um);
        a->mie_extinction_per_m[c] = s->atmosphere.mie_extinction_per_m;
        a->mie_scattering_per_m[c] = s->atmosphere.mie_extinction_per_m * s->atmosphere.mie_albedo;
        a->ozone_absorption_per_m[c] = spectral_ozone_cross_section_m2(lambda) * ozone_density;
        a->ground_albedo[c] = s->atmosphere.ground_albedo;
        a->solar_irradiance[c] = spectral_solar_irradiance(lambda) * s->sun.irradiance_scale;
    }
    return ATMO_OK;
}
