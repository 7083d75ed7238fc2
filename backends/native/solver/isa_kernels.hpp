#pragma once
// How the solver's wide kernels are built for more than one instruction set: each kernel's body
// is an ANYPHYS_KERNEL function, inlined into one entry point compiled for the baseline and, where
// the compiler can target it, one marked ANYPHYS_AVX2; contactKernelsUseAvx2() picks at run time.
// Both give the same bits (the kernels use no fused multiply-add).

#if defined(__GNUC__) && (defined(__x86_64__) || defined(__i386__))
#define ANYPHYS_HAS_AVX2_KERNELS 1
#define ANYPHYS_AVX2 __attribute__((target("avx2")))
#endif

// Inlined into each instruction set's entry point, so each gets its own instructions.
#define ANYPHYS_KERNEL [[gnu::always_inline]] inline
