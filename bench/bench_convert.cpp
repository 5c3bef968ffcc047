#include <benchmark/benchmark.h>

#include "mesh/shapes.h"
#include "surface/model.h"

BENCHMARK_MAIN();
