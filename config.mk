# config.mk — build settings; override on the command line (make CC=clang).
PREFIX  ?= /usr/local
CC      ?= cc
CXX     ?= c++
OPT     ?= -O2 -g
PKGS    := OpenEXR openmesh libpng expat zlib
PKG_CFLAGS := $(shell pkg-config --cflags $(PKGS) 2>/dev/null)
PKG_LIBS   := $(shell pkg-config --libs $(PKGS) 2>/dev/null) -lembree3
# OpenImageIO only in the module pm-oiio.so (lib/scene/oiio.h).
OIIO_CFLAGS := $(shell pkg-config --cflags OpenImageIO 2>/dev/null)
OIIO_LIBS   := $(shell pkg-config --libs OpenImageIO 2>/dev/null)
CFLAGS  ?= $(OPT)
CFLAGS  += -std=c11 -D_POSIX_C_SOURCE=200809L -Wall -Wextra -Wno-unused-parameter -fopenmp -Ilib
CXXFLAGS ?= $(OPT)
CXXFLAGS += -std=c++17 -Wall -Wextra -Ilib $(PKG_CFLAGS)
LDFLAGS += -fopenmp
LDLIBS  += $(PKG_LIBS) -ldl -lm
