// TACTA_HOT_PATH compiles a hot loop twice, for x86-64-v3 (AVX2 and FMA) and for baseline
// x86-64, and the dynamic loader picks one at start-up (GCC's function multiversioning through
// an ifunc). The binary still runs on any x86-64 CPU; where AVX2 exists the per-element and
// sparse loops get 4-wide vectors and fused multiply-adds. Off under the sanitizers (their
// run-time starts after ifunc resolvers) and on other compilers and architectures.
#pragma once

#if defined(__x86_64__) && defined(__GNUC__) && !defined(__clang__) && \
    !defined(__SANITIZE_ADDRESS__) && !defined(__SANITIZE_THREAD__)
#define TACTA_HOT_PATH __attribute__((target_clones("arch=x86-64-v3", "default")))
#else
#define TACTA_HOT_PATH
#endif
