#pragma once
// Private: hot loops compiled twice, for AVX2 and for the baseline x86-64 (SSE2), the one the CPU
// supports chosen when the library loads (GCC's function multi-versioning). The loops are written
// lane by lane (no reordered sums, and "avx2" does not enable FMA contraction), so both versions
// compute the same values: wider vectors, same bytes. Elsewhere (other compilers or CPUs) a no-op.
#if defined(__x86_64__) && defined(__GNUC__) && !defined(__clang__) && !defined(__SANITIZE_ADDRESS__) && \
    !defined(__SANITIZE_THREAD__)
#define OCTOREACH_VECTOR_CLONES __attribute__((target_clones("avx2", "default")))
#else
#define OCTOREACH_VECTOR_CLONES
#endif
