# pm — photon-map global illumination toolset. See README.md.
include config.mk

B        ?= build
LIB_C    := $(wildcard lib/*.c)
LIB_CXX  := $(wildcard lib/*.cpp)
LIB_OBJ  := $(LIB_C:%.c=$(B)/%.o) $(LIB_CXX:%.cpp=$(B)/%.o)
TOOL_SRC := $(wildcard tools/pm-*.c)
TOOLS    := $(TOOL_SRC:tools/%.c=$(B)/bin/%)
UTIL_OBJ := $(B)/tools/util.o
UNIT_SRC := $(wildcard tests/unit/test_*.c)
UNITS    := $(UNIT_SRC:tests/unit/%.c=$(B)/tests/%)

all: $(TOOLS)

$(B)/lib/%.o: lib/%.c $(wildcard lib/*.h) config.mk
	@mkdir -p $(@D)
	$(CC) $(CFLAGS) $(PKG_CFLAGS) -c $< -o $@

$(B)/lib/%.o: lib/%.cpp $(wildcard lib/*.h) config.mk
	@mkdir -p $(@D)
	$(CXX) $(CXXFLAGS) -c $< -o $@

$(B)/libpm.a: $(LIB_OBJ)
	@rm -f $@
	$(AR) rcs $@ $^

$(B)/tools/%.o: tools/%.c tools/util.h $(wildcard lib/*.h) config.mk
	@mkdir -p $(@D)
	$(CC) $(CFLAGS) $(PKG_CFLAGS) -Itools -c $< -o $@

$(B)/bin/%: $(B)/tools/%.o $(UTIL_OBJ) $(B)/libpm.a
	@mkdir -p $(@D)
	$(CXX) $(LDFLAGS) $^ $(LDLIBS) -o $@

$(B)/tests/%: tests/unit/%.c tests/check.h $(B)/libpm.a
	@mkdir -p $(@D)
	$(CC) $(CFLAGS) $(PKG_CFLAGS) -Itests -c $< -o $@.o
	$(CXX) $(LDFLAGS) $@.o $(B)/libpm.a $(LDLIBS) -o $@

deps:
	@sh mk/deps.sh

check: deps
	@$(MAKE) --no-print-directory all-tests
	@sh tests/run.sh $(B)

all-tests: $(TOOLS) $(UNITS)

demo: deps
	@$(MAKE) --no-print-directory all
	@sh examples/cornell/run.sh

install: all
	install -d $(DESTDIR)$(PREFIX)/bin
	install -m 755 $(TOOLS) $(DESTDIR)$(PREFIX)/bin

clean:
	rm -rf $(B)

.PHONY: all deps check all-tests demo install clean
.SECONDARY:

# Helper programs that tests use to make inputs (not tests themselves).
TESTTOOL_SRC := $(wildcard tests/tools/*.c)
TESTTOOLS    := $(TESTTOOL_SRC:tests/tools/%.c=$(B)/tests/tools/%)
all-tests: $(TESTTOOLS)
$(B)/tests/tools/%: tests/tools/%.c $(B)/libpm.a
	@mkdir -p $(@D)
	$(CC) $(CFLAGS) $(PKG_CFLAGS) -Itests -c $< -o $@.o
	$(CXX) $(LDFLAGS) $@.o $(B)/libpm.a $(LDLIBS) -o $@
