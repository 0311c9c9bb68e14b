/* scene_presets.c — the built-in scenes: each a list of "key=value" applied over the defaults.
 *
 * Camera convention (scene.h, presets.md): forward = (-cos p sin y, sin p, cos p cos y),
 * right = (cos y, 0, sin y); the sun direction is (sin z sin a, cos z, sin z cos a), so a camera
 * with yaw y faces the sun's azimuth when a = -y. The default perspective frame is 45 degrees
 * high and 640x360, so about +-36 degrees wide.
 *
 * The default, `planet`, is thesis view 9 at 2 samples per pixel: the first picture a user sees
 * shows the planet (its curve, the limb, clouds over mountains at sunset) and takes well under a
 * minute at the default 640x360 on two CPU cores; at 2 samples per pixel the march's noise is
 * already below what the PNG shows (docs/guide/usage.md has the measurement). `atmo
 * radiance` does not start from it: its scene is the defaults' clear air.
 *
 * Sky presets (camera on the ground at 1.7 m, yaw 0, i.e. looking along +Z):
 *   sky-noon       sun at the zenith, pitch 10 so the horizon sits in the lower third.
 *   sky-afternoon  sun zenith 60, azimuth 45: 30 degrees high and 45 degrees to the right of the
 *                  view, just outside the frame's right edge.
 *   sky-sunset     sun zenith 88, azimuth 0 = -yaw: straight ahead, 2 degrees above the horizon,
 *                  8 degrees below the centre of a frame pitched up by 10.
 *   space          2000 km above the origin, pitch -50; sun zenith 70 at azimuth 120 (behind
 *                  and to the right), so the day side fills the view and the terminator crosses
 *                  the upper left of the disc; terrain with its land/sea field at threshold 0.35:
 *                  continents and oceans (about 28 % sea within 2800 km of the origin).
 *
 * thesis-1 ... thesis-9 are the nine views of shared/reference/presets.md. Their "direction to
 * sun" vectors were converted with z = acos(d_y), a = atan2(d_x, d_z) and written with six
 * decimals of a degree; they reproduce the table's vectors to better than 5e-7 (test_scene.c).
 * The thesis objects (presets.md) are in the views that show them: the sphere and the blue box
 * of view 2, the open box (four boxes: left, right, floor, back wall; no ceiling, no front) and
 * its three small spheres in views 3 and 7, at the thesis' world positions (they sat on its
 * terrain). View 7 is path traced (render.mode = path, 5 bounces, the thesis' N_b): light enters
 * the open box from above and bounces inside it.
 * Thesis 1, 4, 5, 6, 8 and 9 have the fBm cloud layer (with method march, which it needs, the
 * thesis' far plane for clouds as clouds.max_distance_m, and a noise seed that gives each view
 * what the thesis' shows: seed 0 a deck under view 5's glory (the march of
 * tests/test_preset_clouds.c through 32 x 18 pixels reaches optical depth 1 in cloud on every
 * ray of the lower half and 94 % of all; seed 5, that of views 4 and 9, leaves 64 % of the
 * lower half clear, and 0 is the first seed to cover it), seed 47 scattered cumulus around
 * view 6's sun, where seed 0 puts view 6's camera inside a cloud; seed 55 clear air around
 * view 8's camera with clouds under 31 % of its view and terrain under the rest, where seed 5
 * hides all of its terrain under cloud: tests/test_preset_clouds.c measures both (the
 * coverage field's 500 km features lie over the whole view, so a seed tends to give a view of
 * nearly all cloud or nearly all terrain); seed 333 a sunset-lit cumulus left of view 1's snowy peak:
 * cloud under 12 % of the view, none in the sky within 0.4 frame heights of the sun, which sets
 * just behind the peak, and all the terrain of the cloudless view kept, where seed 44 clouds 52
 * of the 79 rays of that sky; tests/test_preset_clouds.c measures these, and a scan of seeds
 * 0-999 at 32 x 18 rays found eight that meet them; of the three rendered (131, 333, 477) 333
 * has the most cloud with the whole terrain kept).
 * Views 1, 2, 3, 8 and 9 and `space` have the procedural terrain (docs/guide/terrain.md). The
 * thesis views' seed 7 puts land under every thesis camera and snow-capped mountains of up to
 * 3.9 km in view 1 (tests/test_terrain_thesis.c), its camera 330 m above the ground (`atmo
 * terrain --at X,Z`); `space` keeps seed 46, whose land/sea field gives its continents. Seed
 * 7 puts views 2's and 3's sites in a ridge's shadow at their low suns (6.7 and 3.7 degrees),
 * where the objects' own shadows cannot show; those two views take seed 34, the same
 * mountains' field (first octave 1e-4 /m), on which both sites and the ground 20 m around them
 * see the sun (tests/test_terrain_thesis.c; of seeds 0-159 only 25, 30, 34, 52, 66, 75 and 126
 * light both sites fully over land, none of them with view 1's snow as well) on slopes of 7
 * and 12 degrees.
 * In the views with terrain (2, 3) the objects stand on it ("on_terrain":
 * their heights above the terrain's surface), about 660 m below (view 2) and 500 m above (view 3)
 * where the thesis' terrain had them, and so do the cameras (camera.on_terrain=at, their
 * heights taken at the objects' anchors), keeping presets.md's offsets from the objects: view
 * 2's camera 6 m above the sphere's centre (7 m above the terrain at the sphere's foot), view
 * 3's 1 m above the open box's floor (1.25 m above the terrain at the box's centre, the box's
 * floor top at 0.25 m), both at presets.md's x and z. View 7 has no terrain and keeps the
 * thesis' absolute heights, its camera's offset from the box with them. */
#include <string.h>
#include "atmo/scene.h"

const char *const atmo_default_preset = "planet";

#define PRESET(name, summary, ...) {name, summary, (const char *const[]){__VA_ARGS__, NULL}}
#define THESIS_TERRAIN_OBJECTS " [terrain and objects; the objects on this terrain]"
#define THESIS_OBJECTS " [objects over the sea-level ground, path traced]"
#define THESIS_CLOUDS " [clouds]"
#define THESIS_CLOUDS_TERRAIN " [clouds and terrain]"
/* the thesis views' terrain: a 10 km first octave (steep mountains, docs/guide/terrain.md)
 * and seed 7; views 2 and 3 on seed 34, whose sites the low sun reaches. Sphere tracing with
 * optimism 4: no error in 35708 hits over these mountains (tests/test_terrain_miss_rate.c; 5
 * gave 3); the default field keeps 3 (4 missed 1 of its 32570). No domain warp: the seeds,
 * sites, cameras and cloud seeds were chosen by scanning the unwarped field, which a warp
 * moves; from these cameras, a few hundred metres to 37 km up, the first octave's 10 km
 * lattice does not show (docs/guide/terrain.md). */
#define THESIS_MOUNTAINS                                                                           \
    "terrain.seed=7", "terrain.frequency_per_m=1e-4", "terrain.optimism=4", "terrain.warp=0"
#define THESIS_SITES                                                                               \
    "terrain.seed=34", "terrain.frequency_per_m=1e-4", "terrain.optimism=4", "terrain.warp=0"
/* presets.md's objects (albedo in linear RGB; the small spheres' (38, 25, 17)/255 written out) */
/* view 2's sphere resting on the terrain (centre 1 m above it) and its box standing on it */
#define THESIS_VIEW2_OBJECTS                                                                       \
    "objects=[{\"type\": \"sphere\", \"center_m\": [22832, 1, 13326], \"radius_m\": 1, "         \
    "\"albedo\": [1, 1, 1], \"on_terrain\": true}, {\"type\": \"box\", \"min_m\": [22832.2, 0, "   \
    "13326.7], \"size_m\": [2, 2, 2], \"albedo\": [0, 0, 1], \"on_terrain\": true}]"
#define THESIS_OPEN_BOX_OBJECTS                                                                    \
    "objects=[{\"type\": \"box\", \"min_m\": [26630, 1336, 10749], \"size_m\": [1, 1, 1], "     \
    "\"albedo\": [0.9, 0.1, 0.1]}, {\"type\": \"box\", \"min_m\": [26632, 1336, 10749], "        \
    "\"size_m\": [1, 1, 1], \"albedo\": [0.1, 0.9, 0.1]}, {\"type\": \"box\", \"min_m\": "      \
    "[26630, 1335, 10749], \"size_m\": [3, 1, 1], \"albedo\": [0.7, 0.7, 0.7]}, {\"type\": "      \
    "\"box\", \"min_m\": [26630, 1336, 10750], \"size_m\": [3, 1, 1], \"albedo\": [0.7, 0.7, "   \
    "0.7]}, {\"type\": \"sphere\", \"center_m\": [26631.33, 1336.12, 10749.66], \"radius_m\": "  \
    "0.12, \"albedo\": [0.149019608, 0.098039216, 0.066666667]}, {\"type\": \"sphere\", "        \
    "\"center_m\": [26631.66, 1336.12, 10749.66], \"radius_m\": 0.12, \"albedo\": [1, 0.5, "     \
    "0.15]}, {\"type\": \"sphere\", \"center_m\": [26631.5, 1336.12, 10749.33], \"radius_m\": "  \
    "0.12, \"albedo\": [1, 1, 1]}]"

/* the same open box on the terrain (views with terrain): its heights relative to the thesis'
 * ground level 1336 m, plus 0.25 m so the floor's top clears the terrain's rise of up to 0.2 m
 * across the box's base (atmo terrain --at its corners), all taken at the box's centre */
#define OPEN_BOX_ANCHOR "\"on_terrain\": true, \"terrain_at_m\": [26631.5, 10749.5]"
#define THESIS_OPEN_BOX_ON_TERRAIN                                                                 \
    "objects=[{\"type\": \"box\", \"min_m\": [26630, 0.25, 10749], \"size_m\": [1, 1, 1], "        \
    "\"albedo\": [0.9, 0.1, 0.1], " OPEN_BOX_ANCHOR "}"                                            \
    ", {\"type\": \"box\", \"min_m\": [26632, 0.25, 10749], \"size_m\": [1, 1, 1], "               \
    "\"albedo\": [0.1, 0.9, 0.1], " OPEN_BOX_ANCHOR "}"                                            \
    ", {\"type\": \"box\", \"min_m\": [26630, -0.75, 10749], \"size_m\": [3, 1, 1], "              \
    "\"albedo\": [0.7, 0.7, 0.7], " OPEN_BOX_ANCHOR "}"                                            \
    ", {\"type\": \"box\", \"min_m\": [26630, 0.25, 10750], \"size_m\": [3, 1, 1], "               \
    "\"albedo\": [0.7, 0.7, 0.7], " OPEN_BOX_ANCHOR "}"                                            \
    ", {\"type\": \"sphere\", \"center_m\": [26631.33, 0.37, 10749.66], \"radius_m\": 0.12, "      \
    "\"albedo\": [0.149019608, 0.098039216, 0.066666667], " OPEN_BOX_ANCHOR "}"                    \
    ", {\"type\": \"sphere\", \"center_m\": [26631.66, 0.37, 10749.66], \"radius_m\": 0.12, "      \
    "\"albedo\": [1, 0.5, 0.15], " OPEN_BOX_ANCHOR "}"                                             \
    ", {\"type\": \"sphere\", \"center_m\": [26631.5, 0.37, 10749.33], \"radius_m\": 0.12, "       \
    "\"albedo\": [1, 1, 1], " OPEN_BOX_ANCHOR "}]"

/* view 9 (presets.md): 37 km up, the sunset over the cloud field and the mountains */
#define THESIS_VIEW9                                                                               \
    "camera.kind=perspective", "camera.position_m=18181,37415,3431", "camera.pitch_deg=-16",     \
        "camera.yaw_deg=-556", "camera.fov_deg=45", "sun.zenith_deg=87.476967",                  \
        "sun.azimuth_deg=-150.985019", "clouds.enabled=true", "clouds.seed=5",                   \
        "clouds.max_distance_m=4e5", "atmosphere.method=march", "terrain.enabled=true",          \
        THESIS_MOUNTAINS

const atmo_preset atmo_presets[] = {
    PRESET("planet",
           "the default: thesis view 9 (a high-altitude sunset over clouds and mountains) at "
           "2 samples per pixel",
           THESIS_VIEW9, "image.samples=2"),
    PRESET("sky-noon",
           "clear sky at noon from the ground, sun at the zenith, looking at the horizon",
           "camera.kind=perspective", "camera.position_m=0,1.7,0", "camera.pitch_deg=10",
           "camera.yaw_deg=0", "sun.zenith_deg=0", "sun.azimuth_deg=0"),
    PRESET("sky-afternoon", "afternoon sky, sun 30 degrees high about 45 degrees right of the view",
           "camera.kind=perspective", "camera.position_m=0,1.7,0", "camera.pitch_deg=10",
           "camera.yaw_deg=0", "sun.zenith_deg=60", "sun.azimuth_deg=45"),
    PRESET("sky-sunset",
           "sunset looking toward the sun, 2 degrees above the horizon, low in the frame",
           "camera.kind=perspective", "camera.position_m=0,1.7,0", "camera.pitch_deg=10",
           "camera.yaw_deg=0", "sun.zenith_deg=88", "sun.azimuth_deg=0"),
    PRESET("space", "the planet from 2000 km: day side with continents and oceans, terminator at the upper "
                    "left, blue limb",
           "camera.kind=perspective", "camera.position_m=0,2e6,0", "camera.pitch_deg=-50",
           "camera.yaw_deg=0", "camera.fov_deg=45", "sun.zenith_deg=70", "sun.azimuth_deg=120",
           "terrain.enabled=true", "terrain.seed=46",
           "terrain.land_fraction=0.35"),
    PRESET("thesis-1",
           "thesis view 1: sunset over snowy mountains, light shafts, clouds" THESIS_CLOUDS_TERRAIN
           " (cloud seed 333: a sunset-lit cumulus left of the peak, the sky around the sun "
           "clear)",
           "camera.kind=perspective", "camera.position_m=23796,2266,16636",
           "camera.pitch_deg=-4.962", "camera.yaw_deg=-550", "camera.fov_deg=45",
           "sun.zenith_deg=87.476967", "sun.azimuth_deg=-150.985019",
           "clouds.enabled=true", "clouds.seed=333", "clouds.max_distance_m=1.5e5",
           "atmosphere.method=march", "terrain.enabled=true", THESIS_MOUNTAINS),
    PRESET("thesis-2",
           "thesis view 2: looking down at a small sphere and box, shadows" THESIS_TERRAIN_OBJECTS,
           "camera.kind=perspective", "camera.position_m=22831,7,13332",
           "camera.on_terrain=at", "camera.terrain_at_m=22832,13326", "camera.pitch_deg=-51.5", "camera.yaw_deg=-518", "camera.fov_deg=45",
           "sun.zenith_deg=83.222271", "sun.azimuth_deg=171.887327", THESIS_VIEW2_OBJECTS,
           "terrain.enabled=true", THESIS_SITES),
    PRESET("thesis-3",
           "thesis view 3: low sun near the open-box site, sun in frame" THESIS_TERRAIN_OBJECTS,
           "camera.kind=perspective", "camera.position_m=26632,1.25,10748", "camera.on_terrain=at",
           "camera.terrain_at_m=26631.5,10749.5", "camera.pitch_deg=-5",
           "camera.yaw_deg=-575", "camera.fov_deg=45", "sun.zenith_deg=86.098524",
           "sun.azimuth_deg=-134.254613", THESIS_OPEN_BOX_ON_TERRAIN,
           "terrain.enabled=true", THESIS_SITES),
    PRESET("thesis-4",
           "thesis view 4: the planet from 2000 km, terminator, cloud field, blue "
           "limb" THESIS_CLOUDS,
           "camera.kind=perspective", "camera.position_m=0,2000000,0", "camera.pitch_deg=-50",
           "camera.yaw_deg=-601", "camera.fov_deg=45", "sun.zenith_deg=88.452425",
           "sun.azimuth_deg=-150.984989",
           "clouds.enabled=true", "clouds.seed=5", "clouds.max_distance_m=4.9e6",
           "atmosphere.method=march"),
    PRESET("thesis-5",
           "thesis view 5: cloud tops away from the sun, glory and fog bow" THESIS_CLOUDS,
           "camera.kind=perspective", "camera.position_m=61950,42398,-83371",
           "camera.pitch_deg=-34", "camera.yaw_deg=-549", "camera.fov_deg=45",
           "sun.zenith_deg=35.396615", "sun.azimuth_deg=0",
           "clouds.enabled=true", "clouds.seed=0", "clouds.max_distance_m=2e5",
           "atmosphere.method=march"),
    PRESET("thesis-6",
           "thesis view 6: sky with the sun and clouds, lens flare, bright cloud "
           "edges" THESIS_CLOUDS,
           "camera.kind=perspective", "camera.position_m=23796,2266,16636",
           "camera.pitch_deg=15.038", "camera.yaw_deg=-519", "camera.fov_deg=45",
           "sun.zenith_deg=62.332413", "sun.azimuth_deg=154.698581", "post.flare=true",
           "clouds.enabled=true", "clouds.seed=47", "clouds.max_distance_m=1.5e5",
           "atmosphere.method=march"),
    PRESET("thesis-7", "thesis view 7: looking +Z into an open box, path traced" THESIS_OBJECTS,
           "camera.kind=perspective", "camera.position_m=26631.5,1336.5,10747.5",
           "camera.pitch_deg=0", "camera.yaw_deg=0", "camera.fov_deg=45",
           "sun.zenith_deg=86.098524", "sun.azimuth_deg=-134.254613", THESIS_OPEN_BOX_OBJECTS,
           "render.mode=path", "path.bounces=5"),
    PRESET("thesis-8",
           "thesis view 8: over clouds and terrain at moderate sun" THESIS_CLOUDS_TERRAIN
           " (cloud seed 55: clear air at the camera, cloud under about a third of the view)",
           "camera.kind=perspective", "camera.position_m=7866,5837,-143910", "camera.pitch_deg=-29",
           "camera.yaw_deg=-535", "camera.fov_deg=45", "sun.zenith_deg=81.435892",
           "sun.azimuth_deg=-170.007181",
           "clouds.enabled=true", "clouds.seed=55", "clouds.max_distance_m=1e5",
           "atmosphere.method=march", "terrain.enabled=true", THESIS_MOUNTAINS),
    PRESET("thesis-9", "thesis view 9: high-altitude sunset over clouds" THESIS_CLOUDS_TERRAIN,
           THESIS_VIEW9),
    PRESET("glory",
           "above a cloud deck of thesis-disperse drops, looking down at the antisolar point: "
           "the fog bow and the glory's bright centre (its one ring lies within 1 deg, smoothed "
           "by the sun's disc; thesis view 5's sun)",
           "camera.kind=perspective", "camera.position_m=0,3000,0", "camera.pitch_deg=-53.85",
           "camera.yaw_deg=180", "camera.fov_deg=90", "sun.zenith_deg=36.15",
           "sun.azimuth_deg=0", "atmosphere.method=march", "cloud.enabled=true",
           "cloud.bottom_m=1000", "cloud.top_m=2000", "cloud.dsd=thesis-disperse",
           "cloud.lwc_g_m3=0.3", "post.exposure=4"),
    PRESET("corona", "the sun 30 degrees high through a thin cloud of narrow-sized drops: corona "
                     "rings around it",
           "camera.kind=perspective", "camera.position_m=0,1.7,0", "camera.pitch_deg=30",
           "camera.yaw_deg=0", "camera.fov_deg=20", "sun.zenith_deg=60", "sun.azimuth_deg=0",
           "atmosphere.method=march", "cloud.enabled=true", "cloud.bottom_m=5000",
           "cloud.top_m=5200", "cloud.dsd=corona", "cloud.lwc_g_m3=0.01", "post.exposure=0.5"),
    PRESET("brocken",
           "Brocken spectre: the photographer's shadow on a fog bank 15 m below, at the "
           "antisolar point, ringed by the glory of stratus drops",
           "camera.kind=perspective", "camera.position_m=0,1015,0", "camera.pitch_deg=-25",
           "camera.yaw_deg=180", "camera.fov_deg=20", "sun.zenith_deg=65", "sun.azimuth_deg=0",
           "atmosphere.method=march", "cloud.enabled=true", "cloud.bottom_m=500",
           "cloud.top_m=1000", "cloud.dsd=stratus", "cloud.lwc_g_m3=0.1", "observer.enabled=true",
           "observer.distance_m=0.3", "observer.height_m=-0.6", "observer.radius_m=1",
           "post.exposure=4"),
    {NULL, NULL, NULL},
};

const atmo_preset *atmo_preset_find(const char *name)
{
    for (const atmo_preset *p = atmo_presets; p->name; p++)
        if (strcmp(p->name, name) == 0)
            return p;
    return NULL;
}
