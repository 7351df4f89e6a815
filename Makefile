# Makefile: builds the ffcontact C library, the FreeFEM plugin and the
# meshes; runs case studies, tests and benchmarks.
#   make            library + plugin
#   make demo       set-up, build, Hertz case study end to end (quadratic, h_c = 0.05)
#   make test       set-up, build, whole test suite
#   make run CASE=<name> ARGS="<options>" [NP=<n>]   one case study -> results/<name>.json
#                   (NP: n ranks of FreeFem++-mpi: small strain, every rank the whole CHOLMOD factor and the compliance columns shared; full systems by parallel MUMPS)
#   make exercise N=<k> ARGS="<options> name=value"   exercise k, checked (README "Exercises")
#   make exercises-check   every exercise's reference solution and common slip

CC      ?= gcc
CXX     ?= g++
CFLAGS  ?= -O2
CFLAGS  += -std=c11 -Wall -Wextra -Werror -fPIC -Iinclude
FFFLAGS  = -shared -fPIC -O2 -std=c++14 -DBAMG_LONG_LONG -DNCHECKPTR -DNDEBUG \
           -isystem /usr/include/freefem++ -Iinclude -Wall -Wno-unused-parameter -Wno-mismatched-new-delete
B       := build
CLIBS   := -lumfpack -lcholmod -llapack -lblas -lm

# PETSc (the iterative path, plugin/ffc_eng_petsc.c) where pkg-config and
# mpicc find it; without it that file builds a stub (FFC_ERR_UNAVAILABLE)
PETSC_OK := $(shell pkg-config --exists PETSc 2>/dev/null && command -v mpicc >/dev/null 2>&1 && echo 1)
ifeq ($(PETSC_OK),1)
PETSC_CFLAGS := -DFFC_PETSC $(patsubst -I%,-isystem %,$(shell pkg-config --cflags-only-I PETSc) $(shell mpicc --showme:compile))
PETSC_LIBS   := $(shell pkg-config --libs PETSc) $(shell mpicc --showme:link)
endif
CSRC    := $(wildcard plugin/*.c)
COBJ    := $(patsubst plugin/%.c,$(B)/obj/%.o,$(CSRC))
# the FreeFEM shim: every plugin/*.cpp, one object each (the FreeFEM flags
# without -shared), linked with the C library into ffcontact.so
SHSRC   := $(wildcard plugin/*.cpp)
SHOBJ   := $(patsubst plugin/%.cpp,$(B)/shim/%.o,$(SHSRC))
SHHDRS  = $(PUBHDRS) $(wildcard plugin/*.hpp)
SHFLAGS  = $(filter-out -shared,$(FFFLAGS))
CTESTS  := $(patsubst tests/c/%.c,$(B)/tests/%,$(wildcard tests/c/test_*.c))
# the public header and its layers (include/ffc/*.h), then the kernels' internal ones
PUBHDRS := include/ffc.h $(wildcard include/ffc/*.h)
HDRS    := $(PUBHDRS) $(wildcard plugin/*.h)

.PHONY: all lib plugin mpi mpitest setup test demo run ctest clean meshes
all: lib plugin mpi meshes

lib: $(B)/libffc.a
plugin: $(B)/ffcontact.so

$(B)/obj/%.o: plugin/%.c $(HDRS)
	@mkdir -p $(dir $@)
	$(CC) $(CFLAGS) -c $< -o $@

$(B)/obj/ffc_eng_petsc.o $(B)/mpi/obj/ffc_eng_petsc.o: CFLAGS += $(PETSC_CFLAGS)
$(B)/libffc.a: $(COBJ)
	@rm -f $@
	ar rcs $@ $^

$(B)/shim/%.o: plugin/%.cpp $(SHHDRS)
	@mkdir -p $(dir $@)
	$(CXX) $(SHFLAGS) -c $< -o $@

$(B)/ffcontact.so: $(SHOBJ) $(B)/libffc.a
	$(CXX) $(FFFLAGS) $(SHOBJ) $(B)/libffc.a $(CLIBS) $(PETSC_LIBS) -o $@

# the plugin for FreeFem++-mpi (scripts/ff -np N): the same sources with
# -DFFC_MPI, parallel MUMPS for the bulk factorization when ranks > 1
MPICC   ?= mpicc
MPICXX  ?= mpicxx
MB      := $(B)/mpi
MOBJ    := $(patsubst plugin/%.c,$(MB)/obj/%.o,$(CSRC))
mpi: $(MB)/ffcontact.so
$(MB)/obj/%.o: plugin/%.c $(HDRS)
	@mkdir -p $(dir $@)
	$(MPICC) $(CFLAGS) -DFFC_MPI -c $< -o $@
$(MB)/libffc.a: $(MOBJ)
	@rm -f $@
	ar rcs $@ $^
MSHOBJ  := $(patsubst plugin/%.cpp,$(MB)/shim/%.o,$(SHSRC))
$(MB)/shim/%.o: plugin/%.cpp $(SHHDRS)
	@mkdir -p $(dir $@)
	$(MPICXX) $(SHFLAGS) -DFFC_MPI -c $< -o $@
$(MB)/ffcontact.so: $(MSHOBJ) $(MB)/libffc.a
	$(MPICXX) $(FFFLAGS) -DFFC_MPI $(MSHOBJ) $(MB)/libffc.a -ldmumps -lscalapack-openmpi $(CLIBS) $(PETSC_LIBS) -o $@
$(MB)/tests/%: tests/mpi/%.c tests/c/ffc_test.h tests/c/engine_test.h $(MB)/libffc.a
	@mkdir -p $(dir $@)
	$(MPICC) $(CFLAGS) -DFFC_MPI -Itests/c -Iplugin $< $(MB)/libffc.a -lcmocka -ldmumps -lscalapack-openmpi $(CLIBS) $(PETSC_LIBS) -o $@
MPITESTS := $(patsubst tests/mpi/%.c,$(MB)/tests/%,$(wildcard tests/mpi/test_*.c))
mpitest: $(MPITESTS)

$(B)/tests/%: tests/c/%.c tests/c/ffc_test.h tests/c/engine_test.h $(B)/libffc.a
	@mkdir -p $(dir $@)
	$(CC) $(CFLAGS) -Itests/c -Iplugin $< $(B)/libffc.a -lcmocka $(CLIBS) $(PETSC_LIBS) -o $@

ctest: $(CTESTS)

setup:
	@sh scripts/setup.sh

test: setup
	@$(MAKE) --no-print-directory all ctest mpitest asan-build
	@sh tests/run.sh

demo: setup
	@$(MAKE) --no-print-directory all
	@$(MAKE) --no-print-directory run CASE=hertz ARGS="-DQUADRATIC=1 $(ARGS)"

run: all
	@test -n "$(CASE)" || { echo "usage: make run CASE=<name> ARGS=\"<options>\""; exit 2; }
	@test -f scripts/$(CASE).edp || { echo "no case study scripts/$(CASE).edp"; exit 2; }
	@mkdir -p results
	sh scripts/ff $(if $(NP),-np $(NP)) scripts/$(CASE).edp $(ARGS)

clean:
	rm -rf $(B)

# exercises (scripts/exercises/, README "Exercises")
.PHONY: exercise exercises-check
exercise: all
	@mkdir -p results
	@sh scripts/exercises/run.sh $(N) $(ARGS)
exercises-check: all
	@sh tests/exercises.sh

# meshes at their default sizes (cases mesh other sizes on demand)
MSH := $(patsubst meshes/%.geo,$(B)/meshes/%.msh,$(wildcard meshes/*.geo))
meshes: $(MSH)
$(B)/meshes/%.msh: meshes/%.geo
	@mkdir -p $(dir $@)
	gmsh -3 -format msh2 -v 1 $< -o $@ >/dev/null

# benchmarks
$(B)/bench_search: tests/bench/bench_search.c $(B)/libffc.a
	$(CC) $(CFLAGS) $< $(B)/libffc.a $(CLIBS) $(PETSC_LIBS) -o $@

.PHONY: bench bench-search bench-contact bench-mpi bench-scene bench-finite bench-scale
bench-search: $(B)/bench_search
	@sh tests/bench/bench_search.sh
bench-contact: all
	@sh tests/bench/bench_contact.sh $(MODE)
# 1 against N ranks (NP, default 2); MODE=full adds ~150k dofs, MODE=large runs that row alone
bench-mpi: all $(B)/bench_pair
	@sh tests/bench/bench_mpi.sh $(or $(MODE),quick) $(or $(NP),2)
$(B)/bench_pair: tests/bench/bench_pair.c
	$(CC) -O2 -std=c11 -D_POSIX_C_SOURCE=200809L -Wall -Wextra -Werror $< -lblas -o $@
# README's own scene and variants (MODE=quick: without the finer mesh)
bench-scene: all
	@sh tests/bench/bench_scene.sh $(MODE)
# finite deformation: the soft ball's three levels (MODE=full: and the ironing)
bench-finite: all
	@sh tests/bench/bench_finite.sh $(MODE)
# the engines as the mesh grows: factored, UMFPACK, iterative on 1 and 2 ranks (MODE=full: 44k dofs too)
bench-scale: all
	@sh tests/bench/bench_scale.sh $(MODE)
bench: bench-search bench-contact bench-mpi bench-scene bench-finite bench-scale

# sanitizers and fuzzing (clang from Debian)
ASAN := -O1 -g -fno-omit-frame-pointer -fsanitize=address,undefined -fno-sanitize-recover=all
$(B)/asan/libffc.a: $(CSRC) $(HDRS)
	@mkdir -p $(B)/asan
	@rm -f $(B)/asan/*.o $@
	cd $(B)/asan && for f in $(CSRC); do clang -std=c11 -Wall -Wextra -Werror -I$(CURDIR)/include $(ASAN) -c $(CURDIR)/$$f || exit 1; done
	ar rcs $@ $(B)/asan/*.o
$(B)/asan/test_%: tests/c/test_%.c tests/c/ffc_test.h tests/c/engine_test.h $(B)/asan/libffc.a
	clang -std=c11 -Wall -Wextra -Iinclude -Itests/c -Iplugin $(ASAN) $< $(B)/asan/libffc.a -lcmocka $(CLIBS) -o $@
$(B)/fuzz/%: tests/fuzz/%.c $(B)/asan/libffc.a
	@mkdir -p $(B)/fuzz
	clang -std=c11 -Iinclude -g -O1 -fsanitize=fuzzer,address,undefined $< $(B)/asan/libffc.a $(CLIBS) -o $@

ASAN_TESTS := $(patsubst tests/c/%.c,$(B)/asan/%,$(wildcard tests/c/test_*.c))
FUZZ := $(patsubst tests/fuzz/%.c,$(B)/fuzz/%,$(wildcard tests/fuzz/fuzz_*.c))
FUZZ_SECONDS ?= 300

.PHONY: test-asan fuzz asan-build
asan-build: $(ASAN_TESTS) $(FUZZ)
test-asan: setup
	@$(MAKE) --no-print-directory asan-build
	@sh tests/run.sh asan
# longer fuzzing by hand: make fuzz FUZZ_SECONDS=3600
fuzz: $(FUZZ)
	@for f in $(FUZZ); do mkdir -p build/fuzz/corpus-$$(basename $$f); \
	  $$f -max_total_time=$(FUZZ_SECONDS) build/fuzz/corpus-$$(basename $$f) tests/fuzz/regress || exit 1; done
# a crash input found by fuzzing becomes a regression test: copy it into
# tests/fuzz/regress/ (every run of make test replays that folder)

# what accuracy costs in time (README "What accuracy costs")
# the impacts on 3 mesh levels x 3 time steps -> results/impact-grid*.csv
.PHONY: impact-grid
impact-grid: all
	@sh scripts/impact-grid.sh bar
	@sh scripts/impact-grid.sh spheres
	@sh scripts/impact-grid.sh oblique

.PHONY: study study-quick study-ensemble
study: all
	@sh scripts/study.sh full
study-quick: all
	@sh scripts/study.sh quick
# Hertz and Cattaneo-Mindlin on 8 meshes of each size (min / median / max of the errors)
study-ensemble: all
	@sh scripts/ensemble.sh
