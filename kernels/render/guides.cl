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
 * Volumes (the cloud layer, -DATMO_CLOUDS): transparent to the guides; the layer's droplets
 * scatter almost without absorption, so a cloud in front of the sky has the sky's albedo 1
 * and normal 0 either way, and where a cloud hides a surface the guide shows the surface.
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
    for (int j = 0; j < GUIDES_GRID; j++)
        for (int i = 0; i < GUIDES_GRID; i++) {
            float3 dir = guides_ray(scene, x, y, i, j);
            if (dot(dir, dir) == 0.0f)
                continue;
            medium_ray ray = medium_ray_from_camera(scene, dir);
            path_hit h = guides_hit(scene, ATMO_LUT_ARGS, &ray);
            if (h.kind == SURFACES_NONE) {
                a += (float3)(1.0f);
                depth += GUIDES_NO_HIT_DEPTH_M;
                disc += dot(dir, sun.xyz) >= sun.w ? 1.0f : 0.0f;
            } else {
                a += h.albedo;
                n += h.normal;
                depth += h.t;
            }
        }
    float inv = 1.0f / (float)(GUIDES_GRID * GUIDES_GRID);
    albedo[pixel] = (float4)(clamp(a * inv, 0.0f, 1.0f), disc * inv);
    normal[pixel] = (float4)(n * inv, depth * inv);
}
