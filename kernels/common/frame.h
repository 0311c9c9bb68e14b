/* frame.h — an orthonormal frame around a unit vector, and the direction at a given cosine and
 * azimuth around it (the rotation that phase and BSDF samplers, which draw cosines to an axis,
 * need to make a direction).
 *
 * The frame is the branch-free basis of Duff et al. 2017 ("Building an orthonormal basis,
 * revisited", JCGT 6(1)): with s = sign(n_z) and a = -1 / (s + n_z),
 *     t = (1 + s n_x^2 a, s n_x n_y a, -s n_x),   b = (n_x n_y a, s + n_y^2 a, -n_y),
 * so (t, b, n) is right-handed to float rounding for every unit n. A direction at cosine c to n
 * and azimuth phi is then sqrt(1 - c^2) (cos phi t + sin phi b) + c n. */
#ifndef ATMO_FRAME_H
#define ATMO_FRAME_H
#ifndef __OPENCL_VERSION__
#include "common/compat.h"
#endif

/* Unit t, b with (t, b, n) orthonormal and right-handed. */
ATMO_FN void frame_basis(vec3 n, vec3 *t, vec3 *b)
{
    float sign = n.z >= 0.0f ? 1.0f : -1.0f;
    float a = -1.0f / (sign + n.z), c = n.x * n.y * a;
    *t = v3(1.0f + sign * n.x * n.x * a, sign * c, -sign * n.x);
    *b = v3(c, sign + n.y * n.y * a, -n.y);
}

/* The unit vector at cosine c to the unit vector n, with azimuth phi (radians) around it. */
ATMO_FN vec3 frame_direction(vec3 n, float c, float phi)
{
    vec3 t, b;
    frame_basis(n, &t, &b);
    float s = atmo_safe_sqrt(1.0f - c * c);
    return v3_normalize(v3_add(v3_add(v3_scale(t, s * cosf(phi)), v3_scale(b, s * sinf(phi))),
                               v3_scale(n, c)));
}

#endif
