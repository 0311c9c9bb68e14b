/* phase.h — phase functions, per steradian (each integrates to 1 over the sphere).
 *
 * nu is the cosine of the scattering angle (1 = forward).
 *   Rayleigh:          p(nu) = 3 (1 + nu^2) / (16 pi)
 *   Henyey-Greenstein: p(nu) = (1 - g^2) / (4 pi (1 + g^2 - 2 g nu)^(3/2))
 *   Cornette-Shanks:   p(nu) = 3/(8 pi) (1 - g^2)/(2 + g^2) (1 + nu^2)/(1 + g^2 - 2 g nu)^(3/2)
 *                      (Cornette & Shanks 1992, eq. 4; its mean cosine is 3g(4+g^2)/(5(2+g^2)))
 * Shared by kernels and host tests (compat.h). */
#ifndef ATMO_PHASE_H
#define ATMO_PHASE_H
#ifndef __OPENCL_VERSION__
#include "compat.h"
#endif

ATMO_FN float phase_rayleigh(float nu)
{
    return 3.0f / (16.0f * ATMO_PI) * (1.0f + nu * nu);
}

ATMO_FN float phase_henyey_greenstein(float nu, float g)
{
    float denom = 1.0f + g * g - 2.0f * g * nu;
    return (1.0f - g * g) / (4.0f * ATMO_PI * denom * sqrtf(denom));
}

ATMO_FN float phase_cornette_shanks(float nu, float g)
{
    float denom = 1.0f + g * g - 2.0f * g * nu;
    return 3.0f / (8.0f * ATMO_PI) * (1.0f - g * g) / (2.0f + g * g) * (1.0f + nu * nu) /
           (denom * sqrtf(denom));
}

#endif
