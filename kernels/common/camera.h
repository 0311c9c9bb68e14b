/* camera.h — primary ray directions.
 *
 * Perspective: a pinhole with vertical field of view fov; pixel (x, y) with sub-pixel offset
 * (jx, jy) in [0, 1)^2 maps to
 *     d = normalize(forward + s_x right + s_y up),  s_x = (2 (x + jx)/W - 1) tan(fov/2) W/H,
 *                                                   s_y = (1 - 2 (y + jy)/H) tan(fov/2).
 * Panorama: equirectangular over the full sphere (the layout of environment maps): the column
 * gives the azimuth phi = 2 pi (u - 1/2) measured from the camera's horizontal forward towards its
 * right, the row the elevation theta = pi (1/2 - v) above the horizontal plane of the world (+Y),
 * so the image centre looks along the camera's yaw at the horizon, the top row at the zenith.
 * Random numbers: the camera draws the first CAMERA_RNG_DIMS numbers of a sample's stage-0 stream
 * (rng.h), the sub-pixel offset (jx, jy); the primary ray's integrator continues that stream. */
#ifndef ATMO_CAMERA_H
#define ATMO_CAMERA_H
#ifndef __OPENCL_VERSION__
#include "common/compat.h"
#include "atmo/gpu_types.h"
#endif

#define CAMERA_RNG_DIMS 2u

ATMO_FN vec3 camera_ray(ATMO_GLOBAL const atmo_gpu_camera *c, float x, float y)
{
    float w = (float)c->width, h = (float)c->height;
    if (c->kind == ATMO_CAMERA_PANORAMA) {
        float phi = 2.0f * ATMO_PI * (x / w - 0.5f);
        float theta = ATMO_PI * (0.5f - y / h);
        /* the host sets forward/right horizontal and up = +Y for panoramas (pitch ignored) */
        vec3 horizontal = v3_add(v3_scale(v3_from4(c->right), sinf(phi)),
                                 v3_scale(v3_from4(c->forward), cosf(phi)));
        return v3_add(v3_scale(horizontal, cosf(theta)), v3_scale(v3_from4(c->up), sinf(theta)));
    }
    float sx = (2.0f * x / w - 1.0f) * c->tan_half_fov * w / h;
    float sy = (1.0f - 2.0f * y / h) * c->tan_half_fov;
    vec3 d = v3_add(v3_from4(c->forward),
                    v3_add(v3_scale(v3_from4(c->right), sx), v3_scale(v3_from4(c->up), sy)));
    return v3_normalize(d);
}

#endif
