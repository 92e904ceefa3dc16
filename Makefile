# Two commands do everything on a fresh Debian machine:
#   make demo   set up, build, and run the demo
#   make test   set up, build, and run every test
BUILD_DIR ?= build
JOBS ?= $(shell nproc)

.PHONY: all setup configure build test demo bench clean

all: build

setup:
	@bash scripts/setup

configure: setup
	@cmake -S . -B $(BUILD_DIR) -DCMAKE_BUILD_TYPE=Release > /dev/null

build: configure
	@cmake --build $(BUILD_DIR) -j $(JOBS)

test: build
	@cd $(BUILD_DIR) && ctest --output-on-failure -j $(JOBS)

demo: build
	@$(BUILD_DIR)/bin/myoshell demo --out out/demo

bench: build
	@$(BUILD_DIR)/bin/myoshell bench

clean:
	rm -rf $(BUILD_DIR)
