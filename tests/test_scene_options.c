/* test_scene_options.c — the scene options shared by `atmo render` and `atmo view`
 * (host/cli/scene_options.c), called with synthetic command lines.
 * labels: unit cli
 *
 * Oracle: the contract of scene_options.h, each case against the scene built by hand from the
 * same calls of atmo/scene.h (defaults, preset, file, assignments), compared field by field
 * exactly (the same double arithmetic, so no tolerance):
 *  - --set and render's shorthands apply in command-line order (the last of --width and
 *    --set image.width wins), and the viewer's parser does not take the shorthands;
 *  - no --preset and no --scene is the default preset; --preset with --scene is refused;
 *  - an end scene (an animation's --scene-end FILE) is the preset unless --scene was given,
 *    then FILE, then the same assignments: --scene's own file is not read for it;
 *  - a missing value, a 257th --set and a shorthand value over 40 characters are refused (-1,
 *    one line on stderr); a 40-character value is taken (validation judges it). */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "../host/cli/scene_options.h"
#include "testlib.h"

/* Feed argv[1..] through the parser as a command's loop does; the first refusal's code. */
static int parse(scene_options *o, int argc, char **argv)
{
    for (int i = 1; i < argc; i++) {
        int taken = scene_options_take(o, argc, argv, &i);
        if (taken <= 0)
            return taken;
    }
    return 1;
}

static void same_scene(const atmo_scene *a, const atmo_scene *b)
{
    CHECK(a->image.width == b->image.width);
    CHECK(a->image.height == b->image.height);
    CHECK(a->image.samples == b->image.samples);
    CHECK(a->sun.zenith_deg == b->sun.zenith_deg);
    CHECK(a->camera.pitch_deg == b->camera.pitch_deg);
    CHECK(a->camera.fov_deg == b->camera.fov_deg);
    CHECK(a->camera.kind == b->camera.kind);
}

static void write_file(const char *path, const char *text)
{
    FILE *f = fopen(path, "w");
    CHECK(f != NULL);
    if (f) {
        fputs(text, f);
        fclose(f);
    }
}

int main(void)
{
    atmo_err e = {{0}};
    scene_options o;
    atmo_scene got, want;
    char dir[] = "/tmp/atmo-scene-options-XXXXXX", end_file[64], start_file[64];
    CHECK(mkdtemp(dir) != NULL);
    snprintf(end_file, sizeof end_file, "%s/end.json", dir);
    snprintf(start_file, sizeof start_file, "%s/start.json", dir);
    write_file(end_file, "{\"sun\": {\"zenith_deg\": 40}}\n");
    write_file(start_file, "{\"camera\": {\"fov_deg\": 30}}\n");

    /* order: the last assignment of a key wins, shorthands among the --set options */
    char *a1[] = {"render", "--width", "8", "--set", "image.width=9", "--height", "4",
                  "--samples", "2", "--camera", "panorama"};
    scene_options_init(&o, "render", 1);
    CHECK(parse(&o, 11, a1) == 1);
    CHECK(scene_options_scene(&o, NULL, &got, &e) == ATMO_OK);
    atmo_scene_defaults(&want);
    atmo_scene_apply_preset(&want, atmo_default_preset, &e);
    atmo_scene_assign(&want, "image.width=9", "--set", &e);
    atmo_scene_assign(&want, "image.height=4", "--set", &e);
    atmo_scene_assign(&want, "image.samples=2", "--set", &e);
    atmo_scene_assign(&want, "camera.kind=panorama", "--set", &e);
    same_scene(&got, &want);
    CHECK(got.image.width == 9 && got.image.height == 4);
    char *a2[] = {"render", "--set", "image.width=9", "--width", "8"};
    scene_options_init(&o, "render", 1);
    CHECK(parse(&o, 5, a2) == 1);
    CHECK(scene_options_scene(&o, NULL, &got, &e) == ATMO_OK);
    CHECK(got.image.width == 8);

    /* the viewer takes no shorthands: --width is left to its own loop (an unknown option) */
    int i = 1;
    scene_options_init(&o, "view", 0);
    CHECK(scene_options_take(&o, 5, a2, &i) == 1 && i == 2);
    i = 3;
    CHECK(scene_options_take(&o, 5, a2, &i) == 0 && i == 3);

    /* the preset, the file, and both */
    char *a3[] = {"render", "--preset", "sky-noon", "--scene", start_file};
    scene_options_init(&o, "render", 1);
    CHECK(parse(&o, 5, a3) == 1);
    CHECK(scene_options_scene(&o, NULL, &got, &e) == ATMO_ERR_USAGE);
    CHECK(strcmp(e.msg, "--preset and --scene exclude each other; pick one") == 0);

    char *a4[] = {"render", "--scene", start_file, "--set", "sun.zenith_deg=70"};
    scene_options_init(&o, "render", 1);
    CHECK(parse(&o, 5, a4) == 1);
    CHECK(scene_options_scene(&o, NULL, &got, &e) == ATMO_OK);
    atmo_scene_defaults(&want);
    atmo_scene_load_json(&want, start_file, &e);
    atmo_scene_assign(&want, "sun.zenith_deg=70", "--set", &e);
    same_scene(&got, &want);
    CHECK(got.camera.fov_deg == 30.0 && got.sun.zenith_deg == 70.0);
    /* its end scene: the defaults (no preset), the end file, the --set; not start.json */
    CHECK(scene_options_scene(&o, end_file, &got, &e) == ATMO_OK);
    atmo_scene_defaults(&want);
    atmo_scene_load_json(&want, end_file, &e);
    atmo_scene_assign(&want, "sun.zenith_deg=70", "--set", &e);
    same_scene(&got, &want);
    CHECK(got.camera.fov_deg != 30.0);

    /* with a preset the end scene starts from the preset */
    char *a5[] = {"render", "--preset", "sky-sunset", "--height", "6"};
    scene_options_init(&o, "render", 1);
    CHECK(parse(&o, 5, a5) == 1);
    CHECK(scene_options_scene(&o, end_file, &got, &e) == ATMO_OK);
    atmo_scene_defaults(&want);
    atmo_scene_apply_preset(&want, "sky-sunset", &e);
    atmo_scene_load_json(&want, end_file, &e);
    atmo_scene_assign(&want, "image.height=6", "--set", &e);
    same_scene(&got, &want);
    CHECK(got.camera.pitch_deg == 10.0 && got.sun.zenith_deg == 40.0 && got.image.height == 6);

    /* refusals */
    char *a6[] = {"view", "--set"};
    scene_options_init(&o, "view", 0);
    CHECK(parse(&o, 2, a6) == -1);
    static char *many[2 * SCENE_OPTIONS_MAX_SETS + 3];
    many[0] = "render";
    for (int k = 0; k <= SCENE_OPTIONS_MAX_SETS; k++) {
        many[1 + 2 * k] = "--set";
        many[2 + 2 * k] = "image.samples=1";
    }
    scene_options_init(&o, "render", 1);
    CHECK(parse(&o, 2 * SCENE_OPTIONS_MAX_SETS + 1, many) == 1); /* 256 */
    CHECK(o.set_count == SCENE_OPTIONS_MAX_SETS);
    scene_options_init(&o, "render", 1);
    CHECK(parse(&o, 2 * SCENE_OPTIONS_MAX_SETS + 3, many) == -1); /* 257 */
    char forty[41], forty_one[42];
    memset(forty, '1', 40);
    forty[40] = 0;
    memset(forty_one, '1', 41);
    forty_one[41] = 0;
    char *a7[] = {"render", "--seed", forty};
    scene_options_init(&o, "render", 1);
    CHECK(parse(&o, 3, a7) == 1);
    CHECK(o.set_count == 1 && strcmp(o.sets[0] + strlen("image.seed="), forty) == 0);
    char *a8[] = {"render", "--seed", forty_one};
    scene_options_init(&o, "render", 1);
    CHECK(parse(&o, 3, a8) == -1);

    remove(end_file);
    remove(start_file);
    remove(dir);
    return test_finish();
}
