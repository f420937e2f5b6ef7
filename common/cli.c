/* cli.c — option values and usage errors of every tool (cli.h). */

#include "cli.h"
#include "cli_help.h"

#include <ctype.h>
#include <errno.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static const char version[] = "0.1";

/* The last line of every usage error; returns GB_EXIT_USAGE. */
static int print_try_line(const char *tool)
{
    fprintf(stderr, "Try '%s --help' for more information.\n", tool);
    return GB_EXIT_USAGE;
}

/* Digits only, at least one, at most max_digits, within text[0..length). */
static int is_digits(const char *text, size_t length, size_t max_digits)
{
    if (length == 0 || length > max_digits)
        return 0;
    for (size_t i = 0; i < length; ++i)
        if (text[i] < '0' || text[i] > '9')
            return 0;
    return 1;
}

/* A side of WxH or a part of I/N: digits up to the stop character. */
static int parse_part(const char *text, size_t length, uint64_t high, uint64_t *value)
{
    if (!is_digits(text, length, 19))
        return 0;
    errno = 0;
    unsigned long long parsed = strtoull(text, NULL, 10);
    if (errno || parsed > high)
        return 0;
    *value = parsed;
    return 1;
}

/* A '-' at most, then digits. */
static int parse_signed(const char *text, long *value)
{
    const char *digits = text[0] == '-' ? text + 1 : text;
    if (!is_digits(digits, strlen(digits), 19))
        return 0;
    errno = 0;
    long parsed = strtol(text, NULL, 10);
    if (errno)
        return 0;
    *value = parsed;
    return 1;
}

int gb_cli_integer(const char *tool, const char *option, const char *text, long low,
                   long high, long *value)
{
    long parsed;
    if (!parse_signed(text, &parsed) || parsed < low || parsed > high) {
        fprintf(stderr, "%s: --%s: '%s' is not an integer in %ld..%ld\n", tool, option, text,
                low, high);
        return print_try_line(tool);
    }
    *value = parsed;
    return GB_EXIT_SUCCESS;
}

int gb_cli_int(const char *tool, const char *option, const char *text, int low, int high,
               int *value)
{
    long parsed;
    int status = gb_cli_integer(tool, option, text, low, high, &parsed);
    if (status == GB_EXIT_SUCCESS)
        *value = (int)parsed;
    return status;
}

int gb_cli_unsigned(const char *tool, const char *option, const char *text, uint64_t low,
                    uint64_t high, uint64_t *value)
{
    uint64_t parsed;
    if (!parse_part(text, strlen(text), high, &parsed) || parsed < low) {
        fprintf(stderr, "%s: --%s: '%s' is not an integer in %llu..%llu\n", tool, option, text,
                (unsigned long long)low, (unsigned long long)high);
        return print_try_line(tool);
    }
    *value = parsed;
    return GB_EXIT_SUCCESS;
}

int gb_cli_uint(const char *tool, const char *option, const char *text, unsigned low,
                unsigned high, unsigned *value)
{
    uint64_t parsed = *value;   /* kept on a usage error */
    int status = gb_cli_unsigned(tool, option, text, low, high, &parsed);
    *value = (unsigned)parsed;
    return status;
}

/* strtod's numbers, but no leading space, no inf, no nan: a sign, a digit
 * or a point first. */
static int parse_finite(const char *text, double *value)
{
    const char *first = text[0] == '-' || text[0] == '+' ? text + 1 : text;
    if (!((*first >= '0' && *first <= '9') || *first == '.'))
        return 0;
    char *end;
    errno = 0;
    double parsed = strtod(text, &end);
    if (errno || end == text || *end || !isfinite(parsed))
        return 0;
    *value = parsed;
    return 1;
}

int gb_cli_number(const char *tool, const char *option, const char *text, double low,
                  double high, double *value)
{
    double parsed;
    if (!parse_finite(text, &parsed) || !(parsed >= low && parsed <= high)) {
        fprintf(stderr, "%s: --%s: '%s' is not a number in [%g, %g]\n", tool, option, text, low,
                high);
        return print_try_line(tool);
    }
    *value = parsed;
    return GB_EXIT_SUCCESS;
}

int gb_cli_float(const char *tool, const char *option, const char *text, double low,
                 double high, float *value)
{
    double parsed;
    int status = gb_cli_number(tool, option, text, low, high, &parsed);
    if (status == GB_EXIT_SUCCESS)
        *value = (float)parsed;
    return status;
}

int gb_cli_number_keep_zero(const char *tool, const char *option, const char *text,
                            double low, double high, double *value)
{
    int status = gb_cli_number(tool, option, text, low, high, value);
    if (status == GB_EXIT_SUCCESS && *value == 0.0)
        *value = -1.0;
    return status;
}

int gb_cli_size(const char *tool, const char *option, const char *text, int max_side,
                int *width, int *height)
{
    const char *x = strchr(text, 'x');
    uint64_t w, h;
    if (!x || !parse_part(text, (size_t)(x - text), (uint64_t)max_side, &w) ||
        !parse_part(x + 1, strlen(x + 1), (uint64_t)max_side, &h) || w < 1 || h < 1) {
        fprintf(stderr, "%s: --%s: '%s' is not WxH with each side in 1..%d\n", tool, option,
                text, max_side);
        return print_try_line(tool);
    }
    *width = (int)w;
    *height = (int)h;
    return GB_EXIT_SUCCESS;
}

int gb_cli_fraction(const char *tool, const char *option, const char *text, uint32_t *index,
                    uint32_t *count)
{
    const char *slash = strchr(text, '/');
    uint64_t i, n;
    if (!slash || !parse_part(text, (size_t)(slash - text), UINT32_MAX, &i) ||
        !parse_part(slash + 1, strlen(slash + 1), UINT32_MAX, &n) || i >= n) {
        fprintf(stderr, "%s: --%s: '%s' is not I/N with I in 0..N-1\n", tool, option, text);
        return print_try_line(tool);
    }
    *index = (uint32_t)i;
    *count = (uint32_t)n;
    return GB_EXIT_SUCCESS;
}

int gb_cli_choice(const char *tool, const char *option, const char *text,
                  const char *const *names, int count, int *index)
{
    for (int i = 0; i < count; ++i)
        if (strcmp(text, names[i]) == 0) {
            *index = i;
            return GB_EXIT_SUCCESS;
        }
    fprintf(stderr, "%s: --%s: '%s' is not one of ", tool, option, text);
    for (int i = 0; i < count; ++i)
        fprintf(stderr, "%s%s", names[i], i + 1 < count ? ", " : "\n");
    return print_try_line(tool);
}

int gb_cli_usage_error(const char *tool, const char *format, ...)
{
    va_list arguments;
    va_start(arguments, format);
    fprintf(stderr, "%s: ", tool);
    vfprintf(stderr, format, arguments);
    fputc('\n', stderr);
    va_end(arguments);
    return print_try_line(tool);
}

/* The long option NAME[0..length) names: the exact one, else the only one
 * it abbreviates; *matches counts the candidates. */
static const struct option *find_long_option(const struct option *options, const char *name,
                                             size_t length, int *matches)
{
    const struct option *found = NULL;
    *matches = 0;
    for (const struct option *o = options; o->name; ++o) {
        if (strncmp(o->name, name, length) != 0)
            continue;
        if (strlen(o->name) == length) {
            *matches = 1;
            return o;
        }
        found = o;
        ++*matches;
    }
    return *matches == 1 ? found : NULL;
}

static const struct option *find_short_option(const struct option *options, int letter)
{
    for (const struct option *o = options; o->name; ++o)
        if (o->val == letter)
            return o;
    return NULL;
}

/* A long option's error: optind is past its word, optopt is 0 (unknown,
 * ambiguous) or its value (a value missing or given to a flag). Returns 0
 * when the error was not about that word. */
static int report_long_option(const char *tool, const char *word,
                              const struct option *options)
{
    size_t length = strcspn(word + 2, "=");
    int matches;
    const struct option *o = find_long_option(options, word + 2, length, &matches);
    if (optopt != 0 && !(o && o->val == optopt))
        return 0;
    int shown = (int)(length + 2);
    if (optopt == 0 && matches > 1)
        gb_cli_usage_error(tool, "option '%.*s' is ambiguous", shown, word);
    else if (optopt == 0)
        gb_cli_usage_error(tool, "unknown option '%.*s'", shown, word);
    else if (o->has_arg == no_argument)
        gb_cli_usage_error(tool, "option '--%s' takes no value", o->name);
    else
        gb_cli_usage_error(tool, "option '--%s' needs a value", o->name);
    return 1;
}

int gb_cli_option_error(const char *tool, char **argv, const struct option *options)
{
    const char *word = optind > 0 ? argv[optind - 1] : NULL;
    if (word && strncmp(word, "--", 2) == 0 && word[2] &&
        report_long_option(tool, word, options))
        return GB_EXIT_USAGE;
    const struct option *o = find_short_option(options, optopt);
    if (o && o->has_arg == required_argument)
        return gb_cli_usage_error(tool, "option '-%c' needs a value", optopt);
    return gb_cli_usage_error(tool, "unknown option '-%c'", optopt);
}

int gb_cli_version(const char *tool)
{
    return printf("%s (gibake) %s\n", tool, version) < 0 ? GB_EXIT_FAILURE : GB_EXIT_SUCCESS;
}

/* getopt's short options of a table: every entry whose value is a letter,
 * followed by ':' when it takes a value; at most 52 letters of 2
 * characters ("o:"). */
static void short_options_of(const struct option *options, char text[128])
{
    size_t length = 0;
    for (const struct option *o = options; o->name && length + 3 <= 128; ++o) {
        if (o->val <= 0 || o->val > 127 || !isalpha(o->val))
            continue;
        text[length++] = (char)o->val;
        if (o->has_arg == required_argument)
            text[length++] = ':';
    }
    text[length] = '\0';
}

/* The getopt table of a command: its entries' (at most
 * GB_CLI_MAX_ENTRIES), then -h and -V. */

static const struct option *option_table(const gb_cli_command *command,
                                         struct option table[GB_CLI_MAX_ENTRIES + 3])
{
    size_t count = 0;
    for (const gb_cli_entry *e = command->entries; e->name; ++e) {
        if (count == GB_CLI_MAX_ENTRIES)
            abort();    /* a table this long is a bug of the tool */
        table[count++] = (struct option){e->name, e->value ? required_argument : no_argument,
                                         NULL, e->code};
    }
    table[count++] = (struct option){"help", no_argument, NULL, 'h'};
    table[count++] = (struct option){"version", no_argument, NULL, 'V'};
    table[count] = (struct option){NULL, 0, NULL, 0};
    return table;
}

static const gb_cli_entry *find_entry(const gb_cli_entry *entries, int code)
{
    for (const gb_cli_entry *e = entries; e && e->name; ++e)
        if (e->code == code)
            return e;
    return NULL;
}

/* A shared option into shared; GB_EXIT_SUCCESS, else the usage status. */
static int parse_shared(const char *tool, const gb_cli_entry *entry, const char *value,
                        gb_cli_shared *shared)
{
    switch (entry->shared) {
    case GB_CLI_SHARED_DEPFILE: shared->depfile = value; return GB_EXIT_SUCCESS;
    case GB_CLI_SHARED_STATS: shared->stats = 1; return GB_EXIT_SUCCESS;
    case GB_CLI_SHARED_QUIET: shared->quiet = 1; return GB_EXIT_SUCCESS;
    case GB_CLI_SHARED_THREADS:
        return gb_cli_int(tool, "threads", value, 1, entry->high, &shared->threads);
    case GB_CLI_SHARED_SEED:
        return gb_cli_unsigned(tool, "seed", value, 0, UINT64_MAX, &shared->seed);
    case GB_CLI_OWN: break;
    }
    abort();            /* not a shared option: find_entry's caller checked */
}

static int print_help(const gb_cli_command *command)
{
    return gb_cli_help_entries(command->usage, command->entries, command->column,
                               command->tail)
               ? GB_EXIT_SUCCESS
               : GB_EXIT_FAILURE;
}

/* Every tool's option loop: getopt_long over argv; -h prints the help, -V
 * the version, a refused option is gb_cli_option_error; a shared option
 * goes into the gb_cli_shared that starts arguments, every other to the
 * tool's option function. GB_CLI_GO_ON when all were read (optind at the
 * first operand), else the exit status. */
static int read_options(const gb_cli_command *command, int argc, char **argv,
                        void *arguments)
{
    struct option storage[GB_CLI_MAX_ENTRIES + 3];
    const struct option *table = option_table(command, storage);
    char short_options[128];
    short_options_of(table, short_options);
    int option, status;
    opterr = 0;
    while ((option = getopt_long(argc, argv, short_options, table, NULL)) != -1) {
        const gb_cli_entry *entry = find_entry(command->entries, option);
        if (option == 'h')
            return print_help(command);
        if (option == 'V')
            return gb_cli_version(command->tool);
        if (option == '?')
            return gb_cli_option_error(command->tool, argv, table);
        if (entry && entry->shared != GB_CLI_OWN)
            status = parse_shared(command->tool, entry, optarg, arguments);
        else
            status = command->option(option, optarg, arguments);
        if (status != GB_EXIT_SUCCESS)
            return status;
    }
    return GB_CLI_GO_ON;
}

int gb_cli_failure(const char *tool, const gb_error *error)
{
    fprintf(stderr, "%s: %s\n", tool, error->message);
    return GB_EXIT_FAILURE;
}

int gb_cli_parse(const gb_cli_command *command, int argc, char **argv, void *arguments)
{
    int status = read_options(command, argc, argv, arguments);
    if (status == GB_CLI_GO_ON)
        status = command->operands(argc - optind, argv + optind, arguments);
    return status;
}

int gb_cli_main(const gb_cli_command *command, int argc, char **argv, gb_cli_run_function run,
                void *arguments)
{
    int status = gb_cli_parse(command, argc, argv, arguments);
    if (status != GB_CLI_GO_ON)
        return status;
    gb_error error;
    if (run(arguments, &error) != GB_OK)
        return gb_cli_failure(command->tool, &error);
    return fflush(stdout) == 0 ? GB_EXIT_SUCCESS : GB_EXIT_FAILURE;
}
