/* view_script.c — `atmo view --script FILE`: synthetic input for tests and demos.
 *
 * One action per line ('#' starts a comment; blank lines are skipped):
 *   wait SECONDS          let SECONDS of real time pass
 *   wait-samples N        wait until every pixel of the current image has N samples (the
 *                         image after the last change; N above the scene's image.samples
 *                         waits for those)
 *   press KEY [MODS]      one key press, as from the keyboard (view_controls.c)
 *   hold KEY SECONDS [MODS]  hold a movement key (W A S D Q E) for SECONDS of simulated time,
 *                         integrated in ticks of 1/60 s whatever the real frame rate
 *   look DX DY            a mouse drag of DX, DY window pixels
 *   quit                  close the viewer
 * KEY is a letter, a digit, or one of Up Down Left Right Tab Escape F1 Equal Minus; MODS is
 * shift, ctrl or shift+ctrl. The viewer runs the actions in order between frames, so a script
 * gives the same scene changes on every run: movement depends on the simulated time of a hold,
 * never on the frame rate. (The alternative, an X event injector such as xdotool, would need
 * another package and makes movement depend on real key-repeat timing.) */
#include <GLFW/glfw3.h>
#include <ctype.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "view_script.h"

static const struct {
    const char *name;
    int key;
} named_keys[] = {{"Up", GLFW_KEY_UP},       {"Down", GLFW_KEY_DOWN},   {"Left", GLFW_KEY_LEFT},
                  {"Right", GLFW_KEY_RIGHT}, {"Tab", GLFW_KEY_TAB},     {"Escape", GLFW_KEY_ESCAPE},
                  {"F1", GLFW_KEY_F1},       {"Equal", GLFW_KEY_EQUAL}, {"Minus", GLFW_KEY_MINUS}};

static int key_code(const char *name)
{
    if (name[0] && !name[1] && isalnum((unsigned char)name[0]))
        return toupper((unsigned char)name[0]); /* GLFW's codes of letters and digits are ASCII */
    for (size_t i = 0; i < sizeof named_keys / sizeof named_keys[0]; i++)
        if (strcmp(name, named_keys[i].name) == 0)
            return named_keys[i].key;
    return -1;
}

static int mods_code(const char *word)
{
    if (!word)
        return 0;
    if (strcmp(word, "shift") == 0)
        return GLFW_MOD_SHIFT;
    if (strcmp(word, "ctrl") == 0)
        return GLFW_MOD_CONTROL;
    if (strcmp(word, "shift+ctrl") == 0 || strcmp(word, "ctrl+shift") == 0)
        return GLFW_MOD_SHIFT | GLFW_MOD_CONTROL;
    return -1;
}

static int number(const char *word, double lo, double hi, double *out)
{
    char *end;
    if (!word)
        return 0;
    *out = strtod(word, &end);
    return *end == 0 && end != word && *out >= lo && *out <= hi;
}

static int parse_line(char *line, view_action *a)
{
    char *w[5] = {NULL};
    int n = 0;
    for (char *t = strtok(line, " \t\r\n"); t && n < 5; t = strtok(NULL, " \t\r\n"))
        w[n++] = t;
    if (n == 0)
        return 0;
    if (strcmp(w[0], "wait") == 0 && n == 2 && number(w[1], 0.0, 3600.0, &a->value))
        a->kind = VIEW_ACT_WAIT;
    else if (strcmp(w[0], "wait-samples") == 0 && n == 2 && number(w[1], 1.0, 1e6, &a->value))
        a->kind = VIEW_ACT_WAIT_SAMPLES;
    else if (strcmp(w[0], "press") == 0 && (n == 2 || n == 3) && (a->key = key_code(w[1])) >= 0 &&
             (a->mods = mods_code(w[2])) >= 0)
        a->kind = VIEW_ACT_PRESS;
    else if (strcmp(w[0], "hold") == 0 && (n == 3 || n == 4) && !w[1][1] &&
             strchr("WASDQE", toupper((unsigned char)w[1][0])) &&
             number(w[2], 0.0, 3600.0, &a->value) && (a->mods = mods_code(w[3])) >= 0) {
        a->kind = VIEW_ACT_HOLD;
        a->key = toupper((unsigned char)w[1][0]);
    }
    else if (strcmp(w[0], "look") == 0 && n == 3 && number(w[1], -1e5, 1e5, &a->value) &&
             number(w[2], -1e5, 1e5, &a->value2))
        a->kind = VIEW_ACT_LOOK;
    else if (strcmp(w[0], "quit") == 0 && n == 1)
        a->kind = VIEW_ACT_QUIT;
    else
        return -1;
    return 1;
}

int view_script_load(view_script *s, const char *path, atmo_err *e)
{
    memset(s, 0, sizeof *s);
    s->started = -1.0;
    FILE *f = fopen(path, "r");
    if (!f)
        return atmo_fail(e, ATMO_ERR_USAGE, "--script '%s': cannot open it", path);
    char line[512];
    int lineno = 0, rc = ATMO_OK;
    while (fgets(line, sizeof line, f)) {
        lineno++;
        char *hash = strchr(line, '#');
        if (hash)
            *hash = 0;
        view_action a = {0};
        a.line = lineno;
        int got = parse_line(line, &a);
        if (got < 0) {
            rc = atmo_fail(e, ATMO_ERR_USAGE,
                           "%s:%d: not an action; write wait S, wait-samples N, press KEY "
                           "[shift|ctrl], hold W|A|S|D|Q|E S [shift|ctrl], look DX DY or quit",
                           path, lineno);
            break;
        }
        if (!got)
            continue;
        view_action *grown = realloc(s->actions, (size_t)(s->count + 1) * sizeof *grown);
        if (!grown) {
            rc = atmo_fail(e, ATMO_ERR_RUNTIME, "out of memory reading '%s'", path);
            break;
        }
        s->actions = grown;
        s->actions[s->count++] = a;
    }
    fclose(f);
    if (rc)
        view_script_free(s);
    return rc;
}

void view_script_free(view_script *s)
{
    free(s->actions);
    memset(s, 0, sizeof *s);
}
