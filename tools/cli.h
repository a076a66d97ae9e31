/*
 * cli.h - the part of main() that the host programs with subcommands share
 * (celsim, celc, svgimport): the help text on -h, --help or help (to standard output,
 * exit 0) and without a command (to standard error, exit 2), the dispatch
 * to a command's own main, an unknown command named, and usage errors as
 * one line "PROGRAM: message" with exit status 2.
 *
 * Numbers on the command line are cli_num.h's.
 */
#ifndef CLI_H
#define CLI_H

#define CLI_EXIT_USAGE 2

typedef struct cli_command {
    const char *name;
    int (*run)(int argc, char **argv); /* argv[0] is the command's name; returns the exit status */
} cli_command;

typedef struct cli_program {
    const char *name;       /* the prefix of its messages: "celc" */
    const char *usage;      /* the whole help text */
    const char *unknown;    /* after "unknown command 'X'" in brackets: "see celc --help" */
    const cli_command *commands;
    int command_count;
} cli_program;

/* Runs the command argv[1] names; returns main()'s exit status. */
int cli_main(const cli_program *p, int argc, char **argv);

/* "PROGRAM: message" on stderr (the program cli_main runs); returns CLI_EXIT_USAGE. */
#if defined(__GNUC__)
__attribute__((format(printf, 1, 2)))
#endif
int cli_usage_error(const char *fmt, ...);

#endif /* CLI_H */
