/* bench_verilog.c - `make bench` entry for bench/verilog/run.sh: shadesim
 * against Verilator and Icarus on the exported horner3 and interp3 RTL.
 * The script says "skipped" when verilator is not installed. */
#include <stdio.h>
#include <stdlib.h>

int main(void)
{
    int rc = system("sh bench/verilog/run.sh");
    if (rc != 0) {
        fprintf(stderr, "bench: bench/verilog/run.sh failed\n");
        return 1;
    }
    return 0;
}
