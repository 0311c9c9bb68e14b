/* commands.h — the subcommands of the atmo CLI. Each takes the arguments after its name
 * (argv[0] is the subcommand's name) and returns the process exit code (status.h). */
#ifndef ATMO_COMMANDS_H
#define ATMO_COMMANDS_H

typedef struct atmo_command {
    const char *name;
    const char *summary;
    int (*run)(int argc, char **argv);
} atmo_command;

int cmd_render(int argc, char **argv);
int cmd_devices(int argc, char **argv);
int cmd_params(int argc, char **argv);
int cmd_presets(int argc, char **argv);
int cmd_bench(int argc, char **argv);
int cmd_mie(int argc, char **argv);
int cmd_radiance(int argc, char **argv);
int cmd_cache(int argc, char **argv);
int cmd_view(int argc, char **argv);
int cmd_merge(int argc, char **argv);
int cmd_dem(int argc, char **argv);
int cmd_terrain(int argc, char **argv);

#endif
