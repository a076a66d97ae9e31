/*
 * celc_import.h - `celc import` and `celc text`, for the celc dispatcher.
 *
 * Both take the subcommand's own argv: argv[0] is the subcommand name
 * ("import" / "text"), options follow. They return a process exit status
 * (0 success, 1 bad input, 2 usage) and print errors and warnings on stderr.
 */
#ifndef CELC_IMPORT_H
#define CELC_IMPORT_H

/* celc import drawing.svg -o scene.json [--tolerance T] [--nominal PX] [--background C] [-q] */
int celc_import_main(int argc, char **argv);

/* celc text "string" -o scene.json [--font F] [--size S] [--position X,Y] [--color C]
 *                                   [--canvas WxH] [--background C] */
int celc_text_main(int argc, char **argv);

#endif /* CELC_IMPORT_H */
