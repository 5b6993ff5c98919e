// Core-clock probe for docs/benchmarks.md (virtual machines here expose no cycle
// counter to perf): gcc -O2 -o target/clock scripts/clock.c && target/clock
// Times a chain of dependent integer adds (one per cycle on every x86 core) and
// prints the rate, which is the clock the core runs one thread at.
#include <stdio.h>
#include <time.h>
static double now(void){struct timespec t;clock_gettime(CLOCK_MONOTONIC,&t);return t.tv_sec+t.tv_nsec*1e-9;}
int main(void){
  long x=0, n=2000000000; double t0=now();
  for(long i=0;i<n;i+=8){
    __asm__ volatile("add $1,%0\n\tadd $1,%0\n\tadd $1,%0\n\tadd $1,%0\n\t"
                     "add $1,%0\n\tadd $1,%0\n\tadd $1,%0\n\tadd $1,%0":"+r"(x));
  }
  double t=now()-t0; printf("%.2f GHz (%ld adds)\n", n/t/1e9, x);
}
