/*
 * cli.c - main() for a program of subcommands (see cli.h).
 *
 * The program's name is kept for cli_usage_error, so a command's option
 * parser reports a bad argument in one call, as it returns.
 */
#include "cli.h"

#include <stdarg.h>
#include <stdio.h>
#include <string.h>

static const char *program = "";

int cli_usage_error(const char *fmt, ...)
{
    va_list ap;
    fprintf(stderr, "%s: ", program);
    va_start(ap, fmt);
    vfprintf(stderr, fmt, ap);
    va_end(ap);
    fputc('\n', stderr);
    return CLI_EXIT_USAGE;
}

int cli_main(const cli_program *p, int argc, char **argv)
{
    program = p->name;
    if (argc < 2) {
        fputs(p->usage, stderr);
        return CLI_EXIT_USAGE;
    }
    const char *cmd = argv[1];
    if (strcmp(cmd, "-h") == 0 || strcmp(cmd, "--help") == 0 || strcmp(cmd, "help") == 0) {
        fputs(p->usage, stdout);
        return 0;
    }
    for (int i = 0; i < p->command_count; i++)
        if (strcmp(cmd, p->commands[i].name) == 0)
            return p->commands[i].run(argc - 1, argv + 1);
    return cli_usage_error("unknown command '%s' (%s)", cmd, p->unknown);
}
