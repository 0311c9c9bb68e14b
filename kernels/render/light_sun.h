/* light_sun.h — next-event estimation to the sun: a direction sampled uniformly over the sun's
 * disc, the cone of half-angle alpha around the direction s to its centre.
 *
 * Uniform in solid angle over the cone: cos(theta) = 1 - u1 (1 - cos alpha), phi = 2 pi u2
 * around s, density 1 / Omega with Omega = 2 pi (1 - cos alpha) (pbrt-v4 sec. A.5.4). The
 * disc's radiance is E_sun T_sun / Omega (the method's disc: atmosphere_sun_disc_radiance), so
 * the estimate f L cos / p of the sunlight a Lambertian surface reflects is
 *     albedo / pi E_sun T_sun V max(0, n . w),
 * with T_sun the atmosphere's transmittance toward the sun from the point (the transmittance
 * LUT, at the disc centre's cosine: the disc is 0.5 degrees wide), V the visibility sources
 * (visibility_sun_surface: the planet, the shadowing media) and the objects' and the terrain's
 * test along w itself (surfaces.h), so their shadows have the penumbra of the disc. */
#ifndef ATMO_RENDER_LIGHT_SUN_H
#define ATMO_RENDER_LIGHT_SUN_H
#ifndef __OPENCL_VERSION__
#include "common/compat.h"
#include "render/bsdf.h"
#endif

/* A direction uniform over the cone of cosine cos_alpha around the unit vector s. */
ATMO_FN vec3 light_sun_sample(vec3 s, float cos_alpha, float u1, float u2)
{
    vec3 t, b;
    frame_basis(s, &t, &b);
    float c = 1.0f - u1 * (1.0f - cos_alpha);
    float sn = sqrtf(fmaxf(1.0f - c * c, 0.0f)), phi = 2.0f * ATMO_PI * u2;
    return v3_add(v3_add(v3_scale(t, sn * cosf(phi)), v3_scale(b, sn * sinf(phi))),
                  v3_scale(s, c));
}

/* Its density per steradian at w (0 outside the cone). */
ATMO_FN float light_sun_pdf(vec3 s, float cos_alpha, vec3 w)
{
    return v3_dot(s, w) >= cos_alpha ? 1.0f / (2.0f * ATMO_PI * (1.0f - cos_alpha)) : 0.0f;
}

#endif
