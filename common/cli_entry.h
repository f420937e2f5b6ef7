/* cli_entry.h — one option of a tool's command line as its table lists
 * it (cli.h): its code, names, help, and whether it is one of the options
 * every tool shares (gb_cli_shared, cli.h), with the macros that make the
 * entries. What cli.c parses and cli_help.c prints from; every string is
 * static. */
#ifndef GB_CLI_ENTRY_H
#define GB_CLI_ENTRY_H

#include <stddef.h>

typedef enum gb_cli_shared_kind {
    GB_CLI_OWN = 0,         /* the tool's option: goes to its option function */
    GB_CLI_SHARED_DEPFILE,
    GB_CLI_SHARED_THREADS,
    GB_CLI_SHARED_STATS,
    GB_CLI_SHARED_QUIET,
    GB_CLI_SHARED_SEED,
} gb_cli_shared_kind;

/* The codes of the shared long options, past every tool's own. */
enum { GB_CLI_SHARED_CODE = 0x10000, GB_CLI_CODE_DEPFILE, GB_CLI_CODE_SEED };

typedef struct gb_cli_entry {
    int code;                   /* a letter (also -x), or a value past 255 */
    const char *name;           /* the long option without its dashes */
    const char *value;          /* the value's name in the help ("FILE"); NULL: a flag */
    const char *help;           /* its help; NULL: the shared option's usual one */
    gb_cli_shared_kind shared;  /* GB_CLI_OWN, or which shared option */
    int high;                   /* --threads: the most */
} gb_cli_entry;

#define GB_CLI_OPTION(code, name, value, help) {(code), (name), (value), (help), GB_CLI_OWN, 0}
/* --depfile FILE; usual help "a make rule: the output and every file read (-MD)" */
#define GB_CLI_DEPFILE(help)                                                                \
    {GB_CLI_CODE_DEPFILE, "depfile", "FILE", (help), GB_CLI_SHARED_DEPFILE, 0}
/* -j, --threads N, 1..high; usual help "threads (default: every core)" */
#define GB_CLI_THREADS(high, help) {'j', "threads", "N", (help), GB_CLI_SHARED_THREADS, (high)}
/* -s, --stats */
#define GB_CLI_STATS(help) {'s', "stats", NULL, (help), GB_CLI_SHARED_STATS, 0}
/* -q, --quiet */
#define GB_CLI_QUIET(help) {'q', "quiet", NULL, (help), GB_CLI_SHARED_QUIET, 0}
/* --seed VALUE (the value's name in the help); usual help "random seed (default 0)" */
#define GB_CLI_SEED(value, help) {GB_CLI_CODE_SEED, "seed", (value), (help), GB_CLI_SHARED_SEED, 0}
#define GB_CLI_ENTRIES_END {0, NULL, NULL, NULL, GB_CLI_OWN, 0}

/* The most entries a command's table holds, GB_CLI_ENTRIES_END aside. */
enum { GB_CLI_MAX_ENTRIES = 64 };

#endif
