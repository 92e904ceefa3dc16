# Two commands do everything on a fresh Debian machine:
#   make demo   set up, build, and run the demo
#   make test   set up, build, and run every test
BUILD_DIR ?= build
JOBS ?= $(shell nproc)

.PHONY: all setup configure build test test-asan demo bench clean

all: build

setup:
	@bash scripts/setup

configure: setup
	@cmake -S . -B $(BUILD_DIR) -DCMAKE_BUILD_TYPE=Release > /dev/null

build: configure
	@cmake --build $(BUILD_DIR) -j $(JOBS)

test: build
	@cd $(BUILD_DIR) && ctest --output-on-failure -j $(JOBS)

# Every test under AddressSanitizer and UndefinedBehaviorSanitizer, in its own build folder.
test-asan: setup
	@cmake -S . -B build-asan -DCMAKE_BUILD_TYPE=RelWithDebInfo -DMYO_SANITIZE=ON -DMYO_BUILD_BENCH=OFF > /dev/null
	@cmake --build build-asan -j $(JOBS)
	@cd build-asan && ASAN_OPTIONS=detect_leaks=1 UBSAN_OPTIONS=print_stacktrace=1 ctest --output-on-failure -j $(JOBS)

demo: build
	@$(BUILD_DIR)/bin/myoshell demo --out out/demo

bench: build
	@$(BUILD_DIR)/bin/myoshell bench

clean:
	rm -rf $(BUILD_DIR)
