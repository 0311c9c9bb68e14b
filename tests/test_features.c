/* test_features — the feature registry (host/plan/features.c, host/features/) and what a plan
 * assembles from it.
 * labels: unit
 *
 * Oracle: the registry's contract (atmo/features.h, DESIGN "models no more than a scene
 * needs"), written out per method:
 *  1. every fragment and source a row names is embedded (a misspelt source would silently drop
 *     out of a cache key); every feature folder registered its set and every row of the sets
 *     and of the engine is in the registry once, with an order of its own (so the registry's
 *     order does not hang on the order the build lists the folders in), in a band that
 *     atmo/features.h names, the registry sorted by it; names are unique;
 *  2. each method's plan has exactly its named buffers, in registry order, its -D flags, and
 *     none of the fragments of features it does not contain; the generated parameter and
 *     argument lists name the buffers in that order;
 *  3. a cloud shell adds its medium after the media's contract (media.h) and before the plan's
 *     composition of the media, its stepping after the visibility and before the composition of
 *     the intervals, which precedes the integrator; the composition numbers its component after
 *     the air's and calls its functions (a sky-only composition names no cloud and has no
 *     intervals); it adds its flag and its phase table as a buffer of its own with host data; a
 *     sky-only scene's assembled source holds no cloud code (sizes printed: what the shell
 *     costs to compile);
 *  4. the composition refuses two features in a slot that takes one (a registry bug) and a
 *     buffer too small for the text;
 *  5. the path tracer's volume medium (row clouds_path_volume, slot volume_at) composes the
 *     volume functions from its row (MEDIA_VOLUME 1, media_volume_at calling its volume_at) and
 *     enters the walk's majorant in volume mode only, while a medium of the methods' walk
 *     (clouds_tracked) enters it in every mode but volume mode; without a volume medium the
 *     volume functions are the empty medium's and the majorant has no mode test; two volume
 *     media are refused. The media group of the largest composition (the air, the volume
 *     medium, the tracked layer, the layer's medium, the cloud shell, Psi_ms) must fit the
 *     plan's 8192-byte buffer (its size printed).
 *  6. the render stages take the features through their slots: the path tracer's surfaces
 *     (the terrain's and the objects' hits and shadow-ray tests in registry order, the ground
 *     sphere a surface unless the terrain replaces it), the preview's camera stages (the
 *     objects' before the terrain's, the method's sky_trace last; fast's terrain stage
 *     integrates the tables, single's only adds the water), the guides' pattern and media (the
 *     path tracer's 8 x 8 filtered rays and segments, the preview's 4 x 4 box; the shell's
 *     chord per ray, the layer's march per block); each composed fragment stands after the
 *     rows whose functions it calls and before its callers, and a plan's -D flags hold no
 *     flag that only a render stage used to test. */
#include <stdlib.h>
#include <string.h>
#include "atmo/cl_runtime.h"
#include "atmo/embedded.h"
#include "atmo/features.h"
#include "atmo/scene.h"
#include "atmosphere/sky_method.h"
#include "testlib.h"
#include "testscene.h"

static int fragment_at(const atmo_plan *p, const char *name)
{
    for (int i = 0; i < p->fragment_count; i++)
        if (strcmp(p->fragments[i], name) == 0)
            return i;
    return -1;
}

/* Every set's rows are in the registry, which is sorted by order, one row per order and
 * name, each order in a band (ATMO_BAND_BASE ... ATMO_BAND_GUIDES + 99); the feature
 * folders of this tree registered their sets. */
static void test_registry_order(void)
{
    int rows = 0, sets = 0;
    for (const atmo_feature_set *const *set = atmo_feature_sets; *set; set++, sets++) {
        CHECK((*set)->count > 0);
        for (int k = 0; k < (*set)->count; k++, rows++)
            CHECK(atmo_feature_find((*set)->rows[k].name) == &(*set)->rows[k]);
    }
    static const char *const folders[] = {"atmosphere", "cloud_shell", "clouds",
                                          "objects",    "path",        "terrain"};
    CHECK(sets == (int)(sizeof folders / sizeof folders[0]));
    for (size_t k = 0; k < sizeof folders / sizeof folders[0]; k++) {
        int found = 0;
        for (const atmo_feature_set *const *set = atmo_feature_sets; *set; set++)
            found += strcmp((*set)->name, folders[k]) == 0;
        CHECK(found == 1);
    }
    int engine = 0;
    for (int i = 0; i < atmo_feature_count(); i++) {
        const atmo_feature *f = atmo_feature_at(i);
        CHECK(f->order >= ATMO_BAND_BASE && f->order < ATMO_BAND_GUIDES + 100);
        if (i > 0)
            CHECK(atmo_feature_at(i - 1)->order < f->order);
        for (int j = 0; j < i; j++)
            CHECK(strcmp(atmo_feature_at(j)->name, f->name) != 0);
        engine += f->compose != ATMO_COMPOSE_NONE;
    }
    /* the engine's rows: a composition per group, and the visibility, the integrator, the
     * render kernels, the surface queries and the guides */
    CHECK(engine == ATMO_COMPOSE_GROUPS - 1);
    CHECK(atmo_feature_count() == rows + engine + 5);
    CHECK(atmo_feature_at(atmo_feature_count()) == NULL && atmo_feature_at(-1) == NULL);
}

static void test_registry_files(void)
{
    for (int i = 0; i < atmo_feature_count(); i++) {
        const atmo_feature *f = atmo_feature_at(i);
        /* a row is files, slots or a generated composition; a composition has no files */
        CHECK(f->fragments || f->slots || f->compose != ATMO_COMPOSE_NONE);
        CHECK(!(f->fragments && f->compose != ATMO_COMPOSE_NONE));
        for (const char *const *s = f->fragments; s && *s; s++)
            CHECK(atmo_embedded_find(atmo_kernel_sources, *s) != NULL);
        for (const char *const *s = f->sources; s && *s; s++)
            CHECK(atmo_embedded_find(atmo_kernel_sources, *s) != NULL);
        for (const char *const *n = f->needs; n && *n; n++)
            CHECK(atmo_feature_find(*n) != NULL);
        CHECK((f->params == NULL) == (f->sources == NULL));
    }
}

/* The plan's buffers are exactly `names` (NULL-terminated) and its prelude lists them. */
static void check_buffers(const atmo_plan *p, const char *const *names)
{
    char params[512] = "#define ATMO_LUT_PARAMS", args[256] = "#define ATMO_LUT_ARGS";
    int n = 0;
    for (; names[n]; n++) {
        CHECK(n < p->buffer_count && strcmp(p->buffers[n].name, names[n]) == 0);
        snprintf(params + strlen(params), sizeof params - strlen(params),
                 "%s ATMO_GLOBAL const %s *%s", n ? "," : "",
                 n < p->buffer_count ? p->buffers[n].type : "?", names[n]);
        snprintf(args + strlen(args), sizeof args - strlen(args), "%s %s", n ? "," : "",
                 names[n]);
    }
    CHECK(p->buffer_count == n);
    CHECK(strstr(p->prelude, params) != NULL);
    CHECK(strstr(p->prelude, args) != NULL);
}

typedef struct method_case {
    const char *method;
    const char *buffers[5];
    const char *defines;
    const char *own;  /* the method's entry fragment */
} method_case;

static void test_methods(void)
{
    static const method_case cases[] = {
        {"single", {"transmittance_lut", NULL}, "", "kernels/atmosphere/method_single.h"},
        {"march", {"transmittance_lut", "ms_lut", NULL}, "",
         "kernels/atmosphere/method_march.h"},
        {"fast", {"transmittance_lut", "ms_lut", "sky_view_lut", NULL}, "",
         "kernels/atmosphere/method_fast.h"},
        {"lut",
         {"transmittance_lut", "scattering_rayleigh", "scattering_mie", "scattering_scratch",
          NULL},
         "", "kernels/atmosphere/method_lut.h"},
        {"reference", {"transmittance_lut", NULL}, "", "kernels/atmosphere/method_reference.h"},
    };
    static const char *const entries[] = {
        "kernels/atmosphere/method_single.h", "kernels/atmosphere/method_march.h",
        "kernels/atmosphere/method_fast.h", "kernels/atmosphere/method_lut.h",
        "kernels/atmosphere/method_reference.h"};
    for (size_t c = 0; c < sizeof cases / sizeof cases[0]; c++) {
        const method_case *m = &cases[c];
        atmo_plan p;
        test_sky_plan(m->method, 0.0, 30.0, &p);
        check_buffers(&p, m->buffers);
        CHECK(strcmp(p.defines, m->defines) == 0);
        CHECK(strcmp(p.method, m->method) == 0);
        for (int i = 0; i < 5; i++)
            CHECK((fragment_at(&p, entries[i]) >= 0) == (strcmp(entries[i], m->own) == 0));
        /* every method integrates the same media: the medium integrator comes before it */
        CHECK(fragment_at(&p, "kernels/media/medium.h") >= 0 &&
              fragment_at(&p, "kernels/media/medium.h") < fragment_at(&p, m->own));
        CHECK(fragment_at(&p, "kernels/cloud_shell/cloud_shell.h") < 0);
        /* common headers first, the render kernels last: the image's, then the guide pass's */
        CHECK(fragment_at(&p, "kernels/common/compat.h") == 0);
        CHECK(fragment_at(&p, "kernels/render/guides.cl") == p.fragment_count - 1);
        CHECK(fragment_at(&p, "kernels/render/sky.cl") >= 0 &&
              fragment_at(&p, "kernels/render/sky.cl") < p.fragment_count - 1);
        /* passes: the transmittance LUT's first, each pass owned by a planned feature */
        CHECK(p.pass_count >= 1 && strcmp(p.passes[0].kernel, "transmittance_lut") == 0);
        for (int i = 0; i < p.pass_count; i++)
            CHECK(p.passes[i].feature >= 0 && p.passes[i].feature < p.feature_count);
        int view = atmo_plan_buffer_index(&p, "sky_view_lut");
        CHECK(view < 0 || p.buffers[view].follows_view);
    }
}

static size_t source_size(const atmo_plan *p, const char *needle, int *has)
{
    atmo_err e;
    const char *texts[ATMO_PLAN_MAX_FRAGMENTS];
    atmo_plan_fragment_texts(p, texts);
    char *src = atmo_cl_assemble(p->prelude, p->fragments, texts, p->fragment_count, NULL, &e);
    CHECK(src != NULL);
    size_t n = src ? strlen(src) : 0;
    *has = src && strstr(src, needle) != NULL;
    free(src);
    return n;
}

static void test_cloud(void)
{
    atmo_scene s;
    atmo_plan sky, cloud, observer;
    test_scene_preset(&s, "sky-noon");
    test_scene_set(&s, "atmosphere.method=march");
    test_plan(&s, &sky);
    test_scene_set(&s, "cloud.enabled=true");
    test_plan(&s, &cloud);
    static const char *const with_table[] = {"transmittance_lut", "cloud_phase_table",
                                             "cloud_phase_cdf", "ms_lut", NULL};
    check_buffers(&cloud, with_table);
    CHECK(strcmp(cloud.defines, "-DATMO_CLOUD") == 0);
    int shell = fragment_at(&cloud, "kernels/cloud_shell/cloud_shell.h");
    int media = fragment_at(&cloud, "plan/media");
    int intervals = fragment_at(&cloud, "plan/intervals");
    /* a medium: after the media's contract, before the composition of the media, which comes
     * before the visibility; its stepping after the visibility, before the composition of the
     * intervals, which comes before the integrator */
    CHECK(shell > fragment_at(&cloud, "kernels/media/media.h"));
    CHECK(shell < media && media < fragment_at(&cloud, "kernels/media/visibility.h"));
    CHECK(fragment_at(&cloud, "kernels/media/visibility.h") <
          fragment_at(&cloud, "kernels/cloud_shell/cloud_shell_march.h"));
    CHECK(fragment_at(&cloud, "kernels/cloud_shell/cloud_shell_march.h") < intervals);
    CHECK(intervals < fragment_at(&cloud, "kernels/media/medium.h"));
    CHECK(shell < fragment_at(&cloud, "kernels/atmosphere/method_march.h"));
    /* the composition: the shell's component numbered after the air's, its functions called
     * (and Psi_ms as march's source); the sky alone has the air and no intervals */
    CHECK(strstr(cloud.prelude, "#define MEDIA_CLOUD 2\n#define MEDIA_COMPONENTS 3\n") != NULL);
    CHECK(strstr(sky.prelude, "#define MEDIA_COMPONENTS 2\n") != NULL);
    CHECK(strstr(sky.prelude, "MEDIA_CLOUD") == NULL);
    const char *texts[ATMO_PLAN_MAX_FRAGMENTS];
    atmo_plan_fragment_texts(&cloud, texts);
    CHECK(strstr(texts[media], "cloud_shell_media_add(s, ATMO_LUT_ARGS, q, &m);") != NULL);
    CHECK(strstr(texts[media], "return ms_lut_ms_source(") != NULL);
    CHECK(strstr(texts[intervals], "return cloud_shell_intervals(") != NULL);
    atmo_plan_fragment_texts(&sky, texts);
    CHECK(strstr(texts[fragment_at(&sky, "plan/media")], "cloud") == NULL);
    CHECK(strstr(texts[fragment_at(&sky, "plan/intervals")], "return 0;") != NULL);
    const atmo_plan_buffer *table = atmo_plan_buffer_find(&cloud, "cloud_phase_table");
    CHECK(table->host_data != NULL && cloud.gpu.cloud.table_size > 1 &&
          table->bytes == sizeof(float4) * (size_t)cloud.gpu.cloud.table_size);
    CHECK(cloud.gpu.cloud.top_m > cloud.gpu.cloud.base_m);

    test_scene_set(&s, "cloud.enabled=false");
    test_scene_set(&s, "observer.enabled=true");
    test_scene_set(&s, "atmosphere.method=single");
    test_plan(&s, &observer);
    table = atmo_plan_buffer_find(&observer, "cloud_phase_table");
    /* one zero row, and table_size says so (the kernel's search reads rows[0 .. size-1]) */
    CHECK(table && table->bytes == sizeof(float4) && observer.gpu.cloud.table_size == 1);
    CHECK(observer.gpu.cloud.observer.w > 0.0f);

    int sky_has, cloud_has;
    size_t n_sky = source_size(&sky, "ATMO_FN void cloud_shell_interval(", &sky_has);
    size_t n_cloud = source_size(&cloud, "ATMO_FN void cloud_shell_interval(", &cloud_has);
    CHECK(cloud_has && source_size(&cloud, "#line 1 \"plan/media\"", &cloud_has) && cloud_has);
    CHECK(!sky_has && cloud_has && n_cloud > n_sky);
    printf("march: assembled source %zu bytes sky-only, %zu with the cloud shell (+%zu)\n", n_sky,
           n_cloud, n_cloud - n_sky);
}

/* The generator refuses a slot that takes one feature when two fill it (two media with their
 * own stepping, two methods' sources), and composes each alone. */
static void test_compose_single_slots(void)
{
    static char text[8192];
    const atmo_feature *both_media[] = {atmo_feature_find("cloud"),
                                        atmo_feature_find("clouds_medium")};
    const atmo_feature *both_sources[] = {atmo_feature_find("ms_lut"), atmo_feature_find("lut")};
    CHECK(atmo_compose(both_media, 2, ATMO_COMPOSE_INTERVALS, text, sizeof text) == -1);
    CHECK(atmo_compose(both_sources, 2, ATMO_COMPOSE_MEDIA, text, sizeof text) == -1);
    CHECK(atmo_compose(both_media, 1, ATMO_COMPOSE_INTERVALS, text, sizeof text) == 0);
    CHECK(atmo_compose(both_sources + 1, 1, ATMO_COMPOSE_MEDIA, text, sizeof text) == 0 &&
          strstr(text, "return lut_ms_source(") != NULL);
    CHECK(atmo_compose(both_media, 2, ATMO_COMPOSE_MEDIA, text, 64) == -1); /* does not fit */
}

/* The volume medium's composition (5 above). */
static void test_compose_volume(void)
{
    static char text[8192], big[8192];
    const atmo_feature *volume = atmo_feature_find("clouds_path_volume");
    const atmo_feature *tracked = atmo_feature_find("clouds_tracked");
    CHECK(volume && tracked);
    if (!volume || !tracked)
        return;
    const atmo_feature *rows[] = {atmo_feature_find("atmosphere"), volume, tracked};
    CHECK(atmo_compose(rows, 3, ATMO_COMPOSE_MEDIA, text, sizeof text) == 0);
    CHECK(strstr(text, "#define MEDIA_VOLUME 1") != NULL);
    CHECK(strstr(text, "return clouds_volume_at(s, ATMO_LUT_ARGS, q, scattering);") != NULL);
    CHECK(strstr(text, "if (mode == MEDIA_WALK_VOLUME)\n        clouds_track_begin(") != NULL);
    CHECK(strstr(text, "if (mode != MEDIA_WALK_VOLUME)\n        clouds_track_begin(") != NULL);
    const atmo_feature *plain[] = {atmo_feature_find("atmosphere"), tracked};
    CHECK(atmo_compose(plain, 2, ATMO_COMPOSE_MEDIA, text, sizeof text) == 0);
    CHECK(strstr(text, "#define MEDIA_VOLUME 0") != NULL);
    CHECK(strstr(text, "MEDIA_WALK_VOLUME") == NULL);
    CHECK(strstr(text, "    *scattering = v3(0.0f, 0.0f, 0.0f);") != NULL);
    const atmo_feature *two[] = {volume, volume};
    CHECK(atmo_compose(two, 2, ATMO_COMPOSE_MEDIA, text, sizeof text) == -1);
    const atmo_feature *largest[] = {atmo_feature_find("atmosphere"), atmo_feature_find("cloud"),
                                     volume, tracked, atmo_feature_find("clouds_medium"),
                                     atmo_feature_find("ms_lut")};
    CHECK(atmo_compose(largest, 6, ATMO_COMPOSE_MEDIA, big, sizeof big) == 0);
    printf("the largest media composition: %zu of %zu bytes\n", strlen(big), sizeof big);
}

/* The render stages' compositions (6 above). */
static void test_compose_stages(void)
{
    static char text[8192];
    const atmo_feature *terrain = atmo_feature_find("terrain_path");
    const atmo_feature *objects = atmo_feature_find("objects_path");
    const atmo_feature *both[] = {terrain, objects};
    CHECK(atmo_compose(both, 2, ATMO_COMPOSE_PATH_SURFACES, text, sizeof text) == 0);
    CHECK(strstr(text, "#define SURFACES_GROUND_SPHERE 0") != NULL);
    const char *t = strstr(text, "terrain_path_hit(s, ATMO_LUT_ARGS, m, h);");
    CHECK(t && strstr(t, "objects_path_hit(s, ATMO_LUT_ARGS, m, h);") != NULL);
    CHECK(strstr(text, "if (terrain_path_occluded(s, ATMO_LUT_ARGS, o, d))") != NULL);
    CHECK(atmo_compose(&objects, 1, ATMO_COMPOSE_PATH_SURFACES, text, sizeof text) == 0);
    CHECK(strstr(text, "#define SURFACES_GROUND_SPHERE 1") != NULL &&
          strstr(text, "terrain") == NULL);

    const atmo_feature *stages[] = {atmo_feature_find("march"), atmo_feature_find("objects_stage"),
                                    atmo_feature_find("terrain_stage")};
    CHECK(atmo_compose(stages, 3, ATMO_COMPOSE_CAMERA, text, sizeof text) == 0);
    t = strstr(text, "if (objects_stage_trace(");
    CHECK(t && (t = strstr(t, "if (terrain_stage_trace_tables(")) != NULL &&
          strstr(t, "sky_trace(s, ATMO_LUT_ARGS, ray, INFINITY, g, sky, sun, view_t);") != NULL);
    CHECK(atmo_compose(stages, 1, ATMO_COMPOSE_CAMERA, text, sizeof text) == 0);
    CHECK(strstr(text, "_stage_trace") == NULL && strstr(text, "sky_trace(") != NULL);

    const atmo_feature *path_guides[] = {atmo_feature_find("cloud"), atmo_feature_find("clouds"),
                                         atmo_feature_find("path")};
    CHECK(atmo_compose(path_guides, 3, ATMO_COMPOSE_GUIDES, text, sizeof text) == 0);
    CHECK(strstr(text, "#define GUIDES_GRID 8") != NULL);
    CHECK(strstr(text, "return path_camera_pixel_ray(s, x, y, u1, u2);") != NULL);
    CHECK(strstr(text, "return path_media_shown(s, t_end);") != NULL);
    CHECK(strstr(text, "d = cloud_shell_guide_depth(s, m, t_end, &w);") != NULL);
    CHECK(strstr(text, "clouds_guide_block(s, m, n, ends, step_scale, tau_stop, tau,") != NULL);
    CHECK(atmo_compose(path_guides, 0, ATMO_COMPOSE_GUIDES, text, sizeof text) == 0);
    CHECK(strstr(text, "#define GUIDES_GRID 4") != NULL && strstr(text, "path_") == NULL &&
          strstr(text, "cloud") == NULL);

    /* the fragments in order: the features' functions, their composition, its callers */
    atmo_scene s;
    atmo_plan p;
    test_scene_preset(&s, "sky-noon");
    test_scene_set(&s, "terrain.enabled=true");
    test_scene_set(&s, "atmosphere.method=fast");
    test_scene_set(&s, "render.mode=path");
    test_plan(&s, &p);
    CHECK(fragment_at(&p, "kernels/terrain/terrain_path.h") >= 0 &&
          fragment_at(&p, "kernels/terrain/terrain_path.h") < fragment_at(&p, "plan/path_surfaces"));
    CHECK(fragment_at(&p, "plan/path_surfaces") < fragment_at(&p, "kernels/render/surfaces.h"));
    CHECK(fragment_at(&p, "kernels/render/surfaces.h") < fragment_at(&p, "kernels/render/path.h"));
    CHECK(fragment_at(&p, "kernels/render/path.h") < fragment_at(&p, "plan/guides"));
    CHECK(fragment_at(&p, "plan/guides") < fragment_at(&p, "kernels/render/guides.cl"));
    CHECK(strstr(p.defines, "ATMO_TERRAIN_STAGE_TABLES") == NULL);
    atmo_plan_free(&p);
    test_scene_set(&s, "render.mode=preview");
    test_plan(&s, &p);
    CHECK(fragment_at(&p, "kernels/terrain/terrain_stage.h") < fragment_at(&p, "plan/camera") &&
          fragment_at(&p, "plan/camera") < fragment_at(&p, "kernels/render/sky.cl"));
    CHECK(p.gpu.path.ground == 1); /* the preview's guides have the ground sphere */
    atmo_plan_free(&p);
}

#define ARGS_TEXT(...) #__VA_ARGS__
#define EXPANDED_TEXT(...) ARGS_TEXT(__VA_ARGS__)

/* The host build's buffer list (atmosphere/sky_method.h, one list for every scene) names every
 * buffer that the plans of scenes holding every feature declare, and declares no other. */
static void test_host_buffer_list(void)
{
    static const char *const scenes[][3] = {
        {"thesis-1", "clouds.shadow_map=true", NULL},       /* layer, shadow map, terrain */
        {"thesis-2", "atmosphere.method=fast", NULL},        /* objects, sky-view LUT */
        {"thesis-7", NULL},                                  /* the path tracer's sky table */
        {"glory", "atmosphere.method=reference", NULL},      /* the cloud shell's tables */
        {"thesis-6", "atmosphere.method=reference", NULL},   /* the layer's majorant grid */
        {"sky-noon", "atmosphere.method=lut", NULL},         /* lut's tables */
    };
    /* the list's names, split at its commas */
    char list[1024], *names[64];
    int count = 0, used[64] = {0};
    snprintf(list, sizeof list, "%s", EXPANDED_TEXT(ATMO_LUT_ARGS));
    for (char *name = strtok(list, ", "); name && count < 64; name = strtok(NULL, ", "))
        names[count++] = name;
    for (size_t k = 0; k < sizeof scenes / sizeof scenes[0]; k++) {
        atmo_scene sc;
        atmo_err e;
        atmo_plan p;
        atmo_scene_defaults(&sc);
        int rc = atmo_scene_apply_preset(&sc, scenes[k][0], &e);
        for (int i = 1; i < 3 && scenes[k][i] && !rc; i++)
            rc = atmo_scene_assign(&sc, scenes[k][i], "test", &e);
        sc.image.width = sc.image.height = 8;
        if (!rc)
            rc = atmo_plan_make(&sc, &p, &e);
        CHECK(rc == ATMO_OK);
        if (rc)
            continue;
        for (int b = 0; b < p.buffer_count; b++) {
            int index = -1;
            for (int i = 0; i < count && index < 0; i++)
                if (strcmp(names[i], p.buffers[b].name) == 0)
                    index = i;
            CHECK(index >= 0);
            if (index >= 0)
                used[index] = 1;
        }
        atmo_plan_free(&p);
    }
    for (int i = 0; i < count; i++)
        CHECK(used[i]);
}

int main(void)
{
    test_registry_order();
    test_registry_files();
    test_compose_single_slots();
    test_compose_volume();
    test_compose_stages();
    test_methods();
    test_cloud();
    test_host_buffer_list();
    return test_finish();
}
