// Memory-read probe for docs/benchmarks.md: gcc -O2 -mavx2 -o target/bandwidth scripts/bandwidth.c
// then `target/bandwidth 2.2` (MiB; fits L3, not L2) and `target/bandwidth 64` (DRAM).
// Streams a buffer of N bytes repeatedly (read only, AVX2 adds) and prints GB/s.
#include <immintrin.h>
#include <stdio.h>
#include <stdlib.h>
#include <time.h>
static double now(void){struct timespec t;clock_gettime(CLOCK_MONOTONIC,&t);return t.tv_sec+t.tv_nsec*1e-9;}
int main(int argc,char**argv){
  size_t bytes=(size_t)(atof(argv[1])*1024*1024); size_t n=bytes/8;
  double*a=aligned_alloc(64,n*8); for(size_t i=0;i<n;i++)a[i]=i*1e-9;
  __m256d s0=_mm256_setzero_pd(),s1=s0,s2=s0,s3=s0;
  size_t reps=(size_t)(4e9/bytes); double t0=now();
  for(size_t r=0;r<reps;r++) for(size_t i=0;i<n;i+=16){
    s0=_mm256_add_pd(s0,_mm256_load_pd(a+i)); s1=_mm256_add_pd(s1,_mm256_load_pd(a+i+4));
    s2=_mm256_add_pd(s2,_mm256_load_pd(a+i+8)); s3=_mm256_add_pd(s3,_mm256_load_pd(a+i+12));}
  double t=now()-t0; double out[4]; _mm256_storeu_pd(out,_mm256_add_pd(_mm256_add_pd(s0,s1),_mm256_add_pd(s2,s3)));
  printf("%.2f MiB: %.1f GB/s (checksum %g)\n",bytes/1048576.0,reps*(double)bytes/t/1e9,out[0]);
}
