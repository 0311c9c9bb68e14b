/* guides.cl — guide_render: the denoiser's guides (Intel Open Image Denoise's "albedo" and
 * "normal" auxiliary images, docs/guide/denoise.md), free of Monte Carlo noise, in every mode.
 *
 * For each pixel the camera rays of a fixed GUIDES_GRID x GUIDES_GRID pattern of positions in
 * the pixel meet the first surface (render/surfaces.h: the ground sphere, the terrain and its
 * sea, the objects); the guides are the means over the pattern of
 *     albedo: the surface's Lambertian albedo; 1 for a ray that meets no surface (OIDN's
 *             convention for the environment: "1 or the environment's colour clamped to
 *             [0, 1]"; 1 keeps the guide flat where the sky's own gradients are, so the filter
 *             takes them from the colour);
 *     normal: the surface's outward unit normal, world axes; 0 for a ray that meets nothing
 *             (OIDN: a zero normal marks "no surface");
 *     depth:  the distance to the surface (m), GUIDES_NO_HIT_DEPTH_M for a ray that meets
 *             nothing (Blender's background depth); written as an EXR layer only.
 * The positions follow each mode's pixel filter, so a guide's edge is anti-aliased as the
 * converged image's is: the preview's box over the pixel (sky.cl) at the cell centres
 * (i + 1/2) / GUIDES_GRID; the path tracer's truncated Gaussian (path_camera.h) by inverting
 * its radial distribution at the same cell centres taken as (u1, u2) — its samples' own
 * mapping, on a stratified grid instead of the Sobol sequence. The rays are the pinhole's
 * (a thin lens blurs what the guide would keep sharp; the host does not use the guides then).
 * Nothing random is drawn: the guides of a pixel are the same for any seed, sample count,
 * tile size or launch, and a 4-spp image gets the guides of the converged image. A fisheye's
 * corners outside its circle (no ray) get albedo 0 and normal 0, as their image is black.
 *
 * Volumes (the cloud shell, -DATMO_CLOUD; the fBm cloud layer, -DATMO_CLOUDS; in every mode
 * and for path.clouds = march and volume alike): a transmittance-weighted average, not the
 * first scattering. A ray's values are
 *     albedo = (1 - T) w + T a_behind,   normal = T_y n_behind
 * per channel, T = e^{-tau} the view transmittance through the clouds that the image shows (not
 * the method's under the path tracer's uniform sky or before a surface nearer than its
 * PATH_AIR_MIN_M, which the path tracer does not march) in front of the first surface (all of
 * them for a ray that meets none), w the clouds' single-scattering albedo (the media's weighted
 * by their optical depths), a_behind and n_behind the surface's values or the sky's (1 and 0).
 * T and w are integrated on the first ray of each 2 x 2 block of the pattern and shared by the
 * block's rays (GUIDES_CLOUD_STRIDE). For a homogeneous shell of optical depth tau along the
 * ray this is the closed form (1 - e^{-tau}) w + e^{-tau} a_behind (tests/test_guides.c). Why
 * this: OIDN documents its features as those of the first hit, noise-free and under the
 * colour's pixel filter, and warns that features seen through transparent surfaces do not help;
 * a cloud pixel's light is a blend of the cloud's and what lies behind in the proportions 1 - T
 * and T, and the guide blends the same way, so a cloud edge over terrain is an edge in the
 * guide where it is one in the image, and a thin veil keeps the terrain's texture in the guide.
 * The first significant scattering is a random point (noise in the guide) or, taken as the
 * point of optical depth 1, a hard switch between cloud and ground where the image blends them.
 * The cloud's own normal is 0, OIDN's "no surface": a cloud has no surface and its multiple
 * scattering follows no local normal, so the filter takes a cloud's shading from the colour as
 * it takes the sky's (a normal facing the camera did worse, docs/guide/denoise.md; the
 * density's gradient was not tried). The optical depth is the shell's chord (closed form) and
 * the layer's density integral on its marcher's steps at their midpoints (cloud_layer.h's
 * clouds_view_density): no random number either.
 *
 * The sun's disc: the share of the pattern's rays that meet no surface and point into the
 * disc (cos of their angle to the sun >= sun_direction.w, the cosine of its angular radius),
 * so the host can keep the disc out of the filter (outputs.c).
 *
 * Output: one work item per pixel `first + id` of the image (row-major, row 0 = top), items
 * past `count` return at once; albedo[pixel] = (albedo, disc share), normal[pixel] = (normal,
 * depth). */

/* 8 x 8 rays: at 4 x 4 the radial-angular grid samples the path tracer's Gaussian too coarsely
 * and the guided filter lost a tenth of its gain (docs/guide/denoise.md) */
#define GUIDES_GRID 8
#define GUIDES_NO_HIT_DEPTH_M 1e10f
/* the clouds' view optical depth is integrated to this (e^-9.2 = 1e-4 of the guide behind) */
#define GUIDES_TAU_STOP 9.2f
/* the clouds are integrated on the first ray of each block of 2 x 2 cells, which the block's
 * four rays share: the layer's march costs each ray about a fifth of a preview sample, and on
 * all 64 rays the pass took about two thirds as long as a 16-spp preview of thesis-8 (160 x 90),
 * on these 16 a quarter (48 x 27) */
#define GUIDES_CLOUD_STRIDE 2
#define GUIDES_BLOCKS (GUIDES_GRID / GUIDES_CLOUD_STRIDE)

/* The camera ray of cell (i, j) of pixel (x, y) under the scene's mode's pixel filter. */
float3 guides_ray(__global const atmo_gpu_scene *scene, int x, int y, int i, int j)
{
    float u1 = ((float)i + 0.5f) / (float)GUIDES_GRID;
    float u2 = ((float)j + 0.5f) / (float)GUIDES_GRID;
#ifdef ATMO_PATH
    float dx, dy;
    path_filter_offset(scene->path.filter_sigma, scene->path.filter_radius, u1, u2, &dx, &dy);
    return camera_ray(&scene->camera, (float)x + 0.5f + dx, (float)y + 0.5f + dy);
#else
    return camera_ray(&scene->camera, (float)x + u1, (float)y + u2);
#endif
}

/* The first surface along the ray: surfaces.h's, and in the preview without terrain the ground
 * sphere, which the preview's methods always have (surfaces.h asks path.ground, a path-mode
 * key). */
path_hit guides_hit(__global const atmo_gpu_scene *scene, ATMO_LUT_PARAMS, const medium_ray *ray)
{
    path_hit h = surfaces_hit(scene, ATMO_LUT_ARGS, ray, INFINITY);
#if !defined(ATMO_PATH) && !defined(ATMO_TERRAIN)
    float R = scene->atmosphere.bottom_radius;
    if (geometry_ray_hits_ground(ray->r, ray->mu, R)) {
        float t = geometry_distance_to_bottom(ray->r, ray->mu, R);
        if (t < h.t) {
            vec3 p = v3_add(ray->origin, v3_scale(ray->dir, t));
            h.t = t;
            h.kind = SURFACES_GROUND;
            h.normal = v3_normalize(v3_add(v3_scale(ray->up, ray->r_c), p));
            h.albedo = v3_from4(scene->atmosphere.ground_albedo);
        }
    }
#endif
    return h;
}

/* The view transmittance of the ray through the clouds over [0, t_end] (per channel) and in
 * *albedo their single-scattering albedo weighted by each medium's optical depth (0 where
 * there is none). */
float3 guides_clouds(__global const atmo_gpu_scene *scene, const medium_ray *ray, float t_end,
                     float3 *albedo)
{
    float3 tau = (float3)(0.0f), tau_albedo = (float3)(0.0f);
    float lo[2], hi[2];
    /* the method's media: not in the path tracer's uniform world (path.sky = uniform), where
     * only a volume medium (path.clouds = volume, MEDIA_VOLUME) scatters, */
    int method_media = 1;
#ifdef ATMO_PATH
    /* nor on a segment shorter than PATH_AIR_MIN_M to its surface (path.h) */
    method_media = scene->path.sky != ATMO_PATH_SKY_UNIFORM && t_end >= PATH_AIR_MIN_M;
#endif
#ifdef ATMO_CLOUD
    float chord = 0.0f;
    int n = method_media ? cloud_shell_intervals(scene, ray, 0.0f, t_end, lo, hi) : 0;
    for (int k = 0; k < n; k++)
        chord += hi[k] - lo[k];
    float3 shell = scene->cloud.extinction.xyz * chord;
    tau += shell;
    tau_albedo += shell * scene->cloud.albedo.xyz;
#endif
#ifdef ATMO_CLOUDS
    __global const atmo_gpu_clouds *c = &scene->clouds;
    /* flags of 0 or 1 joined bitwise: a composed constant in a logical operator is a warning */
    int parts = (method_media | (MEDIA_VOLUME > 0))
                    ? clouds_shell_parts(scene->atmosphere.bottom_radius, c->bottom_m, c->top_m,
                                         ray->r, ray->mu, 0.0f, t_end, lo, hi)
                    : 0;
    float D = 0.0f;
    for (int k = 0; k < parts; k++)
        D += clouds_view_density(scene, ray, lo[k], hi[k],
                                 GUIDES_TAU_STOP - tau.y - D * c->extinction.y);
    float3 layer = c->extinction.xyz * D;
    tau += layer;
    tau_albedo += layer * c->albedo.xyz;
#endif
    *albedo = select((float3)(0.0f), tau_albedo / tau, tau > (float3)(0.0f));
    return exp(-tau);
}

__kernel void guide_render(__global const atmo_gpu_scene *scene, ATMO_LUT_PARAMS,
                           __global float4 *albedo, __global float4 *normal, uint first,
                           uint count)
{
    uint id = get_global_id(0);
    if (id >= count)
        return;
    uint pixel = first + id;
    int width = scene->camera.width;
    int x = (int)(pixel % (uint)width), y = (int)(pixel / (uint)width);
    float3 a = (float3)(0.0f), n = (float3)(0.0f);
    float depth = 0.0f, disc = 0.0f;
    float4 sun = scene->sun_direction;
    /* the clouds of the current row of blocks: transmittance, albedo, whether computed */
    float3 block_t[GUIDES_BLOCKS], block_albedo[GUIDES_BLOCKS];
    int block_done[GUIDES_BLOCKS];
    for (int j = 0; j < GUIDES_GRID; j++) {
        if (j % GUIDES_CLOUD_STRIDE == 0)
            for (int b = 0; b < GUIDES_BLOCKS; b++)
                block_done[b] = 0;
        for (int i = 0; i < GUIDES_GRID; i++) {
            float3 dir = guides_ray(scene, x, y, i, j);
            if (dot(dir, dir) == 0.0f)
                continue;
            medium_ray ray = medium_ray_from_camera(scene, dir);
            path_hit h = guides_hit(scene, ATMO_LUT_ARGS, &ray);
            int b = i / GUIDES_CLOUD_STRIDE;
            if (!block_done[b]) {
                block_t[b] = guides_clouds(scene, &ray, h.t, &block_albedo[b]);
                block_done[b] = 1;
            }
            float3 behind_albedo = (float3)(1.0f), behind_normal = (float3)(0.0f);
            if (h.kind == SURFACES_NONE) {
                depth += GUIDES_NO_HIT_DEPTH_M;
                disc += dot(dir, sun.xyz) >= sun.w ? 1.0f : 0.0f;
            } else {
                behind_albedo = h.albedo;
                behind_normal = h.normal;
                depth += h.t;
            }
            float3 T = block_t[b];
            a += T * behind_albedo + ((float3)(1.0f) - T) * block_albedo[b];
            n += T.y * behind_normal;
        }
    }
    float inv = 1.0f / (float)(GUIDES_GRID * GUIDES_GRID);
    albedo[pixel] = (float4)(clamp(a * inv, 0.0f, 1.0f), disc * inv);
    normal[pixel] = (float4)(n * inv, depth * inv);
}
