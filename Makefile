# Convenience wrapper around CMake/CTest for flexbond.
#
#   make deps          install the Debian packages the build needs (only those missing)
#   make build         configure + build into $(BUILD_DIR) (RelWithDebInfo)
#   make test          deps + build + run the CTest suite
#   make run           deps + build + the default study (examples/apc6x6.yaml, Systems 1 and 2,
#                      report.md) into out/, the modal analyses,
#                      and the quarter-car example into out/quarter_car/
#   make asan          build into $(ASAN_DIR) with ASan+UBSan and run the suite
#   make clang         build into $(CLANG_DIR) with clang and -Werror and run the suite
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
OUT_DIR ?= out
BUILD_TYPE ?= RelWithDebInfo
JOBS ?= $(shell nproc 2>/dev/null || echo 2)
CTEST_JOBS ?= 2

# clang is the second compiler; clang-format serves format/format-check; python3
# checks the JSON the CLI writes (tests/cli_run.sh).
DEB_PACKAGES := build-essential cmake pkg-config libsundials-dev libsuitesparse-dev \
                liblapacke-dev libopenblas-dev libarpack2-dev libfyaml-dev gnuplot-nox graphviz clang \
                clang-format python3
SUDO := $(if $(filter 0,$(shell id -u)),,sudo)
APT := $(SUDO) env DEBIAN_FRONTEND=noninteractive apt-get

FORMAT_SOURCES = $(sort $(shell find include src tests -type f \( -name '*.c' -o -name '*.h' \) 2>/dev/null))

# $(call cmake_build,DIR,EXTRA CMAKE ARGS): configure and build one tree.
cmake_build = cmake -S . -B $(1) -DCMAKE_BUILD_TYPE=$(BUILD_TYPE) $(2) && \
              cmake --build $(1) -j$(JOBS)
# $(call run_ctest,DIR): run the whole suite of one tree.
run_ctest = ctest --test-dir $(1) --output-on-failure -j$(CTEST_JOBS)

.PHONY: deps build test run asan clang format format-check clean

deps:
	@missing=; \
	for pkg in $(DEB_PACKAGES); do \
	  case "$$(dpkg-query -W -f='$${Status}' "$$pkg" 2>/dev/null)" in \
	    "install ok installed") ;; \
	    *) missing="$$missing $$pkg" ;; \
	  esac; \
	done; \
	if [ -z "$$missing" ]; then \
	  echo "deps: all packages already installed"; \
	else \
	  echo "deps: installing$$missing"; \
	  $(APT) update && $(APT) install -y --no-install-recommends $$missing; \
	fi

build:
	$(call cmake_build,$(BUILD_DIR),)

test: deps build
	$(call run_ctest,$(BUILD_DIR))

run: deps build
	./$(BUILD_DIR)/flexbond run examples/apc6x6.yaml -o $(OUT_DIR)/
	./$(BUILD_DIR)/flexbond modes examples/apc6x6.yaml > $(OUT_DIR)/modes.txt
	./$(BUILD_DIR)/flexbond modes examples/apc6x6.yaml --system flexible -o $(OUT_DIR)/modes/ \
	  > $(OUT_DIR)/modes_system2.txt
	./$(BUILD_DIR)/flexbond sim examples/quarter_car.yaml -o $(OUT_DIR)/quarter_car/ --plot
	./$(BUILD_DIR)/flexbond diagram examples/quarter_car.yaml -o $(OUT_DIR)/quarter_car/diagram.dot

asan:
	$(call cmake_build,$(ASAN_DIR),-DFLEXBOND_SANITIZE=ON)
	$(call run_ctest,$(ASAN_DIR))

clang:
	$(call cmake_build,$(CLANG_DIR),-DCMAKE_C_COMPILER=clang -DFLEXBOND_WERROR=ON)
	$(call run_ctest,$(CLANG_DIR))

format:
	$(if $(FORMAT_SOURCES),clang-format -i $(FORMAT_SOURCES),@echo "format: no sources")

format-check:
	$(if $(FORMAT_SOURCES),clang-format --dry-run --Werror $(FORMAT_SOURCES),@echo "format-check: no sources")

clean:
	rm -rf $(BUILD_DIR) $(ASAN_DIR) $(CLANG_DIR) $(OUT_DIR)
