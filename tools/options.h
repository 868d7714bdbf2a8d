/* options.h — one command-line convention for every pm program. A tool
 * describes its options once, in a table; the table drives parsing
 * (getopt_long), the -h text, and what the recorded command line (cmdline)
 * leaves out. -h/--help and --version are added to every table here, so
 * no tool writes them. */
#ifndef PM_OPTIONS_H
#define PM_OPTIONS_H

#include <getopt.h>   /* optarg, optind */

/* One option. Short-only options do not exist: every key below 256 is also
 * spelled --name. Long-only options use a key of OPT_LONG or more. */
typedef struct opt {
	int key;            /* the short letter, or OPT_LONG + n */
	const char *name;   /* the long form, without "--" */
	const char *arg;    /* the value's name in -h, NULL if it takes none */
	const char *help;   /* -h text, wrapped to 80 columns */
	const char *def;    /* the default as -h shows it, NULL for none */
	int inert;          /* 1: does not change what the program writes (-q,
	                     * -j), so every spelling of it is left out of the
	                     * recorded command and outputs stay byte-identical */
} opt;

enum { OPT_LONG = 256 };

typedef struct tool {
	const char *usage;  /* the usage line, word for word the man page's SYNOPSIS */
	const char *about;  /* what the program does, printed after the usage line */
	const opt *opts;    /* ended by an entry whose name is NULL */
	const char *notes;  /* printed after the options, or NULL */
} tool;

/* Sets the program up (util_init) and records its command line, leaving
 * out the table's inert options. Call once, first. */
void opt_init(const tool *t, int argc, char **argv);

/* The next option's key, or -1 when none are left (optind is then the
 * first operand). Handles -h (help on stdout, exit 0), --version
 * ("pm-NAME VERSION", exit 0), and refuses unknown options and missing
 * values with the shared usage error (exit 2). The value is in optarg. */
int opt_next(const tool *t, int argc, char **argv);

/* The command line as opt_init recorded it, shell-quoted where needed, for
 * file histories; static storage. */
const char *cmdline(void);

#endif
