#pragma once
// Private: hot loops compiled twice, for AVX2 and for the baseline x86-64 (SSE2), the one the CPU
// supports chosen when the library loads (GCC's function multi-versioning). The loops are written
// lane by lane (no reordered sums, and "avx2" does not enable FMA contraction), so both versions
// compute the same values: wider vectors, same bytes. Elsewhere (other compilers, CPUs or C
// libraries: the choice needs glibc's ifunc) and in the sanitizer builds a no-op; CMake's
// -DOCTOREACH_VECTOR_CLONES=OFF turns it off too (the baseline loops only, e.g. to compare the bytes).
#if defined(__x86_64__) && defined(__GNUC__) && !defined(__clang__) && defined(__linux__) && defined(__GLIBC__) && \
    !defined(__SANITIZE_ADDRESS__) && !defined(__SANITIZE_THREAD__) && !defined(OCTOREACH_NO_VECTOR_CLONES)
#define OCTOREACH_VECTOR_CLONES __attribute__((target_clones("avx2", "default")))
#else
#define OCTOREACH_VECTOR_CLONES
#endif
