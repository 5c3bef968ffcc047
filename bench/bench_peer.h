// The peer benchmark (bench_peer.cpp), run by quadtri_bench: Embree's native triangles against
// quadric patches in its user geometry, at equal primitive counts.
#pragma once

void registerPeerBenchmarks();
void printPeerSummary();
