/* test_scene_options.c — the scene options shared by `atmo render` and `atmo view`
 * (host/cli/scene_options.c), called with synthetic command lines.
 * labels: unit cli
 *
 * Oracle: the contract of scene_options.h, each case against the scene built by hand from the
 * same calls of atmo/scene.h (defaults, preset, file, assignments), compared field by field
 * exactly (the same double arithmetic, so no tolerance):
 *  - --set and the shorthands apply in command-line order (the last of --width and
 *    --set image.width wins);
 *  - no --preset and no --scene is the default preset; --preset with --scene is refused;
 *  - an end scene (an animation's --scene-end FILE) is the preset unless --scene was given,
 *    then FILE, then the same assignments: --scene's own file is not read for it;
 *  - a missing value, a 257th --set, a shorthand value of the wrong type or out of its key's
 *    range, and one over 40 characters are refused (exit status 2, one line on stderr); a
 *    40-character value of the right type is taken. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "../host/cli/scene_options.h"
#include "testlib.h"

/* A command whose only flags are the scene options, as render and view include them. */
static const cli_flag flags[] = {
    {.type = CLI_INCLUDE, .include = scene_option_flags, .offset = 0},
    {.type = CLI_END},
};
static const cli_command command = {.name = "test", .synopsis = "", .flags = flags};

/* Parse argv[1..] into o as a command does: 1 taken, -1 refused (code 2). */
static int parse(scene_options *o, int argc, char **argv)
{
    int code = -1;
    scene_options_init(o);
    if (cli_parse(&command, o, argc, argv, NULL, NULL, &code))
        return 1;
    CHECK(code == ATMO_ERR_USAGE);
    return -1;
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
    CHECK(parse(&o, 5, a2) == 1);
    CHECK(scene_options_scene(&o, NULL, &got, &e) == ATMO_OK);
    CHECK(got.image.width == 8);

    /* a shorthand is checked against its key: type, range, names */
    char *b1[] = {"render", "--width", "abc"};
    CHECK(parse(&o, 3, b1) == -1);
    char *b2[] = {"render", "--width", "0"};
    CHECK(parse(&o, 3, b2) == -1);
    char *b3[] = {"render", "--camera", "panoramma"};
    CHECK(parse(&o, 3, b3) == -1);
    char *b4[] = {"render", "--width=12", "--camera=panorama"};
    CHECK(parse(&o, 3, b4) == 1);
    CHECK(o.set_count == 2 && strcmp(o.sets[0], "image.width=12") == 0 &&
          strcmp(o.sets[1], "camera.kind=panorama") == 0);

    /* the preset, the file, and both */
    char *a3[] = {"render", "--preset", "sky-noon", "--scene", start_file};
    CHECK(parse(&o, 5, a3) == 1);
    CHECK(scene_options_scene(&o, NULL, &got, &e) == ATMO_ERR_USAGE);
    CHECK(strcmp(e.msg, "--preset and --scene exclude each other; pick one") == 0);

    char *a4[] = {"render", "--scene", start_file, "--set", "sun.zenith_deg=70"};
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
    CHECK(parse(&o, 2, a6) == -1);
    static char *many[2 * SCENE_OPTIONS_MAX_SETS + 3];
    many[0] = "render";
    for (int k = 0; k <= SCENE_OPTIONS_MAX_SETS; k++) {
        many[1 + 2 * k] = "--set";
        many[2 + 2 * k] = "image.samples=1";
    }
    CHECK(parse(&o, 2 * SCENE_OPTIONS_MAX_SETS + 1, many) == 1); /* 256 */
    CHECK(o.set_count == SCENE_OPTIONS_MAX_SETS);
    CHECK(parse(&o, 2 * SCENE_OPTIONS_MAX_SETS + 3, many) == -1); /* 257 */
    char forty[41], forty_one[42]; /* 0.000...01 s: a number in clouds.time_s's range */
    memset(forty, '0', 40);
    forty[1] = '.', forty[39] = '1', forty[40] = 0;
    memset(forty_one, '0', 41);
    forty_one[1] = '.', forty_one[40] = '1', forty_one[41] = 0;
    char *a7[] = {"render", "--time", forty};
    CHECK(parse(&o, 3, a7) == 1);
    CHECK(o.set_count == 1 && strcmp(o.sets[0] + strlen("clouds.time_s="), forty) == 0);
    char *a8[] = {"render", "--time", forty_one};
    CHECK(parse(&o, 3, a8) == -1);

    remove(end_file);
    remove(start_file);
    remove(dir);
    return test_finish();
}
