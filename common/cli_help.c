/* cli_help.c — the --help made from a command's entries (cli_help.h). */

#include "cli_help.h"

#include <stdio.h>
#include <string.h>

/* The usual help of a shared option the tool gave none for. */
static const char *usual_help(const gb_cli_entry *entry)
{
    switch (entry->shared) {
    case GB_CLI_SHARED_DEPFILE: return "a make rule: the output and every file read (-MD)";
    case GB_CLI_SHARED_THREADS: return "threads (default: every core)";
    case GB_CLI_SHARED_SEED: return "random seed (default 0)";
    case GB_CLI_SHARED_STATS: return "print what the run measured on stdout";
    case GB_CLI_SHARED_QUIET: return "no progress bar, no warnings";
    case GB_CLI_OWN: break;
    }
    return "";
}

/* "  -x, --name VALUE" or "      --name VALUE", then the help from the
 * column (two spaces after the name at least), its further lines indented
 * to the column. Nonzero when written. */
static int print_entry(const gb_cli_entry *entry, int column)
{
    char letter[8] = "    ", name[128];
    if (entry->code > 0 && entry->code < 128)
        snprintf(letter, sizeof letter, "-%c, ", entry->code);
    int width = snprintf(name, sizeof name, "  %s--%s%s%s", letter, entry->name,
                         entry->value ? " " : "", entry->value ? entry->value : "");
    const char *line = entry->help ? entry->help : usual_help(entry);
    int pad = width + 2 > column ? 2 : column - width;
    for (const char *lead = name;; lead = "", pad = column) {
        size_t length = strcspn(line, "\n");
        if (printf("%s%*s%.*s\n", lead, pad, "", (int)length, line) < 0)
            return 0;
        if (!line[length])
            return 1;
        line += length + 1;
    }
}

int gb_cli_help_entries(const char *head, const gb_cli_entry *entries, int column,
                        const char *tail)
{
    static const gb_cli_entry last[] = {
        GB_CLI_OPTION('h', "help", NULL, "this help"),
        GB_CLI_OPTION('V', "version", NULL, "the version"),
        GB_CLI_ENTRIES_END,
    };
    if (fputs(head, stdout) == EOF)
        return 0;
    for (const gb_cli_entry *e = entries; e->name; ++e)
        if (!print_entry(e, column))
            return 0;
    for (const gb_cli_entry *e = last; e->name; ++e)
        if (!print_entry(e, column))
            return 0;
    return !tail || fputs(tail, stdout) != EOF;
}
