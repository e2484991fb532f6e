# Thin wrapper over cmake/quickstart.sh and CMake.
.PHONY: demo test build eval bench format fuzz
demo:
	./cmake/quickstart.sh demo
test:
	./cmake/quickstart.sh test
build:
	cmake -S . -B build -DCMAKE_BUILD_TYPE=Release && cmake --build build -j2
eval: build
	./build/examples/gridloc eval
bench: build
	./build/bench/gridloc_bench
format:
	clang-format -i $$(git ls-files '*.cpp' '*.hpp')
# The libFuzzer harnesses (clang; tests/fuzz/README.md), each run FUZZ_SECONDS on its corpus.
FUZZ_SECONDS ?= 60
fuzz:
	cmake -S . -B build-fuzz -DCMAKE_BUILD_TYPE=RelWithDebInfo -DCMAKE_CXX_COMPILER=clang++ \
	  -DGRIDLOC_BUILD_FUZZ=ON -DBUILD_TESTING=OFF -DGRIDLOC_BUILD_BENCH=OFF \
	  -DGRIDLOC_BUILD_EXAMPLES=OFF
	cmake --build build-fuzz -j2 --target gridloc_fuzz
	./tests/fuzz/run_fuzz.sh build-fuzz $(FUZZ_SECONDS)
