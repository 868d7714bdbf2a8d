# config.mk — build settings; override on the command line (make CC=clang).
PREFIX  ?= /usr/local
CC      ?= cc
CXX     ?= c++
OPT     ?= -O2 -g
PKGS    := OpenEXR openmesh libpng expat zlib OpenImageIO
PKG_CFLAGS := $(shell pkg-config --cflags $(PKGS) 2>/dev/null)
PKG_LIBS   := $(shell pkg-config --libs $(PKGS) 2>/dev/null) -lembree3
CFLAGS  ?= $(OPT)
CFLAGS  += -std=c11 -D_POSIX_C_SOURCE=200809L -Wall -Wextra -Wno-unused-parameter -fopenmp -Ilib
CXXFLAGS ?= $(OPT)
CXXFLAGS += -std=c++17 -Wall -Wextra -Ilib $(PKG_CFLAGS)
LDFLAGS += -fopenmp
LDLIBS  += $(PKG_LIBS) -lm
