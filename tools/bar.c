/* bar.c — progress bars on stderr (see bar.h). */
#include "bar.h"

#include <stdio.h>
#include <time.h>
#include <unistd.h>

#include "util.h"

#define BAR 20

static double
now(void)
{
	struct timespec ts;

	clock_gettime(CLOCK_MONOTONIC, &ts);
	return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

/* m:ss, or h:mm:ss past an hour. */
static void
clock_str(char *buf, size_t n, double sec)
{
	unsigned long s = sec > 0 && sec < 1e9 ? (unsigned long)(sec + 0.5) : 0;

	if (s >= 3600)
		snprintf(buf, n, "%lu:%02lu:%02lu", s / 3600, s / 60 % 60, s % 60);
	else
		snprintf(buf, n, "%lu:%02lu", s / 60, s % 60);
}

static void
draw(progress *p, uint64_t done, double t, int final)
{
	char bar[BAR + 1], when[32], speed[32];
	double el = t - p->start, rate = el > 0 ? (double)done / el : 0, frac;
	int fill;

	frac = p->total ? (double)done / (double)p->total : 1.0;
	if (frac > 1)
		frac = 1;
	fill = (int)(frac * BAR);
	for (int i = 0; i < BAR; i++)
		bar[i] = i < fill ? '#' : '.';
	bar[BAR] = 0;
	if (final)
		clock_str(when, sizeof when, el);
	else if (rate > 0 && done < p->total)
		clock_str(when, sizeof when, (double)(p->total - done) / rate);
	else
		snprintf(when, sizeof when, "-:--");
	if (rate >= 1e6)
		snprintf(speed, sizeof speed, "%.1fM", rate / 1e6);
	else if (rate >= 1e3)
		snprintf(speed, sizeof speed, "%.1fk", rate / 1e3);
	else
		snprintf(speed, sizeof speed, "%.1f", rate);
	/* \r back to the line's start, \033[K clears what a longer line left. */
	fprintf(stderr, "\r%s: %s [%s] %llu/%llu %3.0f%% %s/s %s%s\033[K%s", argv0, p->what,
	        bar, (unsigned long long)done, (unsigned long long)p->total, 100 * frac,
	        speed, when, final ? " total" : " left", final ? "\n" : "");
	fflush(stderr);
	p->drawn = 1;
	p->last = t;
}

void
progress_start(progress *p, const char *what, uint64_t total, int quiet)
{
	p->what = what;
	p->total = total;
	p->start = p->last = now();
	p->drawn = 0;
	p->on = !quiet && isatty(2);
}

void
progress_update(progress *p, uint64_t done)
{
	double t;

	if (!p->on)
		return;
	t = now();
	if (p->drawn && t - p->last < 0.1)
		return;
	draw(p, done, t, 0);
}

void
progress_end(progress *p, uint64_t done)
{
	if (!p->on)
		return;
	draw(p, done, now(), 1);
	p->on = 0;
}

void
progress_hook(void *arg, uint64_t done, uint64_t total)
{
	progress *p = arg;

	p->total = total;
	progress_update(p, done);
}
