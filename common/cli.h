/* cli.h — the option values and usage errors every tool's main() shares,
 * so that every command reports a bad value the same way (git's
 * parse-options habit). gb_cli_options runs getopt_long and hands each
 * option to the tool, which hands each value to one of these functions.
 *
 * Exit codes, for every tool: 0 success, 1 failure (a file, the work),
 * 2 usage (a bad option, a bad value, a missing argument).
 *
 * Every parse function returns GB_EXIT_SUCCESS (and stores the value) or,
 * after printing a usage error on stderr, GB_EXIT_USAGE (the value
 * untouched). A usage error is one line naming what is wrong, then one
 * line pointing at the help:
 *     TOOL: --OPTION: 'TEXT' is not an integer in LOW..HIGH
 *     TOOL: --OPTION: 'TEXT' is not a number in [LOW, HIGH]
 *     TOOL: --OPTION: 'TEXT' is not WxH with each side in 1..MAX
 *     TOOL: --OPTION: 'TEXT' is not I/N with I in 0..N-1
 *     TOOL: --OPTION: 'TEXT' is not one of A, B, C
 *     TOOL: unknown option '--foo'          (gb_cli_option_error)
 *     TOOL: WHAT                            (gb_cli_usage_error)
 *     Try 'TOOL --help' for more information.
 * never the whole help. The caller returns the status from main().
 * The help and the version go to stdout (gb_cli_help, gb_cli_version); a
 * failure of the work is "TOOL: MESSAGE" on stderr (gb_cli_failure).
 * Nothing else here prints. The caller owns every string passed in; TOOL
 * is the bare name ("voxelize"), OPTION the long name without its dashes.
 *
 * A tool describes its command line in a gb_cli_command, and its main()
 * is one call, on arguments of its own that start zeroed:
 *     return gb_cli_main(&command, argc, argv, run, &(arguments){0});
 */
#ifndef GB_CLI_H
#define GB_CLI_H

#include <getopt.h>
#include <stdint.h>

#include "result.h"

enum {
    GB_EXIT_SUCCESS = 0,
    GB_EXIT_FAILURE = 1,
    GB_EXIT_USAGE = 2,
    GB_CLI_GO_ON = -1,      /* a parse_arguments() result: not an exit, run */
};

/* The largest side of an image (reference, gbview --resolution WxH). */
#define GB_CLI_MAX_IMAGE_SIDE 16384

/* A strict decimal integer (digits, one optional leading '-') in low..high. */
int gb_cli_integer(const char *tool, const char *option, const char *text, long low,
                   long high, long *value);
/* The same into an int (low and high within int's range). */
int gb_cli_int(const char *tool, const char *option, const char *text, int low, int high,
               int *value);
/* The same for unsigned 64-bit values (seeds, photon counts); no sign. */
int gb_cli_unsigned(const char *tool, const char *option, const char *text, uint64_t low,
                    uint64_t high, uint64_t *value);
/* gb_cli_unsigned into an unsigned (high within unsigned's range). */
int gb_cli_uint(const char *tool, const char *option, const char *text, unsigned low,
                unsigned high, unsigned *value);
/* A finite decimal number in [low, high]. */
int gb_cli_number(const char *tool, const char *option, const char *text, double low,
                  double high, double *value);
int gb_cli_float(const char *tool, const char *option, const char *text, double low,
                 double high, float *value);
/* gb_cli_number for a library option where 0 means "the default" and a
 * negative value means 0: a 0 given on the command line is stored as -1,
 * so that it stays a 0. */
int gb_cli_number_keep_zero(const char *tool, const char *option, const char *text,
                            double low, double high, double *value);
/* WxH, each side a strict decimal integer in 1..max_side. */
int gb_cli_size(const char *tool, const char *option, const char *text, int max_side,
                int *width, int *height);
/* I/N, strict decimal integers with 0 <= I < N <= UINT32_MAX. */
int gb_cli_fraction(const char *tool, const char *option, const char *text, uint32_t *index,
                    uint32_t *count);
/* One of names[0..count-1]; *index is its place. */
int gb_cli_choice(const char *tool, const char *option, const char *text,
                  const char *const *names, int count, int *index);

/* Prints "TOOL: WHAT" (WHAT a printf format) and the Try line; returns
 * GB_EXIT_USAGE. */
int gb_cli_usage_error(const char *tool, const char *format, ...)
    __attribute__((format(printf, 2, 3)));
/* getopt_long returned '?' (opterr = 0): reports the option it refused,
 * from optopt, optind and argv, as "unknown option '--foo'" (or '-x'),
 * "option '--output' needs a value", "option '--quiet' takes no value" or
 * "option '--s' is ambiguous", then the Try line; returns GB_EXIT_USAGE.
 * options is the table given to getopt_long. */
int gb_cli_option_error(const char *tool, char **argv, const struct option *options);

/* The help on stdout; GB_EXIT_SUCCESS, or GB_EXIT_FAILURE if it could not
 * be written. */
int gb_cli_help(const char *text);
/* "TOOL (gibake) VERSION" on stdout; as gb_cli_help. */
int gb_cli_version(const char *tool);

/* The entries of an option table (git's OPT_* habit): NAME is the long
 * option without its dashes, CODE what gb_cli_options hands to the tool's
 * option function: a letter, which is then also the short option (-o), or
 * a value past 255 for a long option alone.
 *     static const struct option long_options[] = {
 *         GB_CLI_VALUE("output", 'o'),        --output FILE, -o FILE
 *         GB_CLI_FLAG("stats", OPTION_STATS), --stats
 *         GB_CLI_OPTIONS_END,
 *     };
 * GB_CLI_OPTIONS_END holds the entries every tool ends with: -q --quiet
 * (each tool's option function says what quiet means), -h --help and
 * -V --version (gb_cli_options answers those), then the terminator. */
#define GB_CLI_VALUE(name, code) {(name), required_argument, NULL, (code)}
#define GB_CLI_FLAG(name, code) {(name), no_argument, NULL, (code)}
#define GB_CLI_OPTIONS_END                                                                  \
    GB_CLI_FLAG("quiet", 'q'), GB_CLI_FLAG("help", 'h'), GB_CLI_FLAG("version", 'V'),      \
        {NULL, 0, NULL, 0}

/* One option of a tool, its value (optarg) or NULL: stores it in the
 * tool's arguments and returns GB_EXIT_SUCCESS, or an exit status. */
typedef int (*gb_cli_option_function)(int option, const char *value, void *arguments);

/* Every tool's option loop: getopt_long over argv with options (ending
 * with GB_CLI_OPTIONS_END); -h prints usage, -V the version, a refused
 * option is gb_cli_option_error; every other option goes to handle.
 * Returns GB_CLI_GO_ON when all were read (optind at the first operand),
 * else the exit status to return. */
int gb_cli_options(const char *tool, const char *usage, int argc, char **argv,
                   const struct option *options, gb_cli_option_function handle,
                   void *arguments);

/* The work failed: prints "TOOL: MESSAGE" (error's) on stderr; returns
 * GB_EXIT_FAILURE. */
int gb_cli_failure(const char *tool, const gb_error *error);

/* After the options, the operands (count of them, from operands[0]) into
 * the arguments, and whatever the options must agree on: GB_CLI_GO_ON, or
 * the status of a usage error. */
typedef int (*gb_cli_operands_function)(int count, char **operands, void *arguments);
/* The work on the parsed arguments, from checking that the outputs can be
 * written to writing them; fills error when it fails. */
typedef gb_result (*gb_cli_run_function)(void *arguments, gb_error *error);

/* A tool's command line: what gb_cli_main reads argv with. */
typedef struct gb_cli_command {
    const char *tool;                   /* "cluster": every message starts with it */
    const char *usage;                  /* the --help text */
    const struct option *options;       /* ends with GB_CLI_OPTIONS_END */
    gb_cli_option_function option;      /* each option into the arguments */
    gb_cli_operands_function operands;  /* then the operands */
} gb_cli_command;

/* Every tool's main(): gb_cli_options, then the operands, then run, each
 * step only if the one before said GB_CLI_GO_ON. Returns the first other
 * status (GB_EXIT_SUCCESS after --help or --version, GB_EXIT_USAGE after a
 * usage error), gb_cli_failure when run fails, else GB_EXIT_SUCCESS once
 * stdout is flushed (GB_EXIT_FAILURE if it cannot be). arguments, the
 * tool's own, goes to each function of command and to run. */
int gb_cli_main(const gb_cli_command *command, int argc, char **argv, gb_cli_run_function run,
                void *arguments);

#endif
