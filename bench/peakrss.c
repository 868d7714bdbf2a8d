/* peakrss.c — runs a command and then prints its peak resident set size
 * (getrusage of the child, in kilobytes) as "peak_rss_kb<TAB>N" on stdout.
 * The command's exit status is passed on. The bench uses it for
 * pm-render's memory per million photons. */
#define _DEFAULT_SOURCE    /* wait4 */
#include <stdio.h>
#include <sys/resource.h>
#include <sys/types.h>
#include <sys/wait.h>
#include <unistd.h>

int
main(int argc, char **argv)
{
	pid_t pid;
	int st;
	struct rusage ru;

	if (argc < 2) {
		fprintf(stderr, "usage: peakrss COMMAND [ARG...]\n");
		return 2;
	}
	pid = fork();
	if (pid < 0) {
		perror("peakrss: fork");
		return 1;
	}
	if (pid == 0) {
		execvp(argv[1], argv + 1);
		perror("peakrss: exec");
		_exit(127);
	}
	if (wait4(pid, &st, 0, &ru) < 0) {
		perror("peakrss: wait");
		return 1;
	}
	fflush(stdout);
	printf("peak_rss_kb\t%ld\n", ru.ru_maxrss);
	return WIFEXITED(st) ? WEXITSTATUS(st) : 1;
}
