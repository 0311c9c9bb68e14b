/* camera.h — primary ray directions for a point (x, y) of the image plane, in pixels from the
 * top-left corner (a pixel's centre is at its index + 1/2), W x H pixels.
 *
 * Perspective: a pinhole with vertical field of view fov (c->tan_half_fov = tan(fov/2)):
 *     d = normalize(forward + s_x right + s_y up),  s_x = (2 x/W - 1) tan(fov/2) W/H,
 *                                                   s_y = (1 - 2 y/H) tan(fov/2).
 * Panorama: equirectangular over the full sphere, in the layout of Blender's World >
 * Environment Texture (Cycles' equirectangular mapping) with the camera's horizontal forward as
 * Blender's +X and the world's up (+Y) as Blender's +Z: the column gives the azimuth
 * phi = 2 pi (x/W - 1/2) from the forward direction toward the camera's right (Blender's -Y),
 * the row the elevation theta = pi (1/2 - y/H) above the horizon, so the image centre looks
 * along the camera's yaw at the horizon, the top row at the zenith, and
 *     d = cos theta (cos phi forward + sin phi right) + sin theta up.
 * The world's axes map to Blender's as (X, Y, Z)_blender = (X, Z, Y)_atmo (atmo's camera frame,
 * the thesis', is left-handed: right x up = forward), so a panorama with camera.yaw_deg = -90
 * (forward = atmo +X) is the environment map of that Blender world as it is, atmo +Z at
 * u = 1/4 (Blender +Y); for another yaw the map's centre (Blender's +X) is the camera's forward
 * instead. The host sets forward and right horizontal and up = +Y for panoramas (pitch ignored).
 * Fisheye: equal-area (Lambert azimuthal) projection around forward, the circle of the field of
 * view fov inscribed in the frame's height and round whatever the aspect: with
 * (s_x, s_y) = ((2 x/W - 1) W/H, 1 - 2 y/H) and rho = |(s_x, s_y)|, the angle to the axis is
 * theta = 2 asin(rho sin(fov/4)) (c->tan_half_fov holds sin(fov/4) for this kind), so equal
 * areas of the image hold equal solid angles; points outside the circle (rho > 1) see nothing
 * and camera_ray returns the zero vector there.
 * Random numbers: sky_render draws the first CAMERA_RNG_DIMS numbers of a sample's stage-0
 * stream (rng.h) for the sub-pixel offset; the primary ray's integrator continues that stream.
 * The path tracer places its samples with its own sequence (render/path_camera.h). */
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
    vec3 forward = v3_from4(c->forward), right = v3_from4(c->right), up = v3_from4(c->up);
    if (c->kind == ATMO_CAMERA_PANORAMA) {
        float phi = 2.0f * ATMO_PI * (x / w - 0.5f);
        float theta = ATMO_PI * (0.5f - y / h);
        vec3 horizontal = v3_add(v3_scale(right, sinf(phi)), v3_scale(forward, cosf(phi)));
        return v3_add(v3_scale(horizontal, cosf(theta)), v3_scale(up, sinf(theta)));
    }
    float sx = (2.0f * x / w - 1.0f) * w / h;
    float sy = 1.0f - 2.0f * y / h;
    if (c->kind == ATMO_CAMERA_FISHEYE) {
        float rho = sqrtf(sx * sx + sy * sy);
        if (rho > 1.0f)
            return v3(0.0f, 0.0f, 0.0f);
        float theta = 2.0f * asinf(fminf(rho * c->tan_half_fov, 1.0f));
        /* sin(theta) / rho, with its limit 2 sin(fov/4) at the centre */
        float k = rho > 1e-6f ? sinf(theta) / rho : 2.0f * c->tan_half_fov;
        vec3 side = v3_add(v3_scale(right, sx * k), v3_scale(up, sy * k));
        return v3_normalize(v3_add(v3_scale(forward, cosf(theta)), side));
    }
    vec3 d = v3_add(forward, v3_add(v3_scale(right, sx * c->tan_half_fov),
                                    v3_scale(up, sy * c->tan_half_fov)));
    return v3_normalize(d);
}

#endif
