/* atmosphere.h — the physical atmosphere model, in double precision on the host.
 *
 * One struct describes the planet's atmosphere at the three render wavelengths; the scene
 * fills it (host/atmosphere_model.c), the host references use it directly, and it is converted to
 * the float struct that kernels read (atmo_gpu_atmosphere in gpu_types.h).
 *
 * Model (Bruneton 2017, defaults in shared/reference/atmosphere.md):
 *   Rayleigh:  sigma_s(h) = beta_R * exp(-h / H_R), no absorption, phase 3(1+nu^2)/(16 pi)
 *   Mie:       sigma_s(h) = beta_M,s * exp(-h / H_M), sigma_t = beta_M,t * exp(-h / H_M),
 *              phase Cornette-Shanks(g) or Henyey-Greenstein(g)
 *   ozone:     sigma_a(h) = beta_O * tent(h): 0 below ozone_bottom, linear up to 1 at ozone_peak,
 *              linear down to 0 at ozone_top
 *   ground:    Lambertian sphere of radius bottom_radius with albedo rho (BRDF rho/pi)
 *   sun:       a disc of angular radius sun_angular_radius, irradiance E at the top.
 * h is the altitude above bottom_radius in metres; all coefficients are per metre. */
#ifndef ATMO_ATMOSPHERE_H
#define ATMO_ATMOSPHERE_H

#include "atmo/gpu_enums.h"

typedef struct atmo_atmosphere {
    double wavelengths_nm[3];
    double bottom_radius_m, top_radius_m;
    double rayleigh_scattering_per_m[3];
    double rayleigh_scale_height_m;
    double mie_scattering_per_m[3];
    double mie_extinction_per_m[3];
    double mie_scale_height_m;
    double mie_g;
    int mie_phase; /* ATMO_PHASE_* (gpu_enums.h) */
    double ozone_absorption_per_m[3]; /* at the peak of the tent */
    double ozone_bottom_m, ozone_peak_m, ozone_top_m;
    double ground_albedo[3];
    double solar_irradiance[3]; /* W m^-2 nm^-1 at the top of the atmosphere */
    double sun_angular_radius_rad;
} atmo_atmosphere;

struct atmo_scene;
struct atmo_err;
/* The model at the scene's render wavelengths (host/atmosphere_model.c): Rayleigh
 * c·lambda[um]^-4, Mie scattering = extinction × albedo, ozone peak absorption = O3 cross-section
 * × peak density of the column, solar irradiance × irradiance_scale, angles in radians. */
int atmo_atmosphere_from_scene(const struct atmo_scene *s, atmo_atmosphere *a,
                               struct atmo_err *e);

#endif
