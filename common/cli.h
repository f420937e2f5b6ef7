/* cli.h — the option values and usage errors every tool's main() shares,
 * so that every command reports a bad value the same way (git's
 * parse-options habit). gb_cli_main runs getopt_long, parses the shared
 * options itself (gb_cli_shared) and hands each other option to the tool,
 * which hands each value to one of these functions.
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
 * The help and the version go to stdout (gb_cli_main answers -h and -V); a
 * failure of the work is "TOOL: MESSAGE" on stderr (gb_cli_failure).
 * Nothing else here prints. The caller owns every string passed in; TOOL
 * is the bare name ("voxelize"), OPTION the long name without its dashes.
 *
 * A tool describes its command line in a gb_cli_command (its options as
 * gb_cli_entry, below), and its main() is one call, on arguments of its
 * own that start zeroed (and start with a gb_cli_shared):
 *     return gb_cli_main(&command, argc, argv, run, &(arguments){0});
 */
#ifndef GB_CLI_H
#define GB_CLI_H

#include <getopt.h>
#include <stdint.h>

#include "cli_entry.h"
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

/* "TOOL (gibake) VERSION" on stdout; GB_EXIT_SUCCESS, or GB_EXIT_FAILURE
 * if it could not be written. */
int gb_cli_version(const char *tool);

/* One option of a tool, its value (optarg) or NULL: stores it in the
 * tool's arguments and returns GB_EXIT_SUCCESS, or an exit status. A code
 * the tool has no case for is a bug of its table: it abort()s, never
 * reads the value as some other option. */
typedef int (*gb_cli_option_function)(int option, const char *value, void *arguments);

/* ---- the options every tool shares (git's parse-options habit) ----
 * A tool lists its options, with their help, in a table of gb_cli_entry;
 * the shared ones are entries of the macros below, placed where its help
 * shows them. gb_cli_main parses those itself into the gb_cli_shared that
 * starts the tool's arguments (its first member), with the same range and
 * message in every tool, and hands every other option to the tool. The
 * help is the usage head, then one line per entry in table order, then
 * -h and -V (which gb_cli_main answers):
 *     "  -j, --threads N" (or "      --seed N"), padded to the command's
 *     column (two spaces at least), then the help, whose next lines
 *     (after each '\n') start at the column.
 *     static const gb_cli_entry entries[] = {
 *         GB_CLI_OPTION('o', "output", "FILE", "the file to write"),
 *         GB_CLI_OPTION(OPTION_MERGE, "merge", NULL, "join the parts"),
 *         GB_CLI_THREADS(256, NULL),
 *         GB_CLI_STATS("print counts and seconds"),
 *         GB_CLI_DEPFILE(NULL),
 *         GB_CLI_QUIET("no progress bar, no warnings"),
 *         GB_CLI_ENTRIES_END,
 *     };
 * A NULL help is the shared option's usual line (cli_entry.h, where the
 * entries and their macros are). A tool's own codes are letters (also the
 * short option) or 256..GB_CLI_SHARED_CODE-1. */
typedef struct gb_cli_shared {
    const char *depfile;    /* --depfile FILE: a make rule of the output and
                               every file read; NULL when not given */
    int threads;            /* -j, --threads N, 1..the entry's most; 0 not given */
    int stats;              /* -s, --stats: print what the run measured */
    int quiet;              /* -q, --quiet: what it silences, the tool's help says */
    uint64_t seed;          /* --seed N, 0..UINT64_MAX; 0 when not given */
} gb_cli_shared;


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

/* A tool's command line: what gb_cli_main reads argv with, and the help
 * made from it. */
typedef struct gb_cli_command {
    const char *tool;                   /* "cluster": every message starts with it */
    const char *usage;                  /* the head of the --help, up to the first option */
    gb_cli_option_function option;      /* each option into the arguments */
    gb_cli_operands_function operands;  /* then the operands */
    const gb_cli_entry *entries;        /* ends with GB_CLI_ENTRIES_END */
    int column;                         /* where each entry's help starts */
    const char *tail;                   /* the help after -h and -V (gbview's window
                                           keys); NULL: none */
} gb_cli_command;

/* gb_cli_main's options and operands: GB_CLI_GO_ON when the tool can run,
 * else the exit status to return (for a tool whose end is its own). */
int gb_cli_parse(const gb_cli_command *command, int argc, char **argv, void *arguments);

/* Every tool's main(): gb_cli_parse, then run, each
 * step only if the one before said GB_CLI_GO_ON. Returns the first other
 * status (GB_EXIT_SUCCESS after --help or --version, GB_EXIT_USAGE after a
 * usage error), gb_cli_failure when run fails, else GB_EXIT_SUCCESS once
 * stdout is flushed (GB_EXIT_FAILURE if it cannot be). arguments, the
 * tool's own, goes to each function of command and to run. */
int gb_cli_main(const gb_cli_command *command, int argc, char **argv, gb_cli_run_function run,
                void *arguments);

#endif
