// tools/omp_regions.c — counts a program's OpenMP parallel regions, each by the function it runs
// (issue #37: a region's fork and join costs microseconds, so a small system's step should open
// few). Preloaded, it wraps libgomp's GOMP_parallel and prints at exit one line per region's
// outlined function: REGION <module> <offset> <calls>, and the total.
//   gcc -O2 -shared -fPIC tools/omp_regions.c -o out/omp_regions.so -ldl
//   LD_PRELOAD=out/omp_regions.so build/examples/ballast/ballast ... 2> regions.txt
//   grep REGION regions.txt | while read -r _ m off n; do echo "$n $(addr2line -f -C -e "$m" "$off" | head -1)"; done
// (docs/record/benchmarks-history.md §11.34)
#define _GNU_SOURCE
#include <dlfcn.h>
#include <stdio.h>

enum { kMax = 512 };
static void* fns[kMax];
static long calls[kMax];
static int nfns;
static long total;

typedef void (*Parallel)(void (*)(void*), void*, unsigned, unsigned);

// (from the drivers' threads: the regions open from the main thread, so a plain count suffices)
void GOMP_parallel(void (*fn)(void*), void* data, unsigned threads, unsigned flags) {
  static Parallel real;
  if (!real) real = (Parallel)dlsym(RTLD_NEXT, "GOMP_parallel");
  int i = 0;
  while (i < nfns && fns[i] != (void*)fn) ++i;
  if (i == nfns && nfns < kMax) fns[nfns++] = (void*)fn;
  if (i < kMax) ++calls[i];
  ++total;
  real(fn, data, threads, flags);
}

__attribute__((destructor)) static void report(void) {
  for (int i = 0; i < nfns; ++i) {
    Dl_info info = {0};
    dladdr(fns[i], &info);
    fprintf(stderr, "REGION %s 0x%lx %ld\n", info.dli_fname ? info.dli_fname : "?",
            (unsigned long)((char*)fns[i] - (char*)info.dli_fbase), calls[i]);
  }
  fprintf(stderr, "REGIONS %ld\n", total);
}
