/* features.h — the feature registry: what a scene can contain, one row per part of a feature.
 *
 * A feature is an atmosphere method, a part that methods share (the Psi_ms LUT), a medium (the
 * cloud shell, the fBm layer), an occluder or surface (terrain, objects, the observer), the path
 * tracer. Each is a folder host/features/<name>/ whose file <name>_feature.c registers its rows
 * with ATMO_FEATURE_SET(<name>, rows); the build lists every such file (CMakeLists.txt
 * generates atmo_feature_sets[] from the folders), so adding a feature adds a folder and edits
 * no central list. The engine's own rows (host/plan/features.c) hold the atmosphere's
 * transmittance, the generic integrator, the render kernels and the generated compositions.
 * A row declares
 *   - its place (order: a band of the program, ATMO_BAND_*, plus its rank in the band),
 *   - when a scene contains it (wanted),
 *   - its kernel fragments, appended to the program in registry order (so a shared part comes
 *     before the methods that call it and a medium before the methods that integrate it: no
 *     insertion by name), and the -D flags it adds,
 *   - its typed GPU struct (a member of atmo_gpu_scene, in its own header of include/atmo/) and
 *     the other fields of the scene struct its passes read (params: the cache key covers them),
 *   - the fragments its passes are compiled from and the features whose buffers they read
 *     (sources, needs: the cache key covers those too, atmo/render.h),
 *   - a plan function that fills its GPU struct from the scene, sizes its named buffers
 *     (atmo_plan_add_buffer) and lists its precompute passes (atmo_plan_add_pass),
 *   - the functions it gives the generic integrator (slots: a medium's coefficients, an
 *     occluder, a surface, a method's multiple-scattering source), which the plan composes
 *     into generated fragments at the rows marked `compose` (host/plan/compose.c).
 * atmo_plan_make walks the rows in order and plans the wanted ones; the kernels then see only
 * the fragments, flags and buffers of the features the scene contains. */
#ifndef ATMO_FEATURES_H
#define ATMO_FEATURES_H
#include <stddef.h>
#include "atmo/plan.h"

/* A span of atmo_gpu_scene (offset and size in bytes) that a feature's passes read. */
typedef struct atmo_gpu_field {
    size_t offset, size;
} atmo_gpu_field;
#define ATMO_GPU_FIELD(member)                                                                     \
    {offsetof(atmo_gpu_scene, member), sizeof(((atmo_gpu_scene *)0)->member)}

/* The functions a feature gives the plan's composition (compose.c), by name, each with the
 * signature of its slot (kernels/media/media.h describes the slots; NULL: not given):
 *   component             its scattering component: MEDIA_<component> numbers it after the air's
 *   media_add             void (s, ATMO_LUT_PARAMS, const medium_point *q, media_sample *m): adds
 *                         its extinction and its component's scattering at q
 *   media_phase           vec3 (s, ATMO_LUT_PARAMS, float nu): its component's phase function
 *   media_sun             vec3 (s, ATMO_LUT_PARAMS, const medium_point *q): the sun's
 *                         transmittance through it to q (a medium that shadows)
 *   media_sun_surface     the same at a surface point (one per camera ray, so it may cost
 *                         more: the fBm layer's march in more steps); NULL: media_sun
 *   media_intervals       int (s, const medium_ray *m, float t_start, float t_end, float *lo,
 *                         float *hi): the parts of the ray it steps itself (at most one medium)
 *   media_interval        void (s, ATMO_LUT_PARAMS, const medium_ray *m, float t0, float t1,
 *                         float jitter, int use_ms, int ground, float grid_d, int grid_n,
 *                         vec3 *L, vec3 *T, vec3 *medium_t): that stepping (grid_d, grid_n:
 *                         the integrator's air grid, break points grid_d (i / grid_n)^2)
 *   ms_source             vec3 (s, ATMO_LUT_PARAMS, const medium_point *q, float nu,
 *                         const media_sample *m, int ground): a method's multiple-scattering
 *                         source (at most one method)
 *   ms_ground_irradiance  vec3 (s, ATMO_LUT_PARAMS, float mu_s): its sky irradiance on the ground
 *   volume_at             vec3 (s, ATMO_LUT_PARAMS, const medium_point *q, vec3 *scattering):
 *                         marks the row as the path tracer's volume medium (at most one, which
 *                         no method sees): its extinction at q, its scattering in *scattering;
 *                         the row's media_phase, majorant_*, media_direction and roulette_gain
 *                         (all needed) then compose the volume functions (media.h) and the
 *                         walk's volume mode instead of the methods' media
 *   volume_air            1: the air (media.h's media_air_at, its Rayleigh and Mie components)
 *                         is a volume medium of the path tracer's walk too (path.air = medium):
 *                         its free flights scatter in it (MEDIA_VOLUME_AIR, media_walk.h)
 *   sun_occluder          float (s, ATMO_LUT_PARAMS, const medium_point *q): 1 where it leaves
 *                         the sun visible from q, 0 in its shadow
 *   surface_occluder      1: that occluder also shadows surface points (the path tracer's, the
 *                         preview's terrain: visibility_sun_surface)
 *   ray_occluder          float (s, ATMO_LUT_PARAMS, const medium_point *q, float t, STATE *st):
 *                         an occluder with a state along the integrator's ray (st 0: no ray);
 *   ray_state, ray_begin  the state's type STATE and void (s, const medium_ray *m, float end,
 *                         float surface_t, STATE *st), which starts it on a ray
 *   surface_hit           float (s, ATMO_LUT_PARAMS, const medium_ray *m, float t_max): the
 *                         distance to its surface before t_max, or -1
 *   surface_radiance      vec3 (s, ATMO_LUT_PARAMS, const medium_ray *m, float t): the light
 *                         of its surface at distance t toward the ray's origin, x < 0 where the
 *                         surface there is not its own (the last surface asked may assume it is)
 * A surface of the path tracer and the denoiser's guides (kernels/render/surfaces.h):
 *   path_hit              void (s, ATMO_LUT_PARAMS, const medium_ray *m, path_hit *h): replaces
 *                         the hit record h (render/path_hit.h) where its surface is nearer
 *   path_occluded         int (s, ATMO_LUT_PARAMS, vec3 o, vec3 d): 1 where its surface blocks
 *                         the shadow ray from o along d
 *   path_replaces_ground  1: its surface replaces the planet's ground sphere (the terrain)
 *   cone_start            float (s, ATMO_LUT_PARAMS, const medium_ray *m, float spread): for a
 *                         surface found by a march, a distance before which no ray from m's
 *                         origin within the chord spread of its direction meets it; its path_hit
 *                         then marches from the record's march_from
 * The denoiser's guides (kernels/render/guides.cl):
 *   guide_depth           vec3 (s, const medium_ray *m, float t_end, vec3 *albedo): a
 *                         medium's optical depth along m over [0, t_end], its single-
 *                         scattering albedo in *albedo
 *   guide_block           void (s, const medium_ray *m, int n, const float *ends,
 *                         float step_scale, float tau_stop, vec3 *tau, vec3 *tau_albedo): the
 *                         same for a block of n rays ending at ends[k] from one march along m,
 *                         added to tau[k] and (times the albedo) to tau_albedo[k]
 *   pixel_ray             vec3 (s, int x, int y, float u1, float u2): the mode's camera ray at
 *                         (u1, u2) of pixel (x, y) (NULL: the preview's box)
 *   media_shown           int (s, float t_end): whether the image shows the method's media in
 *                         front of a surface at t_end (NULL: always)
 *   guides_grid           the mode's rays per pixel side (0: ATMO_GUIDES_PREVIEW_GRID)
 * A stage of the preview's camera rays (kernels/render/sky.cl's render_camera_trace):
 *   camera_stage          int (s, ATMO_LUT_PARAMS, const medium_ray *ray, rng_stream *g,
 *                         vec3 *sky, vec3 *sun, vec3 *view_t): 1 where it traced the ray (its
 *                         sky light, sun disc and view transmittance), 0 to leave it to the
 *                         next stage and in the end to the method's sky_trace
 * A medium in the Monte Carlo walk (kernels/media/majorant_walk.h, media_walk.h):
 *   majorant_state        the type STATE of its majorant along one ray
 *   majorant_begin        void (s, ATMO_LUT_PARAMS, vec3 origin, vec3 dir, float r, float mu,
 *                         float end, STATE *st): starts it on origin + t dir, t in [0, end]
 *                         (r, mu: radius and cosine to the vertical at the origin)
 *   majorant_segment      float (s, ATMO_LUT_PARAMS, STATE *st, float t, float *seg_end): its
 *                         majorant (1/m, >= its extinction) from t up to *seg_end, for t
 *                         increasing from call to call
 *   sun_exact             1: its media_sun is exact (closed form), so the walks toward the sun
 *                         take it from there and do not track it
 *   walk_component        the component whose sampling the next two give (default: component)
 *   media_direction       vec3 (s, ATMO_LUT_PARAMS, vec3 dir, vec3 to_sun, vec3 beta, float u1,
 *                         float u2, rng_stream *g, vec3 *weight): a new direction at a
 *                         scattering by it (weight: phase over the sampling density)
 *   roulette_gain         float (s, ATMO_LUT_PARAMS, float nu): the factor on a path's
 *                         roulette survival leaving at cosine nu to the sun (tracking.h)
 * The composition asks the features in registry order, so a row's place also orders its
 * occluders and surfaces. */
typedef struct atmo_slots {
    const char *component;
    const char *media_add, *media_phase, *media_sun, *media_sun_surface;
    const char *media_intervals, *media_interval;
    const char *ms_source, *ms_ground_irradiance;
    const char *volume_at;
    int volume_air;
    const char *sun_occluder;
    int surface_occluder;
    const char *ray_occluder, *ray_state, *ray_begin;
    const char *surface_hit, *surface_radiance;
    const char *path_hit, *path_occluded;
    int path_replaces_ground;
    const char *cone_start;
    const char *camera_stage;
    const char *guide_depth, *guide_block, *pixel_ray, *media_shown;
    int guides_grid;
    const char *majorant_state, *majorant_begin, *majorant_segment;
    int sun_exact;
    const char *walk_component, *media_direction, *roulette_gain;
} atmo_slots;

/* The generated composition fragments (compose.c): a registry row with compose != 0 has no
 * files; its place in the registry is where the plan puts the generated functions of its group,
 * after the rows whose functions they call and before those that call them. */
enum {
    ATMO_COMPOSE_NONE,
    ATMO_COMPOSE_MEDIA,     /* media_at, media_phase, media_sun_attenuate, medium_ms_source,
                               medium_ms_ground_irradiance; the walk's MEDIA_TRACKED,
                               MEDIA_VOLUME, media_majorant, media_majorant_begin,
                               media_majorant_segment, media_tracked_extinction,
                               media_sun_exact_attenuate, media_phase_direction,
                               media_roulette_gain; MEDIA_VOLUME_AIR; the volume
                               medium's media_volume_at,
                               media_volume_phase, media_volume_direction,
                               media_volume_roulette_gain */
    ATMO_COMPOSE_SUN,       /* visibility_ray, visibility_ray_begin, visibility_sun_occluders,
                               visibility_sun_occluders_on_ray, visibility_surface_occluders */
    ATMO_COMPOSE_SURFACES,  /* visibility_surface_hit, visibility_surface_radiance */
    ATMO_COMPOSE_INTERVALS, /* media_intervals, media_interval */
    ATMO_COMPOSE_PATH_SURFACES, /* SURFACES_GROUND_SPHERE, surfaces_features_hit,
                                   surfaces_features_occluded (render/surfaces.h) */
    ATMO_COMPOSE_CAMERA,    /* render_camera_trace (render/sky.cl) */
    ATMO_COMPOSE_GUIDES,    /* GUIDES_GRID, guides_pixel_ray, guides_media_shown,
                               guides_media_ray, guides_media_block (render/guides.cl) */
    ATMO_COMPOSE_GROUPS
};

/* A row's place in the registry, order = band + rank. The bands are the stages of a program in
 * the order it is assembled; a rank (0-99) orders a row against the other rows of its band
 * where their order matters (the composition asks occluders and surfaces in registry order).
 * Every row's order is its own (test_features checks it), so the registry's order does not
 * depend on the order the build finds the feature folders in. */
enum {
    ATMO_BAND_BASE = 0,              /* the atmosphere's transmittance, which every part reads */
    ATMO_BAND_MEDIA = 100,           /* media, occluders' fields, the methods' sources: before
                                        the media's composition */
    ATMO_BAND_VISIBILITY = 200,      /* the media's and the sun's compositions, the visibility */
    ATMO_BAND_LIGHT = 300,           /* surfaces' light and occluders along a ray: ask the
                                        visibility, before the surfaces' composition */
    ATMO_BAND_SURFACES = 400,        /* the surfaces' composition */
    ATMO_BAND_STEPPING = 500,        /* the media's own stepping: asks the visibility */
    ATMO_BAND_INTEGRATOR = 600,      /* the intervals' composition, the medium integrator */
    ATMO_BAND_METHODS = 700,         /* the methods and their passes, over the integrator */
    ATMO_BAND_CAMERA = 800,          /* the preview's camera stages */
    ATMO_BAND_RENDER = 900,          /* the camera's composition, the render kernels */
    ATMO_BAND_PATH_SURFACES = 1000,  /* the features' surfaces of the path tracer and guides */
    ATMO_BAND_SURFACE_QUERIES = 1100, /* their composition and render/surfaces.h */
    ATMO_BAND_PATH = 1200,           /* the path tracer */
    ATMO_BAND_GUIDES = 1300          /* the guides' composition and kernels */
};

typedef struct atmo_feature {
    const char *name;
    int order;                       /* ATMO_BAND_* + rank */
    int is_method;                   /* an atmosphere method: ATMO_METHOD_* in `method` */
    int method;
    int (*wanted)(const atmo_scene *s);
    const char *const *fragments;    /* NULL-terminated */
    const char *defines;             /* "-DNAME ..." or NULL */
    const atmo_gpu_field *params;    /* {0, 0}-terminated; NULL: no passes */
    const char *const *sources;      /* NULL-terminated; NULL: no passes */
    const char *const *needs;        /* NULL-terminated names of features; NULL: none */
    int (*plan)(const atmo_scene *s, atmo_plan *p, atmo_err *e); /* NULL: nothing to plan */
    int luts_follow_view; /* a method whose buffers hold one camera and sun (its probes of
                             other rays are only valid for that sun) */
    const atmo_slots *slots; /* what it gives the composition; NULL: nothing */
    int compose;             /* ATMO_COMPOSE_*: this row is that generated fragment */
} atmo_feature;

/* A feature's rows, registered by its folder's <name>_feature.c. */
typedef struct atmo_feature_set {
    const char *name; /* the folder under host/features/ */
    const atmo_feature *rows;
    int count;
} atmo_feature_set;
#define ATMO_FEATURE_SET(folder, table)                                                            \
    const atmo_feature_set atmo_feature_set_##folder = {#folder, table,                           \
                                                        (int)(sizeof table / sizeof table[0])}
/* Every feature folder's set, NULL-terminated (generated by the build). */
extern const atmo_feature_set *const atmo_feature_sets[];

/* How many rows the registry has; row i of them in registry order (0 <= i < count). */
int atmo_feature_count(void);
const atmo_feature *atmo_feature_at(int i);
/* The row with this name, or NULL. */
const atmo_feature *atmo_feature_find(const char *name);
/* The atmosphere method's row (ATMO_METHOD_*), or NULL. */
const atmo_feature *atmo_feature_method(int method);
/* "single, march, ..." for messages. */
const char *atmo_plan_available_methods(void);

/* The composition of the features f[0..n-1] (in registry order) for the group
 * (ATMO_COMPOSE_*), as OpenCL C that also compiles as C, into out; returns 0, or -1 when it
 * does not fit or two features fill a slot that takes one (a registry bug). */
int atmo_compose(const atmo_feature *const *f, int n, int group, char *out, size_t size);
/* "#define MEDIA_<component> k" for the media's components (k from 2, after the air's) and
 * "#define MEDIA_COMPONENTS n", one a line, into out; 0 or -1 as atmo_compose. */
int atmo_compose_components(const atmo_feature *const *f, int n, char *out, size_t size);
/* The name of the fragment of a row with compose != 0, e.g. "plan/media". */
const char *atmo_compose_name(int group);

#endif
