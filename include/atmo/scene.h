/* scene.h — everything a render depends on, as the user states it.
 *
 * A scene is the default values of every parameter, then a preset's or a JSON file's values, then
 * --set overrides (dotted keys, e.g. sun.zenith_deg=60). The parameter registry (scene.c and the
 * feature folders, atmo/scene_params.h) lists each key with its type, unit, default, valid
 * range and meaning; `atmo params` prints it, the JSON reader and --set go through it, and
 * --save-scene writes every key back. Units are those
 * of the key's name: degrees where a key says _deg, metres for _m, SI elsewhere.
 *
 * Derived quantities (the atmosphere at the render wavelengths, the camera basis, the sun
 * direction) are computed from a scene by the plan, not stored here. */
#ifndef ATMO_SCENE_H
#define ATMO_SCENE_H
#include <stddef.h>
#include "atmo/gpu_enums.h"
#include "atmo/status.h"

enum { ATMO_QUANTITY_RADIANCE = 0, ATMO_QUANTITY_LUMINANCE = 1 };
/* output.denoise: auto denoises the PNG outputs (quality high) of a path-traced scene or of a
 * preview with more than the air, where the library is installed;
 * off, or the named quality for every output. */
enum {
    ATMO_OUTPUT_DENOISE_AUTO = 0,
    ATMO_OUTPUT_DENOISE_OFF,
    ATMO_OUTPUT_DENOISE_FAST,
    ATMO_OUTPUT_DENOISE_BALANCED,
    ATMO_OUTPUT_DENOISE_HIGH
};
/* camera.on_terrain: what camera.position_m's y is measured from */
enum { ATMO_CAMERA_TERRAIN_OFF = 0, ATMO_CAMERA_TERRAIN_BELOW = 1, ATMO_CAMERA_TERRAIN_AT = 2 };

/* One object of the scene's list ("objects" in a scene file; scene_objects.c): a Lambertian
 * sphere or axis-aligned box in world metres, with an albedo and an emitted radiance at the
 * render wavelengths (W m^-2 sr^-1 nm^-1). */
#define ATMO_MAX_OBJECTS 32
typedef struct atmo_object {
    int type;              /* ATMO_OBJECT_* (gpu_enums.h) */
    double center_m[3];    /* sphere */
    double radius_m;       /* sphere, > 0 */
    double min_m[3];       /* box: the minimum corner */
    double size_m[3];      /* box: extents, each > 0 */
    double albedo[3];      /* 0..1 */
    double emission[3];    /* >= 0 */
    int on_terrain;        /* 1: the anchor's y (centre, min) is metres above the terrain */
    int has_terrain_at;    /* 1: terrain_at_m is given (else the object's own x, z) */
    double terrain_at_m[2]; /* world x, z where the terrain's height is taken */
} atmo_object;

typedef struct atmo_scene {
    struct {
        int width, height;
        int samples; /* samples per pixel */
        int seed;    /* RNG seed, >= 0 */
    } image;
    struct {
        int kind;              /* ATMO_CAMERA_* */
        double position_m[3];  /* world: metres, Y up, planet centre (0, -bottom_radius, 0) */
        double pitch_deg;      /* thesis convention, presets.md: forward = (-cos p sin y, sin p, */
        double yaw_deg;        /*   cos p cos y), right = (cos y, 0, sin y) */
        double fov_deg;        /* vertical field of view (perspective) */
        int on_terrain;        /* ATMO_CAMERA_TERRAIN_*: y above sea level, or above the
                                * terrain's surface under the camera or at terrain_at_m */
        double terrain_at_m[2]; /* world x, z of that surface point (on_terrain = at) */
    } camera;
    struct {
        double zenith_deg;     /* angle between world +Y and the direction to the sun */
        double azimuth_deg;    /* direction = (sin z sin a, cos z, sin z cos a) */
        double angular_radius_deg;
        double irradiance_scale; /* multiplies the solar spectrum (1 = ASTM G-173) */
    } sun;
    struct {
        double bottom_radius_m, top_radius_m;
        double rayleigh_coefficient; /* beta_R(lambda) = c * lambda[um]^-4, m^-1 um^4 */
        double rayleigh_scale_height_m;
        double mie_extinction_per_m; /* at every wavelength (Angstrom alpha = 0) */
        double mie_albedo;           /* single-scattering albedo */
        double mie_scale_height_m;
        double mie_g;
        int mie_phase;               /* ATMO_PHASE_* (gpu_enums.h) */
        int method;                  /* ATMO_METHOD_* */
        int lut_orders;              /* method lut: scattering orders precomputed */
        int lut_r_size, lut_mu_size, lut_mu_s_size, lut_nu_size; /* method lut: 4-D LUT size */
        int lut_steps;               /* method lut: integration steps along a texel's ray */
        int lut_sphere_samples;      /* method lut: zenith rings of the direction grid */
        int reference_min_order;     /* method reference: lowest scattering order counted */
        int reference_max_order;     /* method reference: highest order counted (0 = all) */
        double ozone_column_du;      /* Dobson units in the tent profile */
        double ozone_bottom_m, ozone_peak_m, ozone_top_m;
        double ground_albedo;
    } atmosphere;
    struct {
        double wavelengths_nm[3];
        int spectral_bands;    /* 0: off; else spectral mode with this many bands (spectral_render.h) */
        int quantity;          /* ATMO_QUANTITY_*: what HDR outputs hold */
        int view_steps;        /* ray-march steps along a view ray */
        int transmittance_width, transmittance_height; /* transmittance LUT size (mu, r) */
    } render;
    struct {
        double exposure;       /* multiplies the (white-balanced) radiance before tone mapping */
        int tonemap;           /* ATMO_TONEMAP_* */
        double white_point;    /* for reinhard-white */
        int white_balance;     /* 0/1: divide by the sun's white point */
        int transfer;          /* ATMO_TRANSFER_*: PNG encoding curve */
        int flare;             /* 0/1: lens flare (perspective cameras; host/image/flare.c) */
        double flare_strength; /* its brightness relative to the default lens */
    } post;
    struct {
        int denoise;           /* ATMO_OUTPUT_DENOISE_*: Open Image Denoise (atmo/outputs.h) */
        int blender;           /* 0/1: outputs for Blender (atmo_scene_for_blender) */
    } output;
    struct {                   /* homogeneous cloud/fog shell (kernels/cloud_shell/cloud_shell.h) */
        int enabled;
        double bottom_m, top_m; /* altitudes of the shell above sea level */
        int dsd;               /* index into mie_dsd_preset_names */
        double lwc_g_m3;       /* liquid water content */
        int phase;             /* ATMO_CLOUD_PHASE_* */
        double hg_g;           /* g of phase hg (0: the table's g) */
        int sun_disc;          /* 0/1: Mie table convolved with the sun's disc */
        double sun_guiding;    /* reference: probability of the phase lobe around the sun */
    } cloud;
    struct {                   /* the fBm cloud layer (kernels/clouds/cloud_layer.h) */
        int enabled;
        double bottom_m, top_m, fade_m; /* altitudes above sea level; fades inside them */
        double coverage;       /* mean of the coverage field, 0..1 */
        double density;        /* density scale */
        double sharpness;      /* exponent on (coverage - fBm) */
        double frequency_per_m[3]; /* the shape fBm's base frequency per axis */
        double coverage_scale_m; /* the coverage field's largest features */
        int octaves;           /* of the shape fBm */
        double warp_m;         /* domain-warp amplitude */
        int seed;              /* the noise's seed */
        double wind_m_s, wind_azimuth_deg; /* wind speed and the azimuth it blows toward */
        double time_s;         /* time since the noise's origin: moves it by wind x time */
        double extinction_per_m; /* sigma_t at unit density; 0: from the droplet distribution */
        double albedo;         /* with extinction_per_m > 0 */
        char dsd[512];         /* droplet size distribution of the phase table (and optics):
                                  a preset of atmo mie or a SPEC (mie_dsd_parse); "" = cumulus */
        double lwc_g_m3;       /* liquid water at unit density (extinction_per_m = 0) */
        int phase;             /* ATMO_CLOUD_PHASE_* */
        int steps;             /* the marcher's most steps along a view ray */
        double step_m;         /* its step in cloud near the camera */
        int light_steps;       /* steps of the light march toward the sun */
        double light_distance_m; /* its length */
        int shadow_map;        /* 0/1: the sun shadow map (kernels/clouds/cloud_shadow_map.h) */
        int shadow_map_size;   /* its nodes per horizontal axis */
        int shadow_map_levels; /* its nodes between the layer's bottom and top */
        int shadow_map_steps;  /* steps of each node's integral toward the sun */
        double max_distance_m; /* the marcher's far plane */
        double lod;            /* the noise's footprint in pixels (0: every octave everywhere) */
        int ms_octaves;        /* multiple-scattering octaves (1: single scattering only) */
        double ms_a, ms_b, ms_c; /* their extinction, contribution and anisotropy factors */
        double ms_d;           /* the weight of the diffuse orders beyond them */
        int look;              /* ATMO_CLOUDS_LOOK_* */
        double sun_guiding;    /* reference and path.clouds=volume: the same for the layer */
    } clouds;
    struct {                   /* a sphere in the camera's sun plane (Brocken spectre) */
        int enabled;
        double distance_m;     /* horizontally ahead of the camera, toward the antisolar point */
        double height_m;       /* of its centre relative to the camera */
        double radius_m;
    } observer;
    struct {                   /* a digital elevation model as the terrain (atmo/dem.h) */
        char file[512];        /* path; "" = none (procedural terrain only) */
        double extent_m;       /* PNG/EXR: east-west size; GeoTIFF: 0 (from the file) */
        double center_m[2];    /* world X, Z of the grid's centre */
        double scale_m, offset_m; /* PNG: height = offset + scale * value / max value */
        int detail;            /* 0/1: the procedural fBm adds detail below the file's cells */
        int nodata;            /* ATMO_DEM_NODATA_* (dem.h): how missing samples are filled */
    } dem;
    struct {                   /* render.mode = path (kernels/render/path.h) */
        int mode;              /* ATMO_RENDER_* */
        int bounces;           /* N_b: reflections off surfaces per path */
        int secondary;         /* N_s */
        int rr_bounce;         /* Russian roulette from this event on */
        int sun_nee, sky_nee;  /* 0/1 */
        int sky;               /* ATMO_PATH_SKY_* */
        double uniform_sky[3]; /* the uniform test sky's radiance */
        int ground;            /* 0/1 */
        int sampler;           /* ATMO_SAMPLER_* */
        double filter_radius_px, filter_sigma_px;
        double aperture_m, focus_m; /* thin lens (aperture 0: pinhole) */
        int passes;            /* 0/1: render passes (EXR layers) */
        int clouds;            /* ATMO_PATH_CLOUDS_*: how paths meet the fBm cloud layer */
        int volume_bounces;    /* most scattering events in the volume media per path */
        int air;               /* ATMO_PATH_AIR_*: how paths meet the air */
        int air_collisions;    /* path.air = medium: least tentative collisions per flight */
    } path;
    struct {
        int count;
        atmo_object list[ATMO_MAX_OBJECTS];
    } objects;
    struct {                   /* procedural terrain (kernels/terrain/) */
        int enabled;
        double max_height_m;   /* heights lie in [0, max_height_m] above the ground sphere */
        double sea_level_m;    /* water at and below this altitude */
        double frequency_per_m;          /* first octave of the height fBm */
        double coverage_frequency_per_m; /* first octave of the land/sea field */
        double land_fraction;  /* land/sea threshold: 1 all land, 0 all sea */
        double warp;           /* the height fBm's domain warp, first-octave cells */
        int octaves, coverage_octaves;
        int seed;
        int heightmap_size;    /* texels per side; 0: direct evaluation */
        int heightmap_format;  /* ATMO_TERRAIN_FORMAT_* */
        double heightmap_extent_m;
        int steps;             /* sphere-tracing steps */
        double optimism;       /* sphere-tracing step relaxation */
        int shadow;            /* ATMO_TERRAIN_SHADOW_* */
        int shadow_rays, shadow_steps;
        double shadow_far_m;
        int shafts;            /* bit set of ATMO_TERRAIN_SHAFT_* */
        int air_shadows;       /* the terrain shadows the sun at points of the media */
        int sun_visibility;    /* ATMO_TERRAIN_SUN_BY_* */
        int sun_map_size;      /* the sun-height map's texels per side */
        double sun_map_extent_m;
    } terrain;
} atmo_scene;

typedef enum {
    ATMO_PARAM_INT,
    ATMO_PARAM_FLOAT,
    ATMO_PARAM_VEC3,
    ATMO_PARAM_ENUM,
    ATMO_PARAM_BOOL,
    ATMO_PARAM_VEC2,  /* two doubles, e.g. a position X, Z on the ground */
    ATMO_PARAM_STRING /* a char array of ATMO_PARAM_STRING_MAX bytes, e.g. a file path */
} atmo_param_type;

#define ATMO_PARAM_STRING_MAX 512

typedef struct atmo_param {
    const char *key;      /* dotted, e.g. "sun.zenith_deg" */
    atmo_param_type type;
    size_t offset;        /* into atmo_scene */
    const char *unit;     /* "deg", "m", "1/m", "" ... */
    double min, max;      /* valid range, inclusive (each component for vec3) */
    double def[3];        /* default (def[0] for scalars; enum: index) */
    const char *const *names; /* ENUM: NULL-terminated value names */
    const char *help;     /* one line */
} atmo_param;

typedef struct atmo_preset {
    const char *name;
    const char *summary;          /* what it shows, one line */
    const char *const *settings;  /* NULL-terminated "key=value" applied over the defaults */
} atmo_preset;

extern const atmo_preset atmo_presets[]; /* terminated by name == NULL */
extern const char *const atmo_default_preset;

/* The parameter registry (host/scene/scene.c and the feature folders' sets,
 * atmo/scene_params.h): how many rows, row i of them (NULL outside 0 .. count-1), and the
 * index of a row (-1: not in the registry). */
int atmo_param_count(void);
const atmo_param *atmo_param_at(int i);
int atmo_param_index(const atmo_param *p);
const atmo_param *atmo_param_find(const char *key);
const atmo_preset *atmo_preset_find(const char *name);
/* The registry key, or the preset name, near enough to `key` (`name`) to be what a typo meant
 * (atmo/suggest.h), or NULL: for "did you mean" hints. */
const char *atmo_param_closest(const char *key);
const char *atmo_preset_closest(const char *name);
/* A parameter's value as doubles (scalars in v[0]; enum: index; bool: 0/1; vec2: v[0], v[1];
 * string: zeros, see atmo_param_text). */
void atmo_param_get(const atmo_scene *s, const atmo_param *p, double v[3]);
/* Number of doubles a parameter holds: 3 (vec3), 2 (vec2), 1 (others; 0 for strings). */
int atmo_param_components(const atmo_param *p);
/* A string parameter's text (NULL for other types). */
const char *atmo_param_text(const atmo_scene *s, const atmo_param *p);
/* Check a string value (shorter than ATMO_PARAM_STRING_MAX, no control characters) and store
 * it; `where` names its source for the error message. */
int atmo_param_store_text(atmo_scene *s, const atmo_param *p, const char *text, const char *where,
                          atmo_err *e);
/* Check v (finite, in range, whole for int/enum/bool) and store it; `shown` is the value as
 * the user wrote it and `where` its source, both for the error message. */
int atmo_param_store(atmo_scene *s, const atmo_param *p, const double v[3], const char *shown,
                     const char *where, atmo_err *e);

/* The spectral mode's band counts (render.spectral_bands; host/render/spectral_render.c). */
#define ATMO_SPECTRAL_MIN_BANDS 15
#define ATMO_SPECTRAL_MAX_BANDS 470 /* 1 nm bands */
/* Usage error unless bands is 0 or in [ATMO_SPECTRAL_MIN_BANDS, ATMO_SPECTRAL_MAX_BANDS]. */
int atmo_scene_check_spectral_bands(int bands, atmo_err *e);

void atmo_scene_defaults(atmo_scene *s);
/* A number written as a decimal literal in JSON's grammar ("8", "-3", "0.5", "1e3"; no
 * blanks, '+', 0x, inf/nan or leading zero): 1 and *out when text is one, 0 otherwise. The
 * form integer parameters take from text (whether the value is whole is checked apart). */
int atmo_parse_decimal(const char *text, double *out);
/* Set one parameter from text ("60", "1,2,3", "panorama", "true"); `where` names the source
 * for error messages ("--set", "scene.json"). Rejects unknown keys (suggesting the closest),
 * wrong types, NaN/Inf and out-of-range values. */
int atmo_scene_set(atmo_scene *s, const char *key, const char *value, const char *where,
                   atmo_err *e);
/* "key=value" form of atmo_scene_set. */
int atmo_scene_assign(atmo_scene *s, const char *assignment, const char *where, atmo_err *e);
int atmo_scene_apply_preset(atmo_scene *s, const char *name, atmo_err *e);
int atmo_scene_load_json(atmo_scene *s, const char *path, atmo_err *e);
/* The same for a scene text of `length` bytes (NUL-terminated) that came from `path` (named in
 * the errors), e.g. the scene stored in a part file. */
int atmo_scene_load_json_text(atmo_scene *s, const char *text, size_t length, const char *path,
                              atmo_err *e);
/* Whole scene as nested JSON (every key), malloc'd; NULL when out of memory. */
char *atmo_scene_to_json(const atmo_scene *s);
int atmo_scene_save_json(const atmo_scene *s, const char *path, atmo_err *e);
/* The object list from JSON text (an array of objects, scene_objects.c), replacing the
 * scene's; `where` names the source for one-line errors ("--set", the file). The key
 * "objects" of --set, presets and scene files comes here. */
int atmo_scene_set_objects(atmo_scene *s, const char *json, const char *where, atmo_err *e);
/* A parsed JSON tree (cJSON) with a key given twice in one object: ATMO_ERR_USAGE naming the
 * key's path below `prefix` ("sun.zenith_deg", "objects[1].type") and `where`; else ATMO_OK. cJSON keeps
 * both members and a lookup finds the first, so the second would be silently ignored. */
struct cJSON;
int atmo_json_check_duplicates(const struct cJSON *root, const char *prefix, const char *where,
                               atmo_err *e);
/* Every object's values in range (a scene filled in by code); one-line usage error naming
 * objects[i] otherwise. */
int atmo_scene_check_objects(const atmo_scene *s, atmo_err *e);
/* The object list as a JSON array (malloc'd; "[]" for none), NULL when out of memory. */
char *atmo_scene_objects_json(const atmo_scene *s);

/* Checks between parameters (e.g. top radius above bottom radius). */
int atmo_scene_validate(const atmo_scene *s, atmo_err *e);

/* output.blender (scene_blender.c): with it set, rewrite the scene into what Blender reads as it
 * is: render.quantity radiance -> luminance (linear Rec.709 RGB in cd/m^2; the spectral mode is
 * luminance already), post.exposure times ATMO_LUMINANCE_EXPOSURE_SCALE when the quantity
 * changes (so a PNG of the same render keeps its brightness), and a panorama's camera.yaw_deg
 * set to ATMO_BLENDER_PANORAMA_YAW_DEG (Blender's world orientation). Idempotent. Writes what
 * it changed ("key old -> new, ...") into changes (may be NULL) and returns how many keys. */
#define ATMO_LUMINANCE_EXPOSURE_SCALE 1e-5
#define ATMO_BLENDER_PANORAMA_YAW_DEG (-90.0)
int atmo_scene_for_blender(atmo_scene *s, char *changes, int size);

#endif
