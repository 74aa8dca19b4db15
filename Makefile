# vres - variable-resolution SPH toolkit.
#   make            build libvres and every tool into bin/ (CUDA parts too where nvcc exists)
#   make check      build, then run the whole test suite (unit + tool behaviour + ASan readers)
#                   (B=DIR BINDIR=DIR: another build directory and tool directory, for parallel work)
#                   (CHECK_JOBS=N: objects built at a time, VRES_JOBS=N: tests run at a time;
#                   both default to the CPU count)
#   make bench      throughput table of vres-run (pipelines/bench.sh)
#   make validate   validation cases at their validation dp (pipelines/validate.mk; long)
#   make sweep      error-against-run-time sweeps with GNU parallel (pipelines/sweep.mk; long)
#   make fuzz       build the libFuzzer harnesses (tests/fuzz, clang) and run each FUZZ_S seconds
#   make demo       generate the shipped cases and export them to VTK under demo/
#   make install PREFIX=/usr/local
# Sources are found by wildcard: lib/*.c|*.cc|*.cu -> libvres, tools/vres-*.c -> bin/vres-*,
# tests/lib/test_*.c -> unit tests (Check).

VERSION   := 0.1.0
comma     := ,
PREFIX    ?= /usr/local
CC        := gcc
CXX       := g++
GIT_REV   := $(shell git rev-parse --short HEAD 2>/dev/null || echo unknown)

PKGS      := hdf5-serial libxml-2.0
PKG_CFLAGS := $(shell pkg-config --cflags $(PKGS) 2>/dev/null)
PKG_LIBS  := $(shell pkg-config --libs $(PKGS) 2>/dev/null) -lhdf5_hl
HDF5_LIBDIR := $(patsubst -L%,%,$(filter -L%,$(shell pkg-config --libs-only-L hdf5-serial 2>/dev/null)))
VTK_INC   ?= /usr/include/vtk-9.1
VTK_LIBS  ?= -lvtkIOXML-9.1 -lvtkIOCore-9.1 -lvtkCommonExecutionModel-9.1 -lvtkCommonDataModel-9.1 -lvtkCommonCore-9.1
CHECK_LIBS := $(shell pkg-config --libs check 2>/dev/null)

# -fno-math-errno: sqrt sets no errno, so the interaction's vector loops can use it.
# -fno-trapping-math: no floating-point trap is ever enabled (vres never touches fenv), so GCC may
# compute both arms of a select in a vector loop: without it the cubic spline's piecewise W and F
# kept the interaction's pair pass scalar (GCC 12 moves each arm's products into a branch). Neither
# flag changes a result: values stay IEEE's, nothing is reassociated or fused.
OPT       ?= -O2 -g -fno-math-errno -fno-trapping-math
WARN      := -Wall -Wextra
CFLAGS    := -std=c11 $(WARN) $(OPT) -fopenmp -D_POSIX_C_SOURCE=200809L -Ilib -Ikernels $(PKG_CFLAGS)
CXXFLAGS  := -std=c++17 $(WARN) $(OPT) -Ilib -isystem $(VTK_INC)
LDLIBS    := $(PKG_LIBS) $(VTK_LIBS) -lfftw3 -fopenmp -lm -lstdc++ $(if $(HDF5_LIBDIR),-Wl$(comma)-rpath$(comma)$(HDF5_LIBDIR))

# CUDA: built wherever nvcc is found; CUDA_ARCH kept short (one arch + its PTX for newer GPUs).
NVCC      ?= $(shell command -v nvcc 2>/dev/null || (test -x /usr/local/cuda/bin/nvcc && echo /usr/local/cuda/bin/nvcc))
CUDA_ARCH ?= -gencode arch=compute_75,code=[sm_75,compute_75]
ifneq ($(NVCC),)
  CUDA_HOME := $(patsubst %/bin/nvcc,%,$(NVCC))
  CFLAGS    += -DVRES_HAVE_CUDA
  NVFLAGS   := -O2 -std=c++17 $(CUDA_ARCH) -Ilib -Ikernels -DVRES_HAVE_CUDA
  LDLIBS    += -L$(CUDA_HOME)/lib64 -lcudart -Wl,-rpath,$(CUDA_HOME)/lib64
  CU_SRC    := $(wildcard lib/*.cu)
  CFLAGS    += $(if $(wildcard lib/solver_cuda.cu),-DVRES_HAVE_CUDA_SOLVER)
else
  CU_SRC    :=
endif

LIB_C     := $(wildcard lib/*.c)
LIB_CC    := $(wildcard lib/*.cc)
TOOL_SRC  := $(wildcard tools/vres-*.c)
BINDIR    ?= bin
TOOLS     := $(patsubst tools/%.c,$(BINDIR)/%,$(TOOL_SRC))
TEST_SRC  := $(wildcard tests/lib/test_*.c)
B         ?= build
TESTS     := $(patsubst tests/lib/%.c,$(B)/tests/%,$(TEST_SRC))
LIB_OBJ   := $(patsubst lib/%.c,$(B)/obj/%.o,$(LIB_C)) $(patsubst lib/%.cc,$(B)/obj/%.o,$(LIB_CC)) \
             $(patsubst lib/%.cu,$(B)/obj/%.cu.o,$(CU_SRC))
LIBVRES   := $(B)/libvres.a

# AddressSanitizer build of the tools, used by the tests on bad input (no CUDA objects). -g1:
# line tables only (a report's stack still names file:line), since full debug information
# doubled the make check build's costliest object (build/asan/solver_cpu.o: 139 s of CPU with
# -g, 75 s with -g1, gcc 12)
ASAN_FLAGS := -fsanitize=address,undefined -fno-omit-frame-pointer -g1
ASAN_OBJ  := $(patsubst lib/%.c,$(B)/asan/%.o,$(LIB_C)) $(patsubst lib/%.cc,$(B)/asan/%.o,$(LIB_CC))
ASAN_TOOLS := $(patsubst tools/%.c,$(B)/asan/bin/%,$(TOOL_SRC))

all: $(TOOLS)
ifeq ($(NVCC),)
	@echo "note: nvcc not found: CUDA backend not built (install the CUDA toolkit to build it)"
endif

$(B)/obj/version.o $(B)/asan/version.o: CFLAGS += -DVRES_VERSION='"$(VERSION)"' -DVRES_GIT='"$(GIT_REV)"' \
  -DVRES_CFLAGS='"$(OPT) $(WARN)"'

$(B)/obj/%.o: lib/%.c $(wildcard lib/*.h kernels/*.h) | $(B)/obj
	$(CC) $(CFLAGS) -c $< -o $@
$(B)/obj/%.o: lib/%.cc $(wildcard lib/*.h) | $(B)/obj
	$(CXX) $(CXXFLAGS) -c $< -o $@
$(B)/obj/%.cu.o: lib/%.cu $(wildcard lib/*.h kernels/*.h) | $(B)/obj
	$(NVCC) $(NVFLAGS) -c $< -o $@
$(LIBVRES): $(LIB_OBJ)
	rm -f $@ && ar rcs $@ $^

$(BINDIR)/vres-%: tools/vres-%.c $(LIBVRES) $(wildcard lib/*.h) | $(BINDIR)
	$(CC) $(CFLAGS) $< -o $@ $(LIBVRES) $(LDLIBS)

$(B)/asan/%.o: lib/%.c $(wildcard lib/*.h kernels/*.h) | $(B)/asan/bin
	$(CC) $(filter-out -DVRES_HAVE_CUDA -DVRES_HAVE_CUDA_SOLVER,$(CFLAGS)) -O1 $(ASAN_FLAGS) -c $< -o $@
$(B)/asan/%.o: lib/%.cc $(wildcard lib/*.h) | $(B)/asan/bin
	$(CXX) $(CXXFLAGS) -O1 $(ASAN_FLAGS) -c $< -o $@
$(B)/asan/bin/vres-%: tools/vres-%.c $(ASAN_OBJ) | $(B)/asan/bin
	$(CC) $(filter-out -DVRES_HAVE_CUDA -DVRES_HAVE_CUDA_SOLVER,$(CFLAGS)) -O1 $(ASAN_FLAGS) $< -o $@ $(ASAN_OBJ) \
	  $(filter-out -lcudart,$(LDLIBS))

$(B)/tests/test_%: tests/lib/test_%.c $(LIBVRES) | $(B)/tests
	$(CC) $(CFLAGS) $< -o $@ $(LIBVRES) $(CHECK_LIBS) $(LDLIBS)

# Fuzzing harnesses (tests/fuzz/fuzz_*.c, one reader each). make check replays their corpus and
# regression inputs through replay.c's main() linked with the ASan objects (gcc, no clang needed);
# make fuzz builds them with clang's libFuzzer under ASan+UBSan and runs each FUZZ_S seconds
# (tests/fuzz/run.sh: new inputs under $(B)/fuzz/corpus, crashes under $(B)/fuzz/crash).
FUZZ_NAMES := $(patsubst tests/fuzz/fuzz_%.c,%,$(wildcard tests/fuzz/fuzz_*.c))
REPLAYS   := $(patsubst %,$(B)/fuzz/replay_%,$(FUZZ_NAMES))
FUZZERS   := $(patsubst %,$(B)/fuzz/fuzz_%,$(FUZZ_NAMES))
CLANG     ?= clang
FUZZ_S    ?= 60
FUZZ_SAN  := -fsanitize=address,undefined -fno-sanitize-recover=undefined -fno-omit-frame-pointer
FUZZ_CFLAGS = $(filter-out -DVRES_HAVE_CUDA -DVRES_HAVE_CUDA_SOLVER -O2,$(CFLAGS)) -O1 -Wno-unknown-pragmas -Wno-pass-failed
FUZZ_OBJ  := $(patsubst lib/%.c,$(B)/fuzz/obj/%.o,$(LIB_C))

$(B)/fuzz/replay_%: tests/fuzz/fuzz_%.c tests/fuzz/replay.c tests/fuzz/fuzz.h $(ASAN_OBJ) | $(B)/fuzz/obj
	$(CC) $(filter-out -DVRES_HAVE_CUDA -DVRES_HAVE_CUDA_SOLVER,$(CFLAGS)) -O1 $(ASAN_FLAGS) $< tests/fuzz/replay.c \
	  -o $@ $(ASAN_OBJ) $(filter-out -lcudart,$(LDLIBS))
$(B)/fuzz/obj/%.o: lib/%.c $(wildcard lib/*.h kernels/*.h) | $(B)/fuzz/obj fuzz-clang
	$(CLANG) $(FUZZ_CFLAGS) -fsanitize=fuzzer-no-link $(FUZZ_SAN) -c $< -o $@
$(B)/fuzz/libvres-fuzz.a: $(FUZZ_OBJ)
	rm -f $@ && ar rcs $@ $^
$(B)/fuzz/fuzz_%: tests/fuzz/fuzz_%.c tests/fuzz/fuzz.h $(B)/fuzz/libvres-fuzz.a
	$(CLANG) $(FUZZ_CFLAGS) -fsanitize=fuzzer $(FUZZ_SAN) $< -o $@ $(B)/fuzz/libvres-fuzz.a \
	  $(PKG_LIBS) -lfftw3 -fopenmp -lm $(if $(HDF5_LIBDIR),-Wl$(comma)-rpath$(comma)$(HDF5_LIBDIR))
$(B)/fuzz/obj/version.o: CFLAGS += -DVRES_VERSION='"$(VERSION)"' -DVRES_GIT='"$(GIT_REV)"' \
  -DVRES_CFLAGS='"fuzz"'

fuzz-clang:
	@command -v $(CLANG) >/dev/null || { echo "make fuzz needs clang with libFuzzer: ./setup.sh --deps-only" \
	  "installs clang, libclang-rt-dev and libomp-dev"; exit 1; }
fuzzers: $(FUZZERS)
fuzz: $(FUZZERS)
	FUZZ_S=$(FUZZ_S) VRES_BUILD=$(B) bash tests/fuzz/run.sh $(FUZZ_NAMES)

$(B)/obj $(B)/asan/bin $(B)/tests $(B)/fuzz/obj $(BINDIR):
	mkdir -p $@

asan: $(ASAN_TOOLS)

# The whole test suite: unit tests, tool behaviour tests, ASan runs on bad input, the fuzzing
# corpus replayed. What it needs is built CHECK_JOBS at a time (default: the CPU count; a make
# -jN check keeps its own N), and tests/run runs its tests as many at a time (VRES_JOBS).
CHECK_JOBS ?= $(shell nproc 2>/dev/null || echo 1)
check:
	$(MAKE) $(if $(filter -j%,$(MAKEFLAGS)),,-j$(CHECK_JOBS)) check-build
	VRES_BUILD=$(B) VRES_BIN=$(abspath $(BINDIR)) bash tests/run
check-build: all asan $(TESTS) $(REPLAYS)

# Throughput table of vres-run (not a test; see pipelines/bench.sh).
bench: all
	bash pipelines/bench.sh

demo: all
	$(MAKE) -f pipelines/demo.mk

# Validation cases at their validation dp (pipelines/validate.mk: minutes to an hour on 2 cores)
# and error-against-run-time sweeps (pipelines/sweep.mk: GNU parallel, reports in pipelines/reports/).
validate: all
	$(MAKE) -f pipelines/validate.mk
sweep: all
	$(MAKE) -f pipelines/sweep.mk
.PHONY: validate sweep

install: all
	install -d $(DESTDIR)$(PREFIX)/bin $(DESTDIR)$(PREFIX)/share/man/man1 \
	  $(DESTDIR)$(PREFIX)/share/man/man5 $(DESTDIR)$(PREFIX)/share/man/man7
	install -m 755 $(TOOLS) $(DESTDIR)$(PREFIX)/bin
	install -m 644 $(wildcard man/man1/*.1) $(DESTDIR)$(PREFIX)/share/man/man1
	install -m 644 $(wildcard man/man5/*.5) $(DESTDIR)$(PREFIX)/share/man/man5
	install -m 644 $(wildcard man/man7/*.7) $(DESTDIR)$(PREFIX)/share/man/man7

clean:
	rm -rf $(B) bin demo

.PHONY: all asan check check-build bench demo install clean fuzz fuzzers fuzz-clang
.SECONDARY: $(ASAN_OBJ) $(LIB_OBJ) $(FUZZ_OBJ)
.DELETE_ON_ERROR:
