# SPDX-License-Identifier: BSD-3-Clause
# Convenience wrapper around CMake/CTest for flexbond.
#
#   make deps          install the Debian packages the build needs (only those missing)
#   make build         configure + build into $(BUILD_DIR) (RelWithDebInfo)
#   make test          deps + build + run the CTest suite (warnings are errors)
#   make run           deps + build + the default study (examples/apc6x6.yaml, Systems 1 and 2,
#                      report.md) into out/, the modal analyses, the frequency
#                      response (out/freq/) and the quarter-car example into out/quarter_car/
#   make asan          build into $(ASAN_DIR) with ASan+UBSan and run the suite
#   make clang         build into $(CLANG_DIR) with clang and -Werror and run the suite
#   make release       Release builds (-O3) with gcc and clang, -Werror, into $(RELEASE_DIR)
#                      and $(RELEASE_DIR)-clang; the suite runs on the gcc one
#   make mpi           install OpenMPI, build into $(MPI_DIR) with -DFLEXBOND_MPI=ON (flexbond
#                      sweep --mpi, docs/cluster.md) and run the suite, cli_sweep_mpi included
#   make fuzz          build the libFuzzer targets into $(FUZZ_DIR) (clang) and run each for
#                      $(FUZZ_SECONDS) s; fails on any crash, leak or timeout (docs/fuzzing.md)
#   make valgrind      build into $(VALGRIND_DIR) and run the unit tests (tests/test_*.c) under
#                      valgrind memcheck, all but the slowest (docs/quality.md)
#   make tidy          clang-tidy (checks in .clang-tidy) over src/ and the headers it includes
#   make cppcheck      cppcheck over src/
#   make format        clang-format -i every .c/.h under include/ src/ tests/
#   make format-check  fail if any of those files is not clang-format clean
#   make clean         remove the build directories above and out/
#
# Directories and parallelism can be overridden, e.g. `make test BUILD_DIR=build-mine`.

SHELL := /bin/bash
.DEFAULT_GOAL := build
# Prerequisites must run in the order written (deps before build before ctest);
# each CMake build is parallel on its own.
.NOTPARALLEL:

BUILD_DIR ?= build
ASAN_DIR ?= build-asan
CLANG_DIR ?= build-clang
MPI_DIR ?= build-mpi
RELEASE_DIR ?= build-release
OUT_DIR ?= out
BUILD_TYPE ?= RelWithDebInfo
JOBS ?= $(shell nproc 2>/dev/null || echo 2)
CTEST_JOBS ?= 2

# What building and running need (make deps, for make build and make run): the compiler,
# CMake, the libraries (zlib for the FMU archives), gnuplot and Graphviz for the figures,
# python3 with NumPy and SciPy for the Python package (docs/python.md).
DEB_PACKAGES := build-essential cmake pkg-config libsundials-dev libsuitesparse-dev \
                liblapacke-dev libopenblas-dev libfyaml-dev zlib1g-dev gnuplot-nox graphviz \
                python3 python3-numpy python3-scipy
# What the suite needs besides (make deps-test, for make test): strace shows which files a
# command creates and how (tests/cli_integrity.sh); CalculiX's ccx checks the shell stresses
# and solves the exported decks (tests/test_shell_stress_ccx.c, tests/test_hull_stress_ccx.c,
# tests/cli_calculix.sh; all skipped without it); libxml2-dev builds the test tool fmu_import,
# our own FMI 3.0 importer, which reads an FMU's modelDescription.xml with libxml2 (without it
# tests/cli_fmu.sh skips), unzip unpacks the FMUs it runs and libxml2-utils' xmllint validates
# their descriptions against the FMI 3.0 schemas (tests/cli_fmu.sh).
TEST_DEB_PACKAGES := strace calculix-ccx libxml2-dev libxml2-utils unzip
# The developer tools (make deps-dev, for CI and the targets of docs/quality.md): clang is the
# second compiler; clang-format serves format/format-check; valgrind, clang-tidy and cppcheck
# serve the targets of the same names.
DEV_DEB_PACKAGES := clang clang-format valgrind clang-tidy cppcheck
# OpenMPI for the optional MPI build of flexbond sweep (make mpi, docs/cluster.md).
MPI_DEB_PACKAGES := libopenmpi-dev openmpi-bin
SUDO := $(if $(filter 0,$(shell id -u)),,sudo)
APT := $(SUDO) env DEBIAN_FRONTEND=noninteractive apt-get

FORMAT_SOURCES = $(sort $(shell find include src tests -type f \( -name '*.c' -o -name '*.h' \) 2>/dev/null))

# Warnings are errors for the developer targets (test, asan, clang, mpi, release, valgrind)
# and in CI, never for a plain build: `make build`, `make run` and a plain `cmake` must compile
# with any compiler and flags a user has (CMakeLists.txt's FLEXBOND_WERROR is OFF).
WERROR ?= OFF
# $(call cmake_build,DIR,EXTRA CMAKE ARGS): configure and build one tree.
cmake_build = cmake -S . -B $(1) -DCMAKE_BUILD_TYPE=$(BUILD_TYPE) -DFLEXBOND_WERROR=$(WERROR) $(2) && \
              cmake --build $(1) -j$(JOBS)
# $(call run_ctest,DIR): run the whole suite of one tree.
run_ctest = ctest --test-dir $(1) --output-on-failure -j$(CTEST_JOBS)

.PHONY: deps deps-test deps-dev deps-mpi install install-check build test run asan clang mpi release format format-check clean

test asan clang mpi release valgrind: WERROR := ON

# $(call install_missing,PACKAGES): apt-get install those not yet installed.
define install_missing
	@missing=; \
	for pkg in $(1); do \
	  case "$$(dpkg-query -W -f='$${Status}' "$$pkg" 2>/dev/null)" in \
	    "install ok installed") ;; \
	    *) missing="$$missing $$pkg" ;; \
	  esac; \
	done; \
	if [ -z "$$missing" ]; then \
	  echo "$@: all packages already installed"; \
	else \
	  echo "$@: installing$$missing"; \
	  $(APT) update && $(APT) install -y --no-install-recommends $$missing; \
	fi
endef

deps:
	$(call install_missing,$(DEB_PACKAGES))

deps-test: deps
	$(call install_missing,$(TEST_DEB_PACKAGES))

deps-dev: deps-test
	$(call install_missing,$(DEV_DEB_PACKAGES))

deps-mpi:
	$(call install_missing,$(MPI_DEB_PACKAGES))

build:
	$(call cmake_build,$(BUILD_DIR),)

test: deps-test build
	$(call run_ctest,$(BUILD_DIR))

# Installs into PREFIX (or stages under DESTDIR): docs/install.md. The two reach the shell
# only as environment variables, never pasted into a command, and $(value ...) keeps make from
# expanding a "$" in them; install-check refuses an absolute path with anything but the
# characters below (a backquote, "$", quote, space or line break is a mistake, and flexbond.pc
# could not hold it), before anything is built (the build runs after the check, not beside it
# under -j). Make itself never exports them (unexport: an exported variable given on the command
# line is expanded, "$(shell ...)" and all). sudo only for a prefix the user cannot write
# (/usr/local for a user); ldconfig only for a system prefix, whose libraries the loader caches.
PREFIX ?= /usr/local
unexport PREFIX DESTDIR
install install-check: export FLEXBOND_PREFIX = $(value PREFIX)
install install-check: export FLEXBOND_DESTDIR = $(value DESTDIR)
install-check:
	@case "$$FLEXBOND_PREFIX" in /*) ;; *) \
	  echo "make install: PREFIX must be an absolute path (docs/install.md)" >&2; exit 2 ;; esac; \
	for v in "$$FLEXBOND_PREFIX" "$$FLEXBOND_DESTDIR"; do case "$$v" in *[!A-Za-z0-9/._+,:@=~-]*) \
	  echo "make install: PREFIX and DESTDIR may hold only letters, digits and / . _ + , : @ = ~ -" \
	       "(docs/install.md)" >&2; exit 2 ;; esac; done
install: install-check
	@$(MAKE) --no-print-directory build
	@set -e; sudo=; if [ -z "$$FLEXBOND_DESTDIR" ] && [ ! -w "$$FLEXBOND_PREFIX" ]; then sudo='$(SUDO)'; fi; \
	set -x; $$sudo env DESTDIR="$$FLEXBOND_DESTDIR" cmake --install $(BUILD_DIR) --prefix "$$FLEXBOND_PREFIX"; \
	{ set +x; } 2>/dev/null; \
	if [ -z "$$FLEXBOND_DESTDIR" ]; then case "$$FLEXBOND_PREFIX" in /usr|/usr/local) set -x; $$sudo ldconfig ;; esac; fi

run: deps build
	./$(BUILD_DIR)/flexbond run examples/apc6x6.yaml -o $(OUT_DIR)/ --animate
	./$(BUILD_DIR)/flexbond modes examples/apc6x6.yaml > $(OUT_DIR)/modes.txt
	./$(BUILD_DIR)/flexbond modes examples/apc6x6.yaml --system flexible -o $(OUT_DIR)/modes/ \
	  > $(OUT_DIR)/modes_system2.txt
	./$(BUILD_DIR)/flexbond freq examples/apc6x6.yaml -o $(OUT_DIR)/freq/ > $(OUT_DIR)/freq.txt
	./$(BUILD_DIR)/flexbond sim examples/quarter_car.yaml -o $(OUT_DIR)/quarter_car/ --plot
	./$(BUILD_DIR)/flexbond diagram examples/quarter_car.yaml -o $(OUT_DIR)/quarter_car/diagram.dot

asan: deps-test
	$(call cmake_build,$(ASAN_DIR),-DFLEXBOND_SANITIZE=ON)
	$(call run_ctest,$(ASAN_DIR))

clang: deps-dev
	$(call cmake_build,$(CLANG_DIR),-DCMAKE_C_COMPILER=clang)
	$(call run_ctest,$(CLANG_DIR))

# -O3 raises warnings (-Wmaybe-uninitialized) that the default build's -O2 does not.
release: BUILD_TYPE := Release
release: deps-dev
	$(call cmake_build,$(RELEASE_DIR),-DCMAKE_C_COMPILER=gcc)
	$(call cmake_build,$(RELEASE_DIR)-clang,-DCMAKE_C_COMPILER=clang)
	$(call run_ctest,$(RELEASE_DIR))

# The MPI build of flexbond sweep (docs/cluster.md) and its whole suite, cli_sweep_mpi included.
mpi: deps-test deps-mpi
	$(call cmake_build,$(MPI_DIR),-DFLEXBOND_MPI=ON)
	$(call run_ctest,$(MPI_DIR))

format:
	$(if $(FORMAT_SOURCES),clang-format -i $(FORMAT_SOURCES),@echo "format: no sources")

format-check:
	$(if $(FORMAT_SOURCES),clang-format --dry-run --Werror $(FORMAT_SOURCES),@echo "format-check: no sources")

clean:
	rm -rf $(BUILD_DIR) $(ASAN_DIR) $(CLANG_DIR) $(MPI_DIR) $(RELEASE_DIR) $(RELEASE_DIR)-clang $(VALGRIND_DIR) $(TIDY_DIR) $(OUT_DIR)

# ---- Fuzzing (docs/fuzzing.md): each tests/fuzz/fuzz_NAME.c runs for FUZZ_SECONDS on a copy
# of its seed corpus and crash inputs in $(FUZZ_DIR)/corpus/NAME (the repository is never
# written), from tests/fuzz (the targets' base directory for relative file references).
# Crash, leak and timeout inputs land in $(FUZZ_DIR)/crashes/, cleared at the start.
FUZZ_DIR ?= build-fuzz
FUZZ_SECONDS ?= 60
FUZZ_NAMES := model scenario inp msh
FUZZ_ABS := $(abspath $(FUZZ_DIR))

.PHONY: fuzz
fuzz: deps-dev
	CC=clang cmake -S . -B $(FUZZ_DIR) -DCMAKE_BUILD_TYPE=$(BUILD_TYPE) \
	  -DCMAKE_C_COMPILER=clang -DFLEXBOND_FUZZ=ON
	cmake --build $(FUZZ_DIR) -j$(JOBS) --target $(addprefix fuzz_,$(FUZZ_NAMES))
	@rm -rf $(FUZZ_ABS)/crashes && mkdir -p $(FUZZ_ABS)/crashes; \
	failed=; \
	for name in $(FUZZ_NAMES); do \
	  dict=yaml.dict; opts="-timeout=5"; \
	  [ $$name = inp ] && dict=inp.dict && opts="-timeout=5 -max_len=1048576 -malloc_limit_mb=64"; \
	  [ $$name = msh ] && dict=msh.dict && opts="-timeout=2 -max_len=1048576"; \
	  corpus=$(FUZZ_ABS)/corpus/$$name; mkdir -p $$corpus; \
	  find tests/fuzz/corpus/$$name tests/fuzz/regressions/$$name -type f ! -name '.*' \
	    -exec cp {} $$corpus/ \; ; \
	  echo "fuzz: fuzz_$$name for $(FUZZ_SECONDS) s (log: $(FUZZ_DIR)/fuzz_$$name.log)"; \
	  if ! (cd tests/fuzz && $(FUZZ_ABS)/fuzz_$$name $$corpus -max_total_time=$(FUZZ_SECONDS) \
	        $$opts -rss_limit_mb=2048 -dict=$$dict \
	        -artifact_prefix=$(FUZZ_ABS)/crashes/$$name-) > $(FUZZ_ABS)/fuzz_$$name.log 2>&1; then \
	    failed="$$failed $$name"; tail -n 40 $(FUZZ_ABS)/fuzz_$$name.log; \
	  else \
	    grep -E '^(#[0-9]+.*DONE|Done )' $(FUZZ_ABS)/fuzz_$$name.log; \
	  fi; \
	done; \
	artifacts=$$(find $(FUZZ_ABS)/crashes -type f | sort); \
	if [ -n "$$failed$$artifacts" ]; then \
	  echo "fuzz: FAILED:$${failed:- (artifacts only)}"; \
	  for a in $$artifacts; do echo "  $$a"; done; \
	  echo "fuzz: fix each finding, then copy its input into tests/fuzz/regressions/NAME/"; \
	  echo "      (NAME from the file name, e.g. model-crash-... -> regressions/model/, under a"; \
	  echo "      descriptive name) so that CTest's fuzz_regressions_NAME replays it."; \
	  exit 1; \
	fi; \
	echo "fuzz: no crash, leak or timeout in $(FUZZ_SECONDS) s per target"

# ---- Quality checks (docs/quality.md): valgrind memcheck, clang-tidy, cppcheck.
VALGRIND_DIR ?= build-valgrind
TIDY_DIR ?= build-tidy
# Left out of `make valgrind`: System 2's simulations, 57 s and 40 s natively, most of an hour
# each under memcheck, and the eight 40 s random-road runs of test_ride_psd, 19 s natively
# (docs/quality.md); test_freq runs the same frequency-response code under memcheck. And
# test_hull_basis's three System 2 runs (one of every mode, one nodal; 6 s natively), whose
# solver and bases test_reduce and test_system2_modes cover.
VALGRIND_EXCLUDE ?= ^test_system2_sim$$|^test_model_write_flexible$$|^test_ride_psd$$|^test_hull_basis$$
# Only definite and indirect leaks are errors (and shown); any error fails the test.
VALGRIND_OPTIONS := --leak-check=full --show-leak-kinds=definite,indirect \
                    --errors-for-leak-kinds=definite,indirect --error-exitcode=1 --num-callers=30
CPPCHECK_OPTIONS := --enable=warning,style,performance,portability --std=c11 --error-exitcode=1 \
                    --inline-suppr --suppress=missingIncludeSystem --quiet \
                    -D_POSIX_C_SOURCE=200809L -I include -I src

.PHONY: valgrind tidy cppcheck
# One OpenBLAS thread with its SSE3 kernels: memcheck serialises threads, and it runs the
# default AVX2 kernels about ten times slower; neither choice changes our code's memory use.
valgrind: deps-dev
	$(call cmake_build,$(VALGRIND_DIR),-DFLEXBOND_SANITIZE=OFF)
	OPENBLAS_NUM_THREADS=1 OPENBLAS_CORETYPE=Prescott \
	  ctest --test-dir $(VALGRIND_DIR) -T memcheck -R '^test_' -E '$(VALGRIND_EXCLUDE)' \
	  --output-on-failure -j$(CTEST_JOBS) \
	  --overwrite MemoryCheckCommand=$$(command -v valgrind) \
	  --overwrite 'MemoryCheckCommandOptions=$(VALGRIND_OPTIONS)' \
	  --overwrite MemoryCheckSuppressionFile=$(CURDIR)/tests/valgrind.supp

# A Debug clang tree for its compile_commands.json only (nothing is built): Debug keeps the
# asserts, which tell the analyzer invariants it cannot see across translation units. The
# MPI build, so that src/cli/sweep_mpi.c is analysed too.
tidy: deps-dev deps-mpi
	cmake -S . -B $(TIDY_DIR) -DCMAKE_BUILD_TYPE=Debug -DCMAKE_C_COMPILER=clang \
	  -DFLEXBOND_MPI=ON -DCMAKE_EXPORT_COMPILE_COMMANDS=ON > /dev/null
	@echo "tidy: clang-tidy $$(clang-tidy --version | sed -n 's/.*version //p') over src/"
	@find src -name '*.c' | sort | xargs -P$(JOBS) -I{} bash -c \
	  'out=$$(clang-tidy -p $(TIDY_DIR) --quiet {} 2>&1) || \
	   { grep -v "warnings\? generated\.$$" <<< "$$out"; exit 1; }' \
	  || { echo "tidy: FAILED: fix each finding (docs/quality.md)"; exit 1; }
	@echo "tidy: no findings"

cppcheck: deps-dev
	cppcheck $(CPPCHECK_OPTIONS) -j$(JOBS) src
	@echo "cppcheck: no findings"
