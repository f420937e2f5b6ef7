/* test_cli.c — what common/cli.h gives every tool's main(): the option
 * table's entries (GB_CLI_OPTION, a flag, -q from GB_CLI_QUIET, the short
 * options taken from the table), gb_cli_main's steps and exit statuses, the
 * failure line of gb_cli_failure, gb_cli_uint and gb_cli_number_keep_zero;
 * the shared options (gb_cli_shared) and the help made from entries;
 * and gb_progress_begin_for (common/progress.h). Each call runs with stdout
 * and stderr in files, so that the messages are checked word for word. */
#include "cli.h"
#include "progress.h"
#include "tap.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

/* ---- stdout and stderr of one call ---- */

typedef struct captured {
    char out[4096], err[4096];
} captured;

static int saved_out, saved_err;
static FILE *out_file, *err_file;

static void capture_begin(void)
{
    fflush(stdout);
    fflush(stderr);
    out_file = tmpfile();
    err_file = tmpfile();
    saved_out = dup(STDOUT_FILENO);
    saved_err = dup(STDERR_FILENO);
    dup2(fileno(out_file), STDOUT_FILENO);
    dup2(fileno(err_file), STDERR_FILENO);
}

static void read_back(FILE *file, char *text, size_t size)
{
    rewind(file);
    size_t length = fread(text, 1, size - 1, file);
    text[length] = '\0';
    fclose(file);
}

static void capture_end(captured *c)
{
    fflush(stdout);
    fflush(stderr);
    dup2(saved_out, STDOUT_FILENO);
    dup2(saved_err, STDERR_FILENO);
    close(saved_out);
    close(saved_err);
    read_back(out_file, c->out, sizeof c->out);
    read_back(err_file, c->err, sizeof c->err);
}

/* ---- a small tool: -o FILE, --stats, --seed N (long only), one operand ---- */

enum { OPTION_SEED = 256 };

typedef struct arguments {
    gb_cli_shared shared;   /* first: stats and quiet */
    const char *output, *operand;
    int operand_count;
    uint64_t seed;
    int ran;                /* run was called */
    int fail;               /* run fails */
} arguments;

static const gb_cli_entry demo_entries[] = {
    GB_CLI_OPTION('o', "output", "FILE", "the output"),
    GB_CLI_STATS(NULL),
    GB_CLI_OPTION(OPTION_SEED, "seed", "N", "a seed, 0..9"),
    GB_CLI_QUIET(NULL),
    GB_CLI_ENTRIES_END,
};

static const char usage[] = "usage: demo [options] IN -o OUT\n";
static const char demo_help[] =
    "usage: demo [options] IN -o OUT\n"
    "  -o, --output FILE   the output\n"
    "  -s, --stats         print what the run measured on stdout\n"
    "      --seed N        a seed, 0..9\n"
    "  -q, --quiet         no progress bar, no warnings\n"
    "  -h, --help          this help\n"
    "  -V, --version       the version\n"
    "(the end)\n";

static int parse_option(int option, const char *value, void *context)
{
    arguments *a = context;
    switch (option) {
    case 'o': a->output = value; return GB_EXIT_SUCCESS;
    case OPTION_SEED: return gb_cli_unsigned("demo", "seed", value, 0, 9, &a->seed);
    default: abort();
    }
}

static int check_operands(int count, char **operands, void *context)
{
    arguments *a = context;
    a->operand_count = count;
    if (count != 1 || !a->output)
        return gb_cli_usage_error("demo", "expected one IN and -o OUT");
    a->operand = operands[0];
    return GB_CLI_GO_ON;
}

static gb_result run(void *context, gb_error *error)
{
    arguments *a = context;
    a->ran = 1;
    if (a->fail)
        return gb_fail(error, GB_ERROR_IO, "%s: cannot write", a->output);
    printf("wrote %s\n", a->output);
    return GB_OK;
}

static const gb_cli_command command = {.tool = "demo", .usage = usage,
                                       .option = parse_option, .operands = check_operands,
                                       .entries = demo_entries, .column = 22,
                                       .tail = "(the end)\n"};

/* gb_cli_main on the words of line (at most 15, split at spaces), with a
 * fresh getopt; the words stay until the next call (a points into them). */
static int run_main(const char *line, arguments *a, captured *c)
{
    static char words[256];
    static char *argv[16];
    int argc = 0;
    snprintf(words, sizeof words, "demo %s", line);
    for (char *word = strtok(words, " "); word && argc < 15; word = strtok(NULL, " "))
        argv[argc++] = word;
    argv[argc] = NULL;
    optind = 0;
    capture_begin();
    int status = gb_cli_main(&command, argc, argv, run, a);
    capture_end(c);
    return status;
}

static void test_main_runs(void)
{
    arguments a = {0};
    captured c;
    int status = run_main("in -s --seed 7 -o out.txt -q", &a, &c);
    CHECK_EQ_INT(status, GB_EXIT_SUCCESS, "a good command line runs and exits 0");
    CHECK(a.ran && a.shared.stats && a.shared.quiet && a.seed == 7,
          "every option reached the tool");
    CHECK(a.output && strcmp(a.output, "out.txt") == 0, "-o FILE: the short option of "
                                                        "GB_CLI_OPTION('o', \"output\" ...)");
    CHECK(a.operand_count == 1 && strcmp(a.operand, "in") == 0,
          "the operand, given before the options, is the only one handed on");
    CHECK(strcmp(c.out, "wrote out.txt\n") == 0 && c.err[0] == '\0',
          "run's output on stdout, nothing on stderr");

    a = (arguments){0};
    status = run_main("--output=x --stats --quiet in", &a, &c);
    CHECK(status == GB_EXIT_SUCCESS && a.shared.stats && a.shared.quiet &&
              strcmp(a.output, "x") == 0,
          "the long options: --output=x, --stats, and --quiet from GB_CLI_QUIET");
}

static void test_main_help_and_version(void)
{
    arguments a = {0};
    captured c;
    CHECK_EQ_INT(run_main("--help in", &a, &c), GB_EXIT_SUCCESS, "--help exits 0");
    CHECK(strcmp(c.out, demo_help) == 0 && c.err[0] == '\0' && !a.ran,
          "--help prints the usage, the entries at column 22, -h, -V and the tail on "
          "stdout, and runs nothing");
    CHECK_EQ_INT(run_main("-h", &a, &c), GB_EXIT_SUCCESS, "-h exits 0");
    CHECK(strcmp(c.out, demo_help) == 0, "-h is --help");
    CHECK_EQ_INT(run_main("-V", &a, &c), GB_EXIT_SUCCESS, "-V exits 0");
    CHECK(strcmp(c.out, "demo (gibake) 0.1\n") == 0 && !a.ran,
          "-V prints 'demo (gibake) 0.1' and runs nothing");
    CHECK_EQ_INT(run_main("--version", &a, &c), GB_EXIT_SUCCESS, "--version exits 0");
}

static void test_main_usage_errors(void)
{
    arguments a = {0};
    captured c;
    CHECK_EQ_INT(run_main("-x in -o out", &a, &c), GB_EXIT_USAGE, "an unknown option exits 2");
    CHECK(strcmp(c.err, "demo: unknown option '-x'\n"
                        "Try 'demo --help' for more information.\n") == 0 &&
              c.out[0] == '\0' && !a.ran,
          "an unknown option: its line and the Try line on stderr, nothing run");

    CHECK_EQ_INT(run_main("in -o", &a, &c), GB_EXIT_USAGE, "-o without its value exits 2");
    CHECK(strncmp(c.err, "demo: option '-o' needs a value\n", 32) == 0,
          "the short option takes a value because its long one does");

    CHECK_EQ_INT(run_main("--stats=1 in -o out", &a, &c), GB_EXIT_USAGE,
                 "a value given to a flag exits 2");
    CHECK(strncmp(c.err, "demo: option '--stats' takes no value\n", 38) == 0,
          "a flag takes no value");

    a = (arguments){0};
    CHECK_EQ_INT(run_main("--seed 10 in -o out", &a, &c), GB_EXIT_USAGE,
                 "a bad value exits 2");
    CHECK(a.operand_count == 0 && !a.ran, "after a bad value, no operand check and no run");

    a = (arguments){0};
    CHECK_EQ_INT(run_main("-o out", &a, &c), GB_EXIT_USAGE, "a missing operand exits 2");
    CHECK(strcmp(c.err, "demo: expected one IN and -o OUT\n"
                        "Try 'demo --help' for more information.\n") == 0 &&
              !a.ran,
          "the operands' usage error is the tool's own line, and nothing runs");
}

static void test_main_failure(void)
{
    arguments a = {.fail = 1};
    captured c;
    CHECK_EQ_INT(run_main("in -o out", &a, &c), GB_EXIT_FAILURE, "a failed run exits 1");
    CHECK(strcmp(c.err, "demo: out: cannot write\n") == 0 && c.out[0] == '\0',
          "a failed run is one line: 'demo: ' and the error's message");

    gb_error error;
    gb_fail(&error, GB_ERROR_PARSE, "x.scene:3: bad line");
    capture_begin();
    int status = gb_cli_failure("tool", &error);
    capture_end(&c);
    CHECK(status == GB_EXIT_FAILURE && strcmp(c.err, "tool: x.scene:3: bad line\n") == 0 &&
              c.out[0] == '\0',
          "gb_cli_failure: 'TOOL: MESSAGE' on stderr, GB_EXIT_FAILURE");
}

/* gb_cli_uint("demo", "depth", text, low, high, value), its messages in c. */
static int uint_of(const char *text, unsigned low, unsigned high, unsigned *value, captured *c)
{
    capture_begin();
    int status = gb_cli_uint("demo", "depth", text, low, high, value);
    capture_end(c);
    return status;
}

static void test_uint(void)
{
    unsigned value = 5;
    captured c;
    CHECK(uint_of("10", 1, 10, &value, &c) == GB_EXIT_SUCCESS && value == 10 &&
              c.err[0] == '\0',
          "gb_cli_uint: a value in range is stored");
    CHECK(uint_of("11", 1, 10, &value, &c) == GB_EXIT_USAGE && value == 10,
          "gb_cli_uint: out of range, exit 2, the value untouched");
    CHECK(strcmp(c.err, "demo: --depth: '11' is not an integer in 1..10\n"
                        "Try 'demo --help' for more information.\n") == 0,
          "gb_cli_uint: the range message of every integer");
    CHECK(uint_of("4294967296", 1, UINT32_MAX, &value, &c) == GB_EXIT_USAGE &&
              uint_of("-1", 0, UINT32_MAX, &value, &c) == GB_EXIT_USAGE && value == 10,
          "gb_cli_uint: past UINT32_MAX or with a sign, refused");
    CHECK(uint_of("4294967295", 1, UINT32_MAX, &value, &c) == GB_EXIT_SUCCESS &&
              value == UINT32_MAX,
          "gb_cli_uint: UINT32_MAX fits");
}

/* gb_cli_number_keep_zero("demo", "alpha", text, 0, 100, value), its
 * messages in c. */
static int alpha_of(const char *text, double *value, captured *c)
{
    capture_begin();
    int status = gb_cli_number_keep_zero("demo", "alpha", text, 0.0, 100.0, value);
    capture_end(c);
    return status;
}

static void test_number_keep_zero(void)
{
    double value = 3.0;
    captured c;
    CHECK(alpha_of("0", &value, &c) == GB_EXIT_SUCCESS && value == -1.0,
          "gb_cli_number_keep_zero: 0 is stored as -1 (a library's 'zero', not 'default')");
    CHECK(alpha_of("12.5", &value, &c) == GB_EXIT_SUCCESS && value == 12.5,
          "gb_cli_number_keep_zero: other values as given");
    CHECK(alpha_of("101", &value, &c) == GB_EXIT_USAGE && value == 12.5 &&
              strcmp(c.err, "demo: --alpha: '101' is not a number in [0, 100]\n"
                            "Try 'demo --help' for more information.\n") == 0,
          "gb_cli_number_keep_zero: out of range, exit 2 with gb_cli_number's message");
}

static void test_progress_begin_for(void)
{
    gb_progress progress;
    gb_progress_callback callback = NULL;
    void *user = NULL;
    gb_progress_begin_for(&progress, "demo", 1, &callback, &user);
    CHECK(callback == gb_progress_report && user == &progress && !progress.enabled,
          "gb_progress_begin_for: the slots point at the bar, quiet leaves it off");
    gb_progress_end(&progress);
}

/* ---- a tool of entries: the shared options parsed by cli, the help made ---- */

typedef struct shared_arguments {
    gb_cli_shared shared;
    const char *output;
} shared_arguments;

static int shared_option(int option, const char *value, void *context)
{
    shared_arguments *a = context;
    if (option != 'o')
        abort();
    a->output = value;
    return GB_EXIT_SUCCESS;
}

static int shared_operands(int count, char **operands, void *context)
{
    (void)operands, (void)context;
    return count == 0 ? GB_CLI_GO_ON : gb_cli_usage_error("demo", "no operand");
}

static const gb_cli_entry shared_entries[] = {
    GB_CLI_OPTION('o', "output", "FILE", "the file\nto write"),
    GB_CLI_SEED("N", NULL),
    GB_CLI_THREADS(8, NULL),
    GB_CLI_STATS("print counts"),
    GB_CLI_DEPFILE(NULL),
    GB_CLI_QUIET(NULL),
    GB_CLI_ENTRIES_END,
};

static const gb_cli_command shared_command = {.tool = "demo", .usage = "usage: demo\n\n",
                                              .option = shared_option,
                                              .operands = shared_operands,
                                              .entries = shared_entries, .column = 20};

/* gb_cli_parse of shared_command on argv (NULL-ended). */
static int parse_shared(char **argv, shared_arguments *a, captured *c)
{
    int argc = 0;
    while (argv[argc])
        ++argc;
    optind = 0;
    capture_begin();
    int status = gb_cli_parse(&shared_command, argc, argv, a);
    capture_end(c);
    return status;
}

static void test_shared_options(void)
{
    shared_arguments a = {0};
    captured c;
    char *good[] = {"demo", "-o", "x", "--seed", "7", "-j", "8", "-s", "--depfile", "d", "-q",
                    NULL};
    CHECK_EQ_INT(parse_shared(good, &a, &c), GB_CLI_GO_ON, "the shared options parse");
    CHECK(a.shared.seed == 7 && a.shared.threads == 8 && a.shared.stats && a.shared.quiet &&
              a.shared.depfile && strcmp(a.shared.depfile, "d") == 0 && a.output,
          "each shared option lands in gb_cli_shared, the tool's own in its arguments");
    char *bad[] = {"demo", "-j", "9", NULL};
    CHECK_EQ_INT(parse_shared(bad, &(shared_arguments){0}, &c), GB_EXIT_USAGE,
                 "--threads above the entry's most: a usage error");
    CHECK(strcmp(c.err, "demo: --threads: '9' is not an integer in 1..8\n"
                        "Try 'demo --help' for more information.\n") == 0,
          "... with gb_cli_int's message");
    char *help[] = {"demo", "--help", NULL};
    CHECK_EQ_INT(parse_shared(help, &(shared_arguments){0}, &c), GB_EXIT_SUCCESS, "--help: 0");
    const char *want = "usage: demo\n\n"
                       "  -o, --output FILE  the file\n"
                       "                    to write\n"
                       "      --seed N      random seed (default 0)\n"
                       "  -j, --threads N   threads (default: every core)\n"
                       "  -s, --stats       print counts\n"
                       "      --depfile FILE  a make rule: the output and every file read (-MD)\n"
                       "  -q, --quiet       no progress bar, no warnings\n"
                       "  -h, --help        this help\n"
                       "  -V, --version     the version\n";
    CHECK(strcmp(c.out, want) == 0, "the help: head, each entry at the column (two spaces "
                                    "at least), its next lines indented, then -h and -V");
}

int main(void)
{
    test_shared_options();
    test_main_runs();
    test_main_help_and_version();
    test_main_usage_errors();
    test_main_failure();
    test_uint();
    test_number_keep_zero();
    test_progress_begin_for();
    return tap_done();
}
