/* test_passid.c — pass ids (lib/formats/passid.h): the documented text hashed by
 * FNV-1a against its published reference values, every field of the
 * identity counting, pm.pass_ids parsing and formatting, and which repeat
 * pm_passids_dup reports. */
#include <inttypes.h>
#include <stdlib.h>
#include <string.h>

#include "check.h"
#include "base/fnv.h"
#include "formats/passid.h"

TEST(fnv1a_reference_values)
{
	/* Noll's FNV test vectors for FNV-1a 64. */
	CHECK(pm_fnv1a(PM_FNV_OFFSET, "", 0) == 0xcbf29ce484222325ull);
	CHECK(pm_fnv1a(PM_FNV_OFFSET, "a", 1) == 0xaf63dc4c8601ec8cull);
	CHECK(pm_fnv1a(PM_FNV_OFFSET, "foobar", 6) == 0x85944171f73967e8ull);
}

TEST(id_hashes_the_documented_text)
{
	const char *text = "00000000000000ff compensated 42 0.25 1,2";
	uint64_t want = pm_fnv1a(PM_FNV_OFFSET, text, strlen(text));

	CHECK(pm_pass_id(255, "compensated", 42, 0.25f, "1,2") == want);
	CHECK(want == 0xcde406dc23017600ull);    /* formats/image.md's example */
	text = "a86508990a730cb9 path 18446744073709551615 0.123456791 ";
	want = pm_fnv1a(PM_FNV_OFFSET, text, strlen(text));
	CHECK(pm_pass_id(0xa86508990a730cb9ull, "path", UINT64_MAX, 0.123456789f, "") == want);
}

TEST(every_field_counts)
{
	uint64_t id = pm_pass_id(1, "classical", 7, 0.5f, "7");

	CHECK(id == pm_pass_id(1, "classical", 7, 0.5f, "7"));
	CHECK(id != pm_pass_id(2, "classical", 7, 0.5f, "7"));
	CHECK(id != pm_pass_id(1, "compensated", 7, 0.5f, "7"));
	CHECK(id != pm_pass_id(1, "classical", 8, 0.5f, "7"));
	CHECK(id != pm_pass_id(1, "classical", 7, 0.5000001f, "7"));
	CHECK(id != pm_pass_id(1, "classical", 7, 0.5f, "8"));
	CHECK(id != pm_pass_id(1, "classical", 7, 0.5f, "7,8"));
}

TEST(parse_and_format)
{
	pm_passids l;
	pm_error err;
	size_t n;
	uint64_t id;
	int a, b;
	char *s;

	pm_passids_init(&l);
	CHECK(pm_passids_add(&l, "ffffffffffffffff 0000000000000001", 3, &n, &err) == 0 && n == 2);
	CHECK(pm_passids_add(&l, "0123456789abcdef", 5, &n, &err) == 0 && n == 1);
	CHECK(l.n == 3 && l.v[0].id == UINT64_MAX && l.v[0].src == 3 && l.v[2].id == 0x0123456789abcdefull);
	CHECK(pm_passids_dup(&l, &id, &a, &b) == 0);
	s = pm_passids_format(&l);
	CHECKF(s && strcmp(s, "0000000000000001 0123456789abcdef ffffffffffffffff") == 0, "%s", s ? s : "NULL");
	free(s);
	pm_passids_free(&l);
}

TEST(bad_lists_are_refused_whole)
{
	const char *bad[] = {
		"", " ", "0123", "0123456789ABCDEF", "0123456789abcdeg", "0123456789abcdef ",
		" 0123456789abcdef", "0123456789abcdef  0123456789abcdef", "0123456789abcdef0",
		"0123456789abcdef,0123456789abcdef", "0123456789abcdef 0123456789abcdeX",
	};
	pm_passids l;
	pm_error err;
	size_t n;

	pm_passids_init(&l);
	CHECK(pm_passids_add(&l, "0000000000000001", 0, &n, &err) == 0);
	for (size_t k = 0; k < sizeof bad / sizeof *bad; k++)
		CHECKF(pm_passids_add(&l, bad[k], 1, &n, &err) == -1 && n == 0 && l.n == 1 &&
		       strstr(err.msg, "pm.pass_ids") != NULL, "'%s' accepted", bad[k]);
	pm_passids_free(&l);
}

TEST(dup_reports_the_first_repeat_in_input_order)
{
	pm_passids l;
	pm_error err;
	size_t n;
	uint64_t id;
	int a, b;

	pm_passids_init(&l);
	/* Inputs 0 and 4 share 0..aa, inputs 0, 1 and 2 share 0..ff, input 3
	 * holds 0..bb twice: the repeat first met reading the inputs in order
	 * is 0..ff in input 1. */
	pm_passids_add(&l, "00000000000000aa 00000000000000ff", 0, &n, &err);
	pm_passids_add(&l, "00000000000000ff", 1, &n, &err);
	pm_passids_add(&l, "00000000000000ff", 2, &n, &err);
	pm_passids_add(&l, "00000000000000bb 00000000000000bb", 3, &n, &err);
	pm_passids_add(&l, "00000000000000aa", 4, &n, &err);
	CHECK(pm_passids_dup(&l, &id, &a, &b) == 1);
	CHECKF(id == 0xff && a == 0 && b == 1, "id %" PRIx64 " in %d and %d", id, a, b);
	CHECK(l.n == 7);

	pm_passids_free(&l);
	pm_passids_init(&l);
	pm_passids_add(&l, "00000000000000cc", 0, &n, &err);
	pm_passids_add(&l, "00000000000000bb 00000000000000bb", 1, &n, &err);
	CHECK(pm_passids_dup(&l, &id, &a, &b) == 1 && id == 0xbb && a == 1 && b == 1);
	pm_passids_free(&l);
}

int
main(void)
{
	RUN(fnv1a_reference_values);
	RUN(id_hashes_the_documented_text);
	RUN(every_field_counts);
	RUN(parse_and_format);
	RUN(bad_lists_are_refused_whole);
	RUN(dup_reports_the_first_repeat_in_input_order);
	return check_done();
}
