/* testclouds_oracle.h — what the cloud marcher's quadrature oracles share (test_clouds_march,
 * test_clouds_buildup, test_clouds_march_thick): the clouds' extinction at a point of a ray, the
 * sun's optical depth from it over the layer, the reference's majorant grid filled as its
 * pass fills it, and the marcher's radiance averaged over stratified jitters. Static inline functions of the host build; include after kernels_composed.h. */
#ifndef ATMO_TESTCLOUDS_ORACLE_H
#define ATMO_TESTCLOUDS_ORACLE_H

/* The clouds' extinction (1/m, the 550 nm channel) at the distance t along m. */
static inline double test_clouds_sigma(const atmo_gpu_scene *s, const medium_ray *m, double t)
{
    medium_point q = medium_ray_at(m, (float)t, s->atmosphere.bottom_radius);
    return (double)clouds_density(&s->clouds, q.p, q.h) * s->clouds.extinction.y;
}

/* The sun's optical depth from the point at t along m to the layer's top: the midpoint rule in
 * 10 m steps (the field's finest octave has 200 m features). */
static inline double test_clouds_sun_depth(const atmo_gpu_scene *s, const medium_ray *m, double t)
{
    medium_point q = medium_ray_at(m, (float)t, s->atmosphere.bottom_radius);
    vec3 sun = v3_from4(s->sun_direction);
    double tau = 0.0, du = 10.0;
    for (double u = 0.5 * du;; u += du) {
        float h = geometry_altitude_at(q.r, q.mu_s, (float)u, s->atmosphere.bottom_radius);
        if (h > s->clouds.top_m)
            break;
        vec3 x = v3_add(q.p, v3_scale(sun, (float)u));
        tau += (double)clouds_density(&s->clouds, x, h) * s->clouds.extinction.y * du;
    }
    return tau;
}

/* grid (CLOUDS_GRID_NX x NY x NZ floats): the layer's majorant per cell around the camera of s,
 * as the reference's pass fills it (cloud_majorant.h). */
static inline void test_clouds_fill_grid(const atmo_gpu_scene *s, float *grid)
{
    clouds_grid_frame frame = clouds_grid_frame_make(s);
    for (int k = 0; k < CLOUDS_GRID_NZ; k++)
        for (int j = 0; j < CLOUDS_GRID_NY; j++)
            for (int i = 0; i < CLOUDS_GRID_NX; i++)
                grid[(k * CLOUDS_GRID_NY + j) * CLOUDS_GRID_NX + i] =
                    clouds_grid_cell_bound(s, &frame, i, j, k);
}

/* The marcher's radiance along m (the 550 nm channel; method single's use_ms = 0: no sky),
 * averaged over `jitters` stratified jitters. */
static inline double test_clouds_marcher_mean(const atmo_gpu_scene *s, ATMO_LUT_PARAMS,
                                              const medium_ray *m, int jitters)
{
    double sum = 0.0;
    for (int j = 0; j < jitters; j++) {
        medium_result r;
        medium_integrate(s, ATMO_LUT_ARGS, m, 0.0f, INFINITY, 8, ((float)j + 0.5f) / jitters, 0,
                         &r);
        sum += medium_radiance(s, ATMO_LUT_ARGS, &r, m->nu).y;
    }
    return sum / jitters;
}

#endif
