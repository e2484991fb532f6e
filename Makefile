# Thin wrapper over cmake/quickstart.sh and CMake.
.PHONY: demo test build eval bench format
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
