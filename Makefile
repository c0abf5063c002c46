# trigeo - top-level entry points. `make demo` and `make test` work on a fresh Debian 12 as root:
# they install the missing Debian packages with apt-get first.
#
#   make demo    build, then run the main job on the bundled default mesh (data/nvd_spot.obj)
#   make test    the fast suite: build with gcc and run the tests labelled fast (corpus loops on a
#                fixed subset, sweeps at coarse steps); build with clang + ASan/UBSan and run them
#                again (about 5 minutes on 2 cores from a fresh clone)
#   make check   the full suite: both builds (the sanitizer one with the fuzz targets), every test
#                with TG_FULL=1 (every corpus sample, sweeps, OOM sweeps, install and cluster
#                tests, fuzz smoke runs); about 15 minutes on 2 cores after make test
#   make bench   benchmarks against the peers (Embree, CGAL), tables on stdout
#   make fuzz    libFuzzer targets for a bounded time each (FUZZ_SECONDS, default 60)
#   make build   release build only (build/)
#   make install PREFIX=DIR   the CLI, libraries, header, pkg-config file and CMake package

SHELL := /bin/bash
JOBS ?= $(shell nproc 2>/dev/null || echo 2)
BUILD ?= build
ASAN_BUILD ?= build-asan
BENCH_BUILD ?= build-bench
FUZZ_SECONDS ?= 60
CMAKE_FLAGS ?=

DEPS := cmake make gcc g++ clang libclang-rt-14-dev libomp-dev zlib1g-dev libpng-dev libgmp-dev pkg-config python3 locales \
        python3-numpy python3-scipy python3-pytest python3-distributed python3-pip python3-setuptools python3-wheel \
        python3-venv
BENCH_DEPS := libembree-dev libcgal-dev libeigen3-dev time

.PHONY: all deps bench-deps build build-asan demo test test-release test-asan check check-release check-asan \
        bench fuzz clean large install

PREFIX ?= /usr/local

all: build

deps:
	@bash scripts/ensure-packages.sh $(DEPS)

bench-deps:
	@bash scripts/ensure-packages.sh $(DEPS) $(BENCH_DEPS)

build: deps
	cmake -S . -B $(BUILD) -DCMAKE_BUILD_TYPE=Release -DCMAKE_C_COMPILER=gcc -DCMAKE_CXX_COMPILER=g++ $(CMAKE_FLAGS) >/dev/null
	cmake --build $(BUILD) -j $(JOBS)

# the CLI, libtrigeo (shared and static), trigeo.h, trigeo.pc and the CMake package under PREFIX
install: build
	cmake --install $(BUILD) --prefix $(PREFIX)

demo: build
	@bash scripts/demo.sh $(BUILD)/trigeo

# The sanitizer tree: FUZZ=ON (make check, make fuzz) adds the libFuzzer targets, which build a
# second, coverage-instrumented copy of the library; make test leaves them out.
FUZZ ?= OFF
SAN_ENV := ASAN_OPTIONS=detect_leaks=1:abort_on_error=1 UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1 \
           LSAN_OPTIONS=suppressions=$(CURDIR)/tests/lsan.supp
build-asan: deps
	cmake -S . -B $(ASAN_BUILD) -DCMAKE_BUILD_TYPE=RelWithDebInfo -DCMAKE_C_COMPILER=clang -DCMAKE_CXX_COMPILER=clang++ \
	      -DTG_SANITIZE=ON -DTG_FUZZ=$(FUZZ) $(CMAKE_FLAGS) >/dev/null
	cmake --build $(ASAN_BUILD) -j $(JOBS)

# fast suite: every test but those labelled `full` (tests/CMakeLists.txt), each in its fast form
test-release: build
	cd $(BUILD) && ctest --output-on-failure -j $(JOBS) -LE full

test-asan: build-asan
	cd $(ASAN_BUILD) && $(SAN_ENV) ctest --output-on-failure -j $(JOBS) -LE full

test: test-release test-asan
	@echo "make test: the fast suite passed, gcc release and clang ASan+UBSan (make check runs the full one)"

# full suite: every test, TG_FULL=1
check-release: build
	cd $(BUILD) && TG_FULL=1 ctest --output-on-failure -j $(JOBS)

check-asan:
	$(MAKE) build-asan FUZZ=ON
	cd $(ASAN_BUILD) && TG_FULL=1 $(SAN_ENV) ctest --output-on-failure -j $(JOBS)

check: check-release check-asan
	@echo "make check: the full suite passed, gcc release and clang ASan+UBSan"

large:
	@bash ../shared/tools/make_large_meshes.sh $(BUILD)/large
	@for l in 7 8; do [ -s $(BUILD)/large/icosphere$$l.ply ] || python3 bench/make_icosphere.py $$l $(BUILD)/large/icosphere$$l.ply; done

bench: bench-deps large
	cmake -S . -B $(BENCH_BUILD) -DCMAKE_BUILD_TYPE=Release -DCMAKE_C_COMPILER=gcc -DCMAKE_CXX_COMPILER=g++ \
	      -DTG_BENCH=ON -DTG_TESTS=OFF -DTG_LARGE_DIR=$(abspath $(BUILD))/large $(CMAKE_FLAGS) >/dev/null
	cmake --build $(BENCH_BUILD) -j $(JOBS)
	@bash bench/run.sh $(BENCH_BUILD) $(abspath $(BUILD))/large

fuzz:
	$(MAKE) build-asan FUZZ=ON
	@bash fuzz/run.sh $(ASAN_BUILD) $(FUZZ_SECONDS)

clean:
	rm -rf $(BUILD) $(ASAN_BUILD) $(BENCH_BUILD)
