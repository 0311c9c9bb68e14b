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
 * The shell's optical depth is each ray's chord (closed form); for a homogeneous shell of
 * optical depth tau along the ray the guide is (1 - e^{-tau}) w + e^{-tau} a_behind
 * (tests/test_guides.c). The layer's is a march (cloud_layer.h's clouds_view_density_ends, on
 * GUIDES_CLOUD_STEP_SCALE times the marcher's steps, at their midpoints: no random number
 * either) along the centre ray of each GUIDES_CLOUD_STRIDE x GUIDES_CLOUD_STRIDE block of the
 * pattern, which gives each of the block's rays the density in front of its own surface: the
 * rays of a block differ by a fraction of a pixel across, but their surfaces' distances can
 * differ by kilometres (a peak in front of the valley behind it). Why
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
 * density's gradient was not tried).
 *
 * The sun's disc: the share of the pattern's rays that meet no surface and point into the
 * disc (cos of their angle to the sun >= sun_direction.w, the cosine of its angular radius),
 * so the host can keep the disc out of the filter (outputs.c).
 *
 * Output: one work item per pixel `first + id` of the image (row-major, row 0 = top), items
 * past `count` return at once; albedo[pixel] = (albedo, disc share), normal[pixel] = (normal,
 * depth). */

/* The pattern and the clouds' blocks per mode (gpu_enums.h). Path: 8 x 8 rays, since at 4 x 4
 * the radial-angular grid samples the Gaussian too coarsely and the guided filter lost a tenth
 * of its gain. Preview: its box at 4 x 4 cell centres. Both march the layer once per 2 x 2
 * block (docs/guide/denoise.md: the rays, the blocks and the step, measured). */
#ifdef ATMO_PATH
#define GUIDES_GRID ATMO_GUIDES_PATH_GRID
#define GUIDES_CLOUD_STRIDE ATMO_GUIDES_PATH_BLOCK
#else
#define GUIDES_GRID ATMO_GUIDES_PREVIEW_GRID
#define GUIDES_CLOUD_STRIDE ATMO_GUIDES_PREVIEW_BLOCK
#endif
#define GUIDES_BLOCK_RAYS (GUIDES_CLOUD_STRIDE * GUIDES_CLOUD_STRIDE)
/* the layer's march takes this many times the marcher's steps: the guide needs the
 * transmittance's shape, not the image's accuracy */
#define GUIDES_CLOUD_STEP_SCALE 2.0f
#define GUIDES_NO_HIT_DEPTH_M 1e10f
/* the clouds' view optical depth is integrated to this (e^-9.2 = 1e-4 of the guide behind) */
#define GUIDES_TAU_STOP 9.2f

/* The camera ray at (u1, u2) in [0, 1)^2 of pixel (x, y) under the scene's mode's pixel
 * filter. */
float3 guides_ray(__global const atmo_gpu_scene *scene, int x, int y, float u1, float u2)
{
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

/* Whether the image shows the method's media in front of a surface at t_end: not in the path
 * tracer's uniform world (path.sky = uniform), where only a volume medium (path.clouds =
 * volume, MEDIA_VOLUME) scatters, nor on a segment shorter than PATH_AIR_MIN_M (path.h). */
int guides_method_media(__global const atmo_gpu_scene *scene, float t_end)
{
#ifdef ATMO_PATH
    return scene->path.sky != ATMO_PATH_SKY_UNIFORM && t_end >= PATH_AIR_MIN_M;
#else
    return 1;
#endif
}

/* The cloud shell's view optical depth along the ray over [0, t_end] (its chord, closed form),
 * per channel, and in *tau_albedo that depth times the shell's albedo. */
float3 guides_shell(__global const atmo_gpu_scene *scene, const medium_ray *ray, float t_end,
                    float3 *tau_albedo)
{
    float3 tau = (float3)(0.0f);
#ifdef ATMO_CLOUD
    float lo[2], hi[2], chord = 0.0f;
    int n = guides_method_media(scene, t_end)
                ? cloud_shell_intervals(scene, ray, 0.0f, t_end, lo, hi)
                : 0;
    for (int k = 0; k < n; k++)
        chord += hi[k] - lo[k];
    tau = scene->cloud.extinction.xyz * chord;
    *tau_albedo = tau * scene->cloud.albedo.xyz;
#else
    *tau_albedo = tau;
#endif
    return tau;
}

/* The cloud layer's density integral (m) in front of each of a block's n rays, in D[k]: one
 * march along the block's ray `ray` to the farthest of the ends[] (the rays' surfaces,
 * INFINITY for the sky, 0 for a ray whose layer the image does not show), each ray's share
 * taken up to its own end (cloud_layer.h's clouds_view_density_ends). */
void guides_layer(__global const atmo_gpu_scene *scene, const medium_ray *ray, int n,
                  const float *ends, float *D)
{
    for (int k = 0; k < n; k++)
        D[k] = 0.0f;
#ifdef ATMO_CLOUDS
    __global const atmo_gpu_clouds *c = &scene->clouds;
    float t_far = 0.0f, lo[2], hi[2];
    for (int k = 0; k < n; k++)
        t_far = fmax(t_far, ends[k]);
    int parts = t_far > 0.0f ? clouds_shell_parts(scene->atmosphere.bottom_radius, c->bottom_m,
                                                  c->top_m, ray->r, ray->mu, 0.0f, t_far, lo,
                                                  hi)
                             : 0;
    float total = 0.0f;
    for (int k = 0; k < parts; k++)
        total += clouds_view_density_ends(scene, ray, lo[k], hi[k], GUIDES_CLOUD_STEP_SCALE,
                                          GUIDES_TAU_STOP - total * c->extinction.y, n, ends,
                                          D);
#endif
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
    const float cell = 1.0f / (float)GUIDES_GRID;
    for (int bj = 0; bj < GUIDES_GRID; bj += GUIDES_CLOUD_STRIDE)
        for (int bi = 0; bi < GUIDES_GRID; bi += GUIDES_CLOUD_STRIDE) {
            /* the block's rays: their surfaces, and where the layer in front of each ends */
            path_hit hit[GUIDES_BLOCK_RAYS];
            float3 dirs[GUIDES_BLOCK_RAYS];
            float ends[GUIDES_BLOCK_RAYS], D[GUIDES_BLOCK_RAYS];
            int any_ray = 0;
            for (int k = 0; k < GUIDES_BLOCK_RAYS; k++) {
                int i = bi + k % GUIDES_CLOUD_STRIDE, j = bj + k / GUIDES_CLOUD_STRIDE;
                dirs[k] = guides_ray(scene, x, y, ((float)i + 0.5f) * cell,
                                     ((float)j + 0.5f) * cell);
                ends[k] = 0.0f;
                if (dot(dirs[k], dirs[k]) == 0.0f)
                    continue;
                medium_ray ray = medium_ray_from_camera(scene, dirs[k]);
                hit[k] = guides_hit(scene, ATMO_LUT_ARGS, &ray);
                ends[k] = (guides_method_media(scene, hit[k].t) | (MEDIA_VOLUME > 0))
                              ? hit[k].t
                              : 0.0f;
                any_ray = 1;
            }
            /* the layer along the block's centre ray (its first ray where the centre sees
             * nothing: a fisheye's rim) */
            float3 centre = guides_ray(scene, x, y, ((float)bi + 0.5f * GUIDES_CLOUD_STRIDE) * cell,
                                       ((float)bj + 0.5f * GUIDES_CLOUD_STRIDE) * cell);
            for (int k = 0; k < GUIDES_BLOCK_RAYS && dot(centre, centre) == 0.0f; k++)
                centre = dirs[k];
            medium_ray shared = medium_ray_from_camera(scene, centre);
            guides_layer(scene, &shared, any_ray ? GUIDES_BLOCK_RAYS : 0, ends, D);
            for (int k = 0; k < GUIDES_BLOCK_RAYS; k++) {
                if (dot(dirs[k], dirs[k]) == 0.0f)
                    continue;
                path_hit h = hit[k];
                medium_ray ray = medium_ray_from_camera(scene, dirs[k]);
                float3 tau_albedo;
                float3 tau = guides_shell(scene, &ray, h.t, &tau_albedo);
#ifdef ATMO_CLOUDS
                float3 layer = scene->clouds.extinction.xyz * D[k];
                tau += layer;
                tau_albedo += layer * scene->clouds.albedo.xyz;
#endif
                float3 w = select((float3)(0.0f), tau_albedo / tau, tau > (float3)(0.0f));
                float3 T = exp(-tau);
                float3 behind_albedo = (float3)(1.0f), behind_normal = (float3)(0.0f);
                if (h.kind == SURFACES_NONE) {
                    depth += GUIDES_NO_HIT_DEPTH_M;
                    disc += dot(dirs[k], sun.xyz) >= sun.w ? 1.0f : 0.0f;
                } else {
                    behind_albedo = h.albedo;
                    behind_normal = h.normal;
                    depth += h.t;
                }
                a += T * behind_albedo + ((float3)(1.0f) - T) * w;
                n += T.y * behind_normal;
            }
        }
    float inv = 1.0f / (float)(GUIDES_GRID * GUIDES_GRID);
    albedo[pixel] = (float4)(clamp(a * inv, 0.0f, 1.0f), disc * inv);
    normal[pixel] = (float4)(n * inv, depth * inv);
}
