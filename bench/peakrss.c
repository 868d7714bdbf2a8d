/* peakrss.c — runs a command and then prints its peak resident set size
 * (getrusage of the child, in kilobytes) as "peak_rss_kb<TAB>N" on stdout,
 * and its CPU seconds (user + system) and wall seconds as "cpu_s<TAB>S"
 * and "wall_s<TAB>S". The command's exit status is passed on. The bench
 * uses it for pm-render's memory per million photons and for view-pass
 * times on a machine that may be shared (bench/compcost.sh). */
#define _DEFAULT_SOURCE    /* wait4 */
#include <stdio.h>
#include <sys/resource.h>
#include <sys/types.h>
#include <sys/wait.h>
#include <time.h>
#include <unistd.h>

int
main(int argc, char **argv)
{
	pid_t pid;
	int st;
	struct rusage ru;
	struct timespec t0, t1;

	if (argc < 2) {
		fprintf(stderr, "usage: peakrss COMMAND [ARG...]\n");
		return 2;
	}
	clock_gettime(CLOCK_MONOTONIC, &t0);
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
	clock_gettime(CLOCK_MONOTONIC, &t1);
	fflush(stdout);
	printf("peak_rss_kb\t%ld\n", ru.ru_maxrss);
	printf("cpu_s\t%.3f\n", ru.ru_utime.tv_sec + ru.ru_stime.tv_sec +
	       1e-6 * (ru.ru_utime.tv_usec + ru.ru_stime.tv_usec));
	printf("wall_s\t%.3f\n", (t1.tv_sec - t0.tv_sec) + 1e-9 * (t1.tv_nsec - t0.tv_nsec));
	return WIFEXITED(st) ? WEXITSTATUS(st) : 1;
}
