/* check.h — the unit-test harness: TAP-like lines that tests/run.sh counts.
 *
 *   TEST(name) { CHECK(x == 1); CHECKF(fabs(a-b) < 1e-6, "a=%g b=%g", a, b); }
 *   int main(void) { RUN(name); return check_done(); }
 *
 * Each TEST prints "ok - name" or "not ok - name: FILE:LINE: what failed". */
#ifndef PM_CHECK_H
#define PM_CHECK_H

#include <stdio.h>

static int check_npass, check_nfail, check_cur_failed;
static const char *check_cur;

#define TEST(name) static void test_##name(void)
#define RUN(name) do { \
	check_cur = #name; check_cur_failed = 0; test_##name(); \
	if (check_cur_failed) check_nfail++; \
	else { check_npass++; printf("ok - %s\n", check_cur); } \
	fflush(stdout); } while (0)
#define CHECKF(cond, ...) do { if (!(cond)) { \
	if (!check_cur_failed) printf("not ok - %s: %s:%d: %s", check_cur, __FILE__, __LINE__, #cond); \
	else printf("  also %s:%d: %s", __FILE__, __LINE__, #cond); \
	printf(" ("); printf(__VA_ARGS__); printf(")\n"); check_cur_failed = 1; } } while (0)
#define CHECK(cond) CHECKF(cond, "false")

static inline int check_done(void) { return check_nfail ? 1 : 0; }

#endif
