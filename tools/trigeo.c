/* trigeo.c - the trigeo command-line tool: the command table, help and dispatch; main.
 * Based on: the CLI contract of the project's DESIGN.md (commands, exit codes, error format). */
#include "cli.h"

#include <errno.h>
#include <string.h>
#ifdef _OPENMP
#include <omp.h>
#endif

static const cli_command* const commands[] = {
    &cli_cmd_info,
    &cli_cmd_closest,
    &cli_cmd_render,
    &cli_cmd_path,
    &cli_cmd_field,
    &cli_cmd_trace,
    &cli_cmd_logmap,
    &cli_cmd_sample,
    &cli_cmd_compare,
    &cli_cmd_mean,
};
#define COMMAND_COUNT (sizeof commands / sizeof commands[0])

static void print_overview(FILE* f)
{
    fprintf(f, "trigeo %s - distances and shortest paths on triangle meshes\n\n", tg_version());
    fprintf(f, "usage: trigeo COMMAND [ARGS...]\n\ncommands:\n");
    for (size_t i = 0; i < COMMAND_COUNT; ++i) fprintf(f, "  trigeo %s\n", commands[i]->synopsis);
    fprintf(f, "  trigeo help [COMMAND]\n  trigeo --version\n\n");
    fprintf(f, "Meshes: OBJ, OFF, PLY (ascii, binary), STL (ascii, binary), optionally .gz; '-' reads the\n"
               "mesh from standard input (gzip data is inflated; the format from --format obj|off|ply|stl or the\n"
               "content).\n");
    fprintf(f, "Indices are 0-based in file order. Exit codes: 0 ok, 1 usage, 2 input/IO error, 130 interrupted\n"
               "(Ctrl-C or SIGTERM).\n");
    fprintf(f, "Outputs (-o) appear only when complete: written into a private temporary directory beside the\n"
               "target and renamed; an existing character device or FIFO is written directly; an output that\n"
               "is one of the inputs is refused.\n");
}

static const cli_command* find_command(const char* name)
{
    for (size_t i = 0; i < COMMAND_COUNT; ++i)
        if (strcmp(commands[i]->name, name) == 0) return commands[i];
    return NULL;
}

/* The command names as the help lists them ("info, closest, ..., help"), from the table. */
static void print_command_names(FILE* f)
{
    for (size_t i = 0; i < COMMAND_COUNT; ++i) fprintf(f, "%s, ", commands[i]->name);
    fputs("help", f);
}

static int dispatch(int argc, char** argv);

/* Ends the OpenMP runtime's worker threads (the batch commands start them) before main returns:
 * the runtime joins them only in its library destructor, after the exit-time leak check of a
 * sanitizer build, whose tracer crashed now and then on a worker still parked in the runtime
 * (tests/tg_test.h, tg_test_release_threads). */
static void release_threads(void)
{
#ifdef _OPENMP
    (void)omp_pause_resource_all(omp_pause_hard);
#endif
}

/* Every exit goes through here: output that could not be written (a full disk, /dev/full, a
 * closed pipe) is an error, exit 2, never a silent success. */
int main(int argc, char** argv)
{
    int rc = dispatch(argc, argv);
    int err = 0;
    if (fflush(stdout) != 0 || ferror(stdout)) err = errno ? errno : EIO;
    release_threads();
    if (err) {
        cli_error("-", 0, "cannot write the output to stdout: %s", strerror(err));
        return rc == CLI_OK ? CLI_INPUT : rc;
    }
    return rc;
}

static int dispatch(int argc, char** argv)
{
    if (argc < 2) {
        print_overview(stderr);
        return CLI_USAGE;
    }
    const char* cmd = argv[1];
    if (!strcmp(cmd, "--help") || !strcmp(cmd, "-h")) {
        print_overview(stdout);
        return CLI_OK;
    }
    if (!strcmp(cmd, "--version")) {
        printf("trigeo %s\n", tg_version());
        return CLI_OK;
    }
    if (!strcmp(cmd, "help")) {
        if (argc < 3) {
            print_overview(stdout);
            return CLI_OK;
        }
        if (!strcmp(argv[2], "help") || !strcmp(argv[2], "--help") || !strcmp(argv[2], "-h")) {
            printf("usage: trigeo help [COMMAND]\n\nWithout COMMAND: the list of commands. With one: its full help (the same as\n"
                   "'trigeo COMMAND --help'). Commands: ");
            print_command_names(stdout);
            printf(".\n");
            return CLI_OK;
        }
        const cli_command* c = find_command(argv[2]);
        if (!c) {
            fprintf(stderr, "trigeo: unknown command '%s' (commands: ", argv[2]);
            print_command_names(stderr);
            fputs(")\n(see 'trigeo help')\n", stderr);
            return CLI_USAGE;
        }
        printf("usage: trigeo %s\n\n%s", c->synopsis, c->help);
        return CLI_OK;
    }
    const cli_command* c = find_command(cmd);
    if (!c) {
        cli_error(NULL, 0, "unknown command '%s' (try 'trigeo --help')", cmd);
        return CLI_USAGE;
    }
    /* --format FMT (every command): taken out here, it applies to the mesh */
    for (int i = 2; i < argc; ++i) {
        if (strcmp(argv[i], "--format")) continue;
        static const char* const names[] = {"obj", "off", "ply", "stl"};
        static const tg_format formats[] = {TG_FORMAT_OBJ, TG_FORMAT_OFF, TG_FORMAT_PLY, TG_FORMAT_STL};
        int k = 0;
        while (i + 1 < argc && k < 4 && strcmp(argv[i + 1], names[k])) ++k;
        if (i + 1 >= argc || k == 4) return cli_usage(cmd, "--format takes obj, off, ply or stl");
        cli_set_mesh_format(formats[k]);
        for (int j = i; j + 2 <= argc; ++j) argv[j] = argv[j + 2];
        argc -= 2;
        --i;
    }
    /* a mesh read from standard input leaves none for another input */
    if (argc > 2 && !strcmp(argv[2], "-"))
        for (int i = 3; i < argc; ++i)
            if (!strcmp(argv[i], "-") && strcmp(argv[i - 1], "-o") && strcmp(argv[i - 1], "--csv"))
                return cli_usage(cmd, "the mesh is read from standard input ('-'): another input cannot be too");
    for (int i = 2; i < argc; ++i) {
        if (!strcmp(argv[i], "--help") || !strcmp(argv[i], "-h")) {
            printf("usage: trigeo %s\n\n%s", c->synopsis, c->help);
            return CLI_OK;
        }
    }
    cli_interrupt_install(); /* Ctrl-C: exit 130, no temporary left, whatever the command does */
    return c->run(argc - 1, argv + 1);
}
