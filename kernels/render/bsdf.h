/* bsdf.h — the Lambertian BRDF f = albedo / pi and its cosine-weighted sampling.
 *
 * Sampling (Malley's method): a point uniform on the unit disc, r = sqrt(u1), phi = 2 pi u2,
 * lifted to the hemisphere around n, gives the direction (r cos phi, r sin phi, sqrt(1 - u1))
 * in the frame (t, b, n) with density p(w) = cos(theta) / pi per steradian (pbrt-v4 sec.
 * A.5.3). So f cos / p = albedo: a bounce's weight is the albedo itself. The frame around n is
 * frame.h's (Duff et al. 2017). */
#ifndef ATMO_RENDER_BSDF_H
#define ATMO_RENDER_BSDF_H
#ifndef __OPENCL_VERSION__
#include "common/compat.h"
#include "common/frame.h"
#endif

/* The direction of (u1, u2) in the hemisphere around n, cosine-distributed. */
ATMO_FN vec3 bsdf_sample_cosine(vec3 n, float u1, float u2)
{
    vec3 t, b;
    frame_basis(n, &t, &b);
    float r = sqrtf(u1), phi = 2.0f * ATMO_PI * u2;
    float z = sqrtf(fmaxf(1.0f - u1, 0.0f));
    return v3_add(v3_add(v3_scale(t, r * cosf(phi)), v3_scale(b, r * sinf(phi))),
                  v3_scale(n, z));
}

/* Its density per steradian at w. */
ATMO_FN float bsdf_pdf_cosine(vec3 n, vec3 w)
{
    return fmaxf(v3_dot(n, w), 0.0f) * (1.0f / ATMO_PI);
}

#endif
