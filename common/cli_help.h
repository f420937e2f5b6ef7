/* cli_help.h — the --help of a command that lists its options as
 * gb_cli_entry (cli_entry.h): the usage head, one line per entry, then -h and
 * -V, every entry's help starting at one column. Only cli.c calls it; the
 * caller owns every string. */
#ifndef GB_CLI_HELP_H
#define GB_CLI_HELP_H

#include "cli_entry.h"

/* head, then each entry of entries (up to GB_CLI_ENTRIES_END), then
 * "-h, --help" and "-V, --version", then tail (NULL: none), on stdout;
 * nonzero when written, 0 when it could not be. */
int gb_cli_help_entries(const char *head, const gb_cli_entry *entries, int column,
                        const char *tail);

#endif
