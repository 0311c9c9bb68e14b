/* flare.h — a procedural lens flare, added in screen space to a perspective image's linear
 * radiance (host/image/flare.c). */
#ifndef ATMO_FLARE_H
#define ATMO_FLARE_H

typedef struct atmo_flare_camera {
    int width, height;
    double forward[3], right[3], up[3]; /* the camera's unit basis */
    double tan_half_fov;                /* vertical */
    double sun[3];                      /* unit vector toward the sun */
    double sun_radius_rad;              /* angular radius of its disc */
} atmo_flare_camera;

/* Where the flare's light comes from, as atmo_flare_apply measured it. */
typedef struct atmo_flare_info {
    double sun_x, sun_y;   /* the sun's centre in pixels (may lie outside the image) */
    double irradiance[3];  /* what the image's sun pixels deliver, W m^-2 nm^-1 (0: covered) */
    double added[3];       /* the flare's irradiance added to the image, the same units */
} atmo_flare_info;

/* Add the flare of strength `strength` (1: the default lens) to rgb (W x H x 3, row 0 = top)
 * and say what it did in *info (may be NULL). */
void atmo_flare_apply(float *rgb, const atmo_flare_camera *c, double strength,
                      atmo_flare_info *info);

#endif
